#include "bench/discrimination_scenes.h"

#include <cstdio>

#include "bench/paper_scenes.h"

namespace criticality::bench {
namespace {

constexpr double kCarLength = 5.0;
constexpr double kCarWidth = 1.8;
constexpr double kPi = 3.14159265358979323846;

LaneDivider Straight(double y) {
  LaneDivider d;
  d.points = {Point2{0.0, y}, Point2{40.0, y}, Point2{80.0, y}};
  return d;
}

Lane LaneBetween(double y_right, double y_left, bool counter = false) {
  Lane lane;
  lane.right = Straight(y_right);
  lane.left = Straight(y_left);
  lane.counter_traffic = counter;
  return lane;
}

// A two-lane road (rural or urban): the own lane and, on the left, a lane of oncoming traffic.
LaneSet TwoWayRoad() {
  LaneSet lanes;
  lanes.own = LaneBetween(-0.5 * kLaneWidth, 0.5 * kLaneWidth);
  lanes.left = LaneBetween(0.5 * kLaneWidth, 1.5 * kLaneWidth, /*counter=*/true);
  return lanes;
}

Scene EgoOn(const LaneSet& lanes, double speed) {
  Scene s;
  s.ego.id = "ego";
  s.ego.state.speed_mps = speed;
  s.ego.length_m = kCarLength;
  s.ego.width_m = kCarWidth;
  s.ego.lanes = lanes;
  return s;
}

Vehicle Car(const std::string& id, double x, double y, double yaw, double speed,
            double accel = 0.0) {
  Vehicle v;
  v.id = id;
  v.state.x_m = x;
  v.state.y_m = y;
  v.state.yaw_rad = yaw;
  v.state.speed_mps = speed;
  v.state.accel_mps2 = accel;
  v.length_m = kCarLength;
  v.width_m = kCarWidth;
  return v;
}

// Centre x of a car whose rear bumper is `gap` metres ahead of the ego's front bumper (or,
// negative, whose front bumper is -gap behind the ego's rear).
double Ahead(double gap) { return gap + kCarLength; }
double Behind(double gap) { return -(gap + kCarLength); }

Pedestrian Walker(const std::string& id, double x, double y, double yaw, double speed) {
  Pedestrian p;
  p.id = id;
  p.state.x_m = x;
  p.state.y_m = y;
  p.state.yaw_rad = yaw;
  p.state.speed_mps = speed;
  return p;
}

std::string Format(const char* fmt, double a) {
  char buf[96];
  std::snprintf(buf, sizeof buf, fmt, a);
  return buf;
}

}  // namespace

std::vector<DiscriminationScene> DiscriminationScenes() {
  std::vector<DiscriminationScene> out;
  const double v = 20.0;

  // A stopped car in the ego's lane of a three-lane road, the ego at 20 m/s (the issue's
  // "stopped car 30 m / 25 m / 15 m ahead" are TTC 1.5, 1.25, 0.75). With a 2 s horizon no
  // collision is possible from TTC 3 on: the ego has time to brake normally (3.3 m/s^2 at TTC 3).
  for (double ttc : {4.0, 3.0, 2.0, 1.5, 1.25, 1.0, 0.75, 0.5}) {
    DiscriminationScene d;
    d.name = Format("stopped-car-ttc-%.2f", ttc);
    d.critical = ttc <= 2.0;
    d.ttc_s = d.critical ? ttc : -1.0;
    d.family = "stopped car";
    d.what = Format("a stopped car %.0f m ahead in the ego lane, ego at 20 m/s", ttc * v);
    d.scene = EgoOn(StraightThreeLanes(), v);
    d.scene.vehicles.push_back(Car("stopped", Ahead(ttc * v), 0.0, 0.0, 0.0));
    out.push_back(d);
  }

  // Following at 0.8-2.5 s headway on a two-way road, with a follower at the same headway.
  for (double h : {0.8, 1.2, 1.8, 2.5}) {
    DiscriminationScene d;
    d.name = Format("following-%.1fs", h);
    d.what = Format("leader and follower at %.1f s headway, 20 m/s, two-way road", h);
    d.scene = EgoOn(TwoWayRoad(), v);
    d.scene.vehicles.push_back(Car("leader", Ahead(h * v), 0.0, 0.0, v));
    d.scene.vehicles.push_back(Car("follower", Behind(h * v), 0.0, 0.0, v));
    out.push_back(d);
  }

  {  // The first scene.
    DiscriminationScene d;
    d.name = "leader-18m-oncoming-follower";
    d.what = "leader 18 m ahead, follower 18 m behind, two oncoming cars, 20 m/s";
    d.scene = EgoOn(TwoWayRoad(), v);
    d.scene.vehicles.push_back(Car("leader", Ahead(18.0), 0.0, 0.0, v));
    d.scene.vehicles.push_back(Car("follower", Behind(18.0), 0.0, 0.0, v));
    d.scene.vehicles.push_back(Car("oncoming-1", Ahead(30.0), kLaneWidth, kPi, v));
    d.scene.vehicles.push_back(Car("oncoming-2", Ahead(90.0), kLaneWidth, kPi, v));
    out.push_back(d);
  }
  {  // The second scene.
    DiscriminationScene d;
    d.name = "motorway-leader-18m-four-neighbours";
    d.what = "three lanes at 20 m/s: leader 18 m ahead, two cars alongside, two 15 m off";
    d.scene = EgoOn(StraightThreeLanes(), v);
    d.scene.vehicles.push_back(Car("leader", Ahead(18.0), 0.0, 0.0, v));
    d.scene.vehicles.push_back(Car("left-alongside", 0.0, kLaneWidth, 0.0, v));
    d.scene.vehicles.push_back(Car("left-ahead", Ahead(15.0), kLaneWidth, 0.0, v));
    d.scene.vehicles.push_back(Car("right-alongside", -2.0, -kLaneWidth, 0.0, v));
    d.scene.vehicles.push_back(Car("right-behind", Behind(15.0), -kLaneWidth, 0.0, v));
    out.push_back(d);
  }
  {
    DiscriminationScene d;
    d.name = "rural-oncoming-traffic";
    d.what =
        "two-lane rural road at 22 m/s: three oncoming cars (passing within 0.5-2.6 s), "
        "leader at 2 s";
    d.scene = EgoOn(TwoWayRoad(), 22.0);
    for (double gap : {20.0, 60.0, 110.0}) {
      d.scene.vehicles.push_back(
          Car(Format("oncoming-%.0f", gap), Ahead(gap), kLaneWidth, kPi, 22.0));
    }
    d.scene.vehicles.push_back(Car("leader", Ahead(44.0), 0.0, 0.0, 22.0));
    out.push_back(d);
  }
  {
    DiscriminationScene d;
    d.name = "motorway-neighbours-alongside";
    d.what =
        "three lanes at 30 m/s: cars alongside left and right, two more in the neighbour "
        "lanes, leader at 2 s, follower at 1.5 s";
    d.scene = EgoOn(StraightThreeLanes(), 30.0);
    d.scene.vehicles.push_back(Car("left-alongside", 1.0, kLaneWidth, 0.0, 30.0));
    d.scene.vehicles.push_back(Car("right-alongside", -1.5, -kLaneWidth, 0.0, 30.0));
    d.scene.vehicles.push_back(Car("left-ahead", Ahead(25.0), kLaneWidth, 0.0, 30.0));
    d.scene.vehicles.push_back(Car("right-behind", Behind(20.0), -kLaneWidth, 0.0, 30.0));
    d.scene.vehicles.push_back(Car("leader", Ahead(60.0), 0.0, 0.0, 30.0));
    d.scene.vehicles.push_back(Car("follower", Behind(45.0), 0.0, 0.0, 30.0));
    out.push_back(d);
  }
  {
    DiscriminationScene d;
    d.name = "pedestrians-on-sidewalks";
    d.what =
        "urban two-way road at 14 m/s: three pedestrians walking along the sidewalks, "
        "1.5 m from the road";
    d.scene = EgoOn(TwoWayRoad(), 14.0);
    const double right_walk = -0.5 * kLaneWidth - 1.5, left_walk = 1.5 * kLaneWidth + 1.5;
    d.scene.pedestrians.push_back(Walker("walker-same-way", 20.0, right_walk, 0.0, 1.4));
    d.scene.pedestrians.push_back(Walker("walker-towards", 35.0, right_walk, kPi, 1.4));
    d.scene.pedestrians.push_back(Walker("walker-left", 25.0, left_walk, kPi, 1.4));
    out.push_back(d);
  }
  // A pedestrian crossing at 1.4 m/s from the right, placed so that it reaches the ego's centre
  // line when the ego (14 m/s) reaches it, after ttc seconds: from the kerb (1.8 s, 1.5 s: it
  // starts 0.8 or 0.35 m outside the ego lane) or already on the road (1.2 s, 0.9 s).
  for (double ttc : {1.8, 1.5, 1.2, 0.9}) {
    DiscriminationScene d;
    d.name = Format("pedestrian-crosses-ttc-%.1f", ttc);
    d.critical = true;
    d.ttc_s = ttc;
    d.family = "pedestrian crosses";
    d.what =
        Format("a pedestrian crosses from the right, ego at 14 m/s reaches it after %.1f s", ttc);
    d.scene = EgoOn(TwoWayRoad(), 14.0);
    const double x = 0.5 * kCarLength + 14.0 * ttc + 0.25;
    d.scene.pedestrians.push_back(Walker("crossing", x, -1.4 * ttc, kPi / 2, 1.4));
    out.push_back(d);
  }

  // Junctions: a crossing road (two lanes, right-hand traffic) along y. Crossing cars drive on
  // it and carry its lanes, seen from their own frame: their lane and the oncoming one left.
  auto crossing_car = [&](const std::string& id, double x, double y, bool northbound,
                          double speed) {
    Vehicle c = Car(id, x, y, northbound ? kPi / 2 : -kPi / 2, speed);
    c.lanes = TwoWayRoad();
    return c;
  };
  {
    DiscriminationScene d;
    d.name = "junction-ego-waits-cross-traffic";
    d.what =
        "the ego waits (stopped) 1 m before a crossing road; cars cross in front of it at "
        "14 m/s from both sides";
    d.scene = EgoOn(TwoWayRoad(), 0.0);
    const double road = 0.5 * kCarLength + 1.0 + kLaneWidth;  // centre line of the crossing road
    d.scene.vehicles.push_back(crossing_car("from-right", road + 1.75, -25.0, true, 14.0));
    d.scene.vehicles.push_back(crossing_car("from-left", road - 1.75, 20.0, false, 14.0));
    d.scene.vehicles.push_back(crossing_car("just-passed", road + 1.75, 8.0, true, 14.0));
    out.push_back(d);
  }
  {
    DiscriminationScene d;
    d.name = "junction-side-car-waits";
    d.what =
        "ego at 14 m/s on the main road; a car waits (stopped) in a side road on the right, "
        "its front 1 m from the ego lane";
    d.scene = EgoOn(TwoWayRoad(), 14.0);
    d.scene.vehicles.push_back(
        crossing_car("waiting", 15.0, -0.5 * kLaneWidth - 1.0 - 0.5 * kCarLength, true, 0.0));
    out.push_back(d);
  }
  {
    DiscriminationScene d;
    d.name = "junction-car-crosses-ttc-1.3";
    d.critical = true;
    d.ttc_s = 1.33;
    d.what =
        "ego at 14 m/s; a car crosses from the right at 10 m/s, both reach the conflict "
        "point after 1.3 s";
    d.scene = EgoOn(TwoWayRoad(), 14.0);
    const double t = 1.33, x = 0.5 * kCarLength + 14.0 * t + 0.5 * kCarWidth;
    d.scene.vehicles.push_back(
        crossing_car("crossing", x, -0.5 * kCarWidth - 0.5 * kCarLength - 10.0 * t, true, 10.0));
    out.push_back(d);
  }
  {
    DiscriminationScene d;
    d.name = "cut-in-ttc-1.0";
    d.critical = true;
    d.ttc_s = 1.0;
    d.what =
        "a slower car (12 m/s) cuts in 8 m ahead, its centre already in the ego lane; ego "
        "at 20 m/s";
    d.scene = EgoOn(StraightThreeLanes(), v);
    d.scene.vehicles.push_back(Car("cutting-in", Ahead(8.0), 1.4, -0.05, 12.0));
    out.push_back(d);
  }
  {
    DiscriminationScene d;
    d.name = "leader-brakes-hard-8m";
    d.critical = true;
    d.ttc_s = 1.41;
    d.what = "the leader, 8 m ahead at 20 m/s, brakes at 8 m/s^2; the ego reaches it after 1.4 s";
    d.scene = EgoOn(StraightThreeLanes(), v);
    d.scene.vehicles.push_back(Car("braking", Ahead(8.0), 0.0, 0.0, v, -8.0));
    out.push_back(d);
  }
  {
    DiscriminationScene d;
    d.name = "head-on-ttc-1.2";
    d.critical = true;
    d.ttc_s = 1.2;
    d.what = "an oncoming car in the ego's lane (overtaking), both at 20 m/s, 48 m apart";
    d.scene = EgoOn(TwoWayRoad(), v);
    d.scene.vehicles.push_back(Car("wrong-lane", Ahead(48.0), 0.0, kPi, v));
    out.push_back(d);
  }
  return out;
}

}  // namespace criticality::bench
