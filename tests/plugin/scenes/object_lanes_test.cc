// The corridor ahead of a vehicle (plugin/scenes/object_lanes.h, FollowRoute): through a junction
// turn it follows both parts of the junction's internal lane with junction_shapes, and jumps
// along the chord between the lanes without. A vehicle seen changing lanes (LaneChangeTarget)
// has the lane it moves into as its own.
#include "plugin/scenes/object_lanes.h"

#include <gtest/gtest.h>

#include <cmath>

#include "../fake_sumo_world.h"
#include "criticality/geometry.h"
#include "plugin/network/traffic_side.h"

namespace criticality::plugin {
namespace {

using testing::FakeSumoWorld;

FakeSumoWorld UTurn() { return testing::SplitUTurn(); }

// The corridor's largest distance north of y = 0 (how far it reaches into the turn).
double NorthMost(const LaneCorridor& c) {
  double y = -1e9;
  for (const Point2& p : c.centre) y = std::fmax(y, p.y);
  return y;
}

LaneCorridor CorridorOf(FakeSumoWorld& w, bool junction_shapes) {
  VehicleOnLane v;
  v.lane = "N_0";
  v.lane_position_m = 95.0;
  v.route = {"N", "S"};
  v.route_index = 0;
  v.junction_shapes = junction_shapes;
  LaneCorridor c;
  c.centre = w.Lane("N_0").shape;
  c.position_m = 92.5;
  std::string beyond;
  std::optional<double> route_end;
  FollowRoute(v, 30.0, &w, &c, &beyond, &route_end);
  EXPECT_EQ(beyond, "S_0");
  return c;
}

TEST(ObjectLanes, WithJunctionShapesTheCorridorFollowsBothPartsOfAUTurn) {
  FakeSumoWorld w = UTurn();
  const LaneCorridor c = CorridorOf(w, true);
  // The turn's apex (-2, 2) is on the centre line: the first part's end, the second's start.
  bool apex = false, second_part = false;
  for (const Point2& p : c.centre) {
    if (std::hypot(p.x + 2.0, p.y - 2.0) < 1e-9) apex = true;
    const double a = 0.75 * kPi;  // a point inside the second part only
    if (std::hypot(p.x - (-2.0 + 2.0 * std::cos(a)), p.y - 2.0 * std::sin(a)) < 1e-9)
      second_part = true;
  }
  EXPECT_TRUE(apex);
  EXPECT_TRUE(second_part);
  EXPECT_NEAR(NorthMost(c), 2.0, 1e-9);
  EXPECT_NEAR(c.centre.back().x, -4.0, 1e-9);
  EXPECT_NEAR(c.centre.back().y, -100.0, 1e-9);
}

TEST(ObjectLanes, WithoutJunctionShapesTheCorridorJumpsAlongTheChord) {
  FakeSumoWorld w = UTurn();
  const LaneCorridor c = CorridorOf(w, false);
  // From N's end (0, 0) straight to S's start (-4, 0): nothing north of the junction.
  EXPECT_NEAR(NorthMost(c), 0.0, 1e-9);
  EXPECT_NEAR(c.centre.back().x, -4.0, 1e-9);
}

// A 12 m bus on the right lane of a two-lane edge running east (E_0 centre y = -1.6, E_1 centre
// y = +1.6), its front `offset_m` left of E_0's centre and its heading `turn_rad` left of east,
// as SUMO's continuous lane change places it.
// A vehicle on lane `index` of edge E (running east), its front 50 m along it.
VehicleOnLane OnEdgeE(int index, double length_m, double speed_mps, const std::string& vclass) {
  VehicleOnLane v;
  v.lane = "E_" + std::to_string(index);
  v.lane_index = index;
  v.lane_position_m = 50.0;
  v.length_m = length_m;
  v.speed_mps = speed_mps;
  v.route = {"E"};
  v.vehicle_class = vclass;
  return v;
}

VehicleOnLane ChangingBus(double offset_m, double turn_rad, Blinker blinker) {
  VehicleOnLane v = OnEdgeE(0, 12.0, 2.0, "bus");
  v.blinker = blinker;
  v.front = Point2{50.0, -1.6 + offset_m};
  v.centre = Pose2{50.0 - 6.0 * std::cos(turn_rad), v.front.y - 6.0 * std::sin(turn_rad), turn_rad};
  return v;
}

FakeSumoWorld TwoLanesEast() {
  FakeSumoWorld w;
  w.AddEdge("E", 0, 0, 200, 0, 2);
  return w;
}

TEST(ObjectLanes, AVehicleSeenChangingLanesMovesIntoTheLaneItsBlinkerShows) {
  FakeSumoWorld w = TwoLanesEast();
  EXPECT_EQ(LaneChangeTarget(ChangingBus(0.16, 0.026, Blinker::kLeft), &w), "E_1");
  // Not changing: no blinker, the blinker the other way (and no lane there), the front on the
  // centre line (SUMO's default instant lane changes, or a blinker for a turn ahead), the
  // heading along the lane, or past the middle of the change (SUMO has put it on E_1, its
  // front still right of E_1's centre).
  EXPECT_EQ(LaneChangeTarget(ChangingBus(0.16, 0.026, Blinker::kNone), &w), "");
  EXPECT_EQ(LaneChangeTarget(ChangingBus(0.16, 0.026, Blinker::kRight), &w), "");
  EXPECT_EQ(LaneChangeTarget(ChangingBus(0.0, 0.026, Blinker::kLeft), &w), "");
  EXPECT_EQ(LaneChangeTarget(ChangingBus(0.16, 0.0, Blinker::kLeft), &w), "");
  VehicleOnLane past = ChangingBus(-1.41 + 3.2, 0.23, Blinker::kLeft);
  past.lane = "E_1";
  past.lane_index = 1;
  EXPECT_EQ(LaneChangeTarget(past, &w), "");
  // A lane its class may not use.
  FakeSumoWorld bus_only_left;
  bus_only_left.AddEdge("E", 0, 0, 200, 0, 2, 3.2, {"passenger"});
  EXPECT_EQ(LaneChangeTarget(ChangingBus(0.16, 0.026, Blinker::kLeft), &bus_only_left), "");
}

TEST(ObjectLanes, WithLaneChangeTargetTheLanesAreThoseOfTheLaneMovedInto) {
  FakeSumoWorld w = TwoLanesEast();
  CounterLanes counter(&w);
  SceneConfig config;  // the default: its own lane
  const VehicleOnLane bus = ChangingBus(0.16, 0.026, Blinker::kLeft);
  const ObjectLanes own = LanesOf(bus, config, 0.1, &w, &counter);
  config.lane_change_target = true;
  const ObjectLanes into = LanesOf(bus, config, 0.1, &w, &counter);
  ASSERT_TRUE(into.lanes.own && own.lanes.own);
  // In the bus's frame (its centre on E_0's centre line, turned 1.5 degrees left): E_0 runs
  // from y = -1.6 to 1.6 at its first samples, E_1 from 1.6 to 4.8.
  EXPECT_NEAR(into.lanes.own->left.points[0].y, 4.8, 0.01);
  EXPECT_NEAR(into.lanes.own->right.points[0].y, 1.6, 0.01);
  EXPECT_TRUE(into.lanes.right.has_value());
  EXPECT_FALSE(into.lanes.left.has_value());
  EXPECT_NEAR(own.lanes.own->left.points[0].y, 1.6, 0.01);
  EXPECT_NEAR(own.lanes.own->right.points[0].y, -1.6, 0.01);
  EXPECT_TRUE(own.lanes.left.has_value());
  EXPECT_FALSE(own.lanes.right.has_value());
}

// A left-hand road running east and west (netconvert --lefthand numbers lanes from the kerb,
// now on the left): eastbound E keeps to the north half, E_0 at y = 4.8 by the kerb, E_1 at 1.6
// by the centre line; westbound W keeps to the south half, W_0 at -4.8, W_1 at -1.6.
FakeSumoWorld LeftHandRoad() {
  FakeSumoWorld w;
  w.AddEdge("E", 0, 3.2, 200, 3.2, 2);
  w.AddEdge("W", 200, -3.2, 0, -3.2, 2);
  w.MirrorLanes("E");
  w.MirrorLanes("W");
  return w;
}

TEST(ObjectLanes, InALeftHandNetworkTheNeighboursAndTheOncomingLaneAreMirrored) {
  FakeSumoWorld right_hand = TwoLanesEast();
  FakeSumoWorld left_hand = LeftHandRoad();
  EXPECT_FALSE(LeftHandTraffic(right_hand));
  EXPECT_TRUE(LeftHandTraffic(left_hand));
  FakeSumoWorld single;
  single.AddEdge("S", 0, 0, 100, 0, 1);
  EXPECT_FALSE(LeftHandTraffic(single));  // nothing to read: taken as right-hand

  CounterLanes counter(&left_hand);
  EXPECT_TRUE(counter.LeftHand());
  EXPECT_EQ(counter.Offside("E_1").value_or(""), "W_1");
  EXPECT_EQ(counter.Offside("W_1").value_or(""), "E_1");
  EXPECT_FALSE(counter.Offside("E_0").has_value());  // the kerb lane: nothing beyond the road
  // A car by the centre line, E_1: the kerb lane on its left, the oncoming lane on its right.
  VehicleOnLane car = OnEdgeE(1, 5.0, 10.0, "passenger");
  car.front = Point2{50.0, 1.6};
  car.centre = Pose2{47.5, 1.6, 0.0};
  const ObjectLanes by_centre = LanesOf(car, SceneConfig{}, 0.1, &left_hand, &counter);
  ASSERT_TRUE(by_centre.lanes.left && by_centre.lanes.right);
  EXPECT_FALSE(by_centre.lanes.left->counter_traffic);
  EXPECT_TRUE(by_centre.lanes.right->counter_traffic);
  // In the car's frame (its centre on y = 1.6): E_0's kerb side at y = 6.4, W_1's far side at
  // y = -3.2.
  EXPECT_NEAR(by_centre.lanes.left->left.points[0].y, 4.8, 0.01);
  EXPECT_NEAR(by_centre.lanes.right->right.points[0].y, -4.8, 0.01);
  // By the kerb, E_0: E_1 on its right, nothing on its left.
  car = OnEdgeE(0, 5.0, 10.0, "passenger");
  car.front = Point2{50.0, 4.8};
  car.centre = Pose2{47.5, 4.8, 0.0};
  const ObjectLanes by_kerb = LanesOf(car, SceneConfig{}, 0.1, &left_hand, &counter);
  EXPECT_FALSE(by_kerb.lanes.left.has_value());
  ASSERT_TRUE(by_kerb.lanes.right.has_value());
  EXPECT_FALSE(by_kerb.lanes.right->counter_traffic);
  EXPECT_NEAR(by_kerb.lanes.right->right.points[0].y, -4.8, 0.01);  // E_1's side at y = 0
}

TEST(ObjectLanes, InALeftHandNetworkALeftBlinkerPointsToTheLowerIndex) {
  FakeSumoWorld w = TwoLanesEast();
  w.MirrorLanes("E");  // E_0 at y = 1.6 (left), E_1 at y = -1.6
  VehicleOnLane bus = ChangingBus(0.16, 0.026, Blinker::kLeft);  // moving left from y = -1.6
  bus.lane = "E_1";
  bus.lane_index = 1;
  EXPECT_EQ(LaneChangeTarget(bus, &w, /*left_hand=*/true), "E_0");
  EXPECT_EQ(LaneChangeTarget(bus, &w, /*left_hand=*/false), "");  // no E_2 to the "left"
}

}  // namespace
}  // namespace criticality::plugin
