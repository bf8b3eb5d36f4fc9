#include "bench/paper_scenes.h"

#include <algorithm>
#include <cctype>

#include "criticality/errors.h"

namespace criticality::bench {
namespace {

LaneDivider StraightDivider(double y) {
  LaneDivider d;
  d.points = {Point2{0.0, y}, Point2{40.0, y}, Point2{80.0, y}};
  return d;
}

Lane StraightLane(double y_right, double y_left) {
  Lane lane;
  lane.right = StraightDivider(y_right);
  lane.left = StraightDivider(y_left);
  return lane;
}

// A vehicle on lane `lane` (-1 right, 0 ego lane, +1 left), `ahead` metres in front of the ego.
Vehicle Car(const std::string& id, int lane, double ahead, double speed) {
  Vehicle v;
  v.id = id;
  v.state.x_m = ahead;
  v.state.y_m = lane * kLaneWidth;
  v.state.speed_mps = speed;
  v.length_m = 4.5;
  v.width_m = 1.8;
  v.lanes = StraightThreeLanes();  // centred in its lane, heading along the road
  return v;
}

Scene EgoOnRoad() {
  Scene s;
  s.ego.id = "ego";
  s.ego.state.speed_mps = 25.0;
  s.ego.length_m = 4.5;
  s.ego.width_m = 1.8;
  s.ego.lanes = StraightThreeLanes();
  return s;
}

}  // namespace

LaneSet StraightThreeLanes(double w) {
  LaneSet lanes;
  lanes.own = StraightLane(-0.5 * w, 0.5 * w);
  lanes.left = StraightLane(0.5 * w, 1.5 * w);
  lanes.right = StraightLane(-1.5 * w, -0.5 * w);
  return lanes;
}

Scene PaperSceneS1() {
  Scene s = EgoOnRoad();
  s.vehicles = {Car("lead", 0, 30.0, 20.0), Car("left", 1, 12.0, 25.0),
                Car("right-behind", -1, -20.0, 26.0)};
  return s;
}

Scene PaperSceneS2() {
  Scene s = PaperSceneS1();
  s.vehicles.push_back(Car("follower", 0, -30.0, 26.0));
  s.vehicles.push_back(Car("left-ahead", 1, 40.0, 22.0));
  s.vehicles.push_back(Car("left-behind", 1, -18.0, 27.0));
  s.vehicles.push_back(Car("right-ahead", -1, 45.0, 21.0));
  s.vehicles.push_back(Car("right-near", -1, 15.0, 24.0));
  s.vehicles.push_back(Car("left-far", 1, 70.0, 25.0));
  s.vehicles.push_back(Car("lead-far", 0, 65.0, 22.0));
  return s;
}

Scene ScalingScene(int n) {
  Scene s = EgoOnRoad();
  for (int k = 0; k < n; ++k) {
    const int lane = k % 3 - 1;  // right, own, left, right, ...
    const int rank = k / 3;      // 0, 0, 0, 1, 1, 1, ...
    const double ahead = (rank % 2 == 0 ? 1.0 : -1.0) * (15.0 + 12.0 * (rank / 2)) + 3.0 * lane;
    const double speed = 20.0 + (k * 7 % 11);  // 20..30 m/s, deterministic
    s.vehicles.push_back(Car("co" + std::to_string(k), lane, ahead, speed));
  }
  return s;
}

Scene PaperScene(const std::string& name) {
  std::string n = name;
  std::transform(n.begin(), n.end(), n.begin(), [](unsigned char c) { return std::toupper(c); });
  if (n == "S1") return PaperSceneS1();
  if (n == "S2") return PaperSceneS2();
  throw InputError("scene = '" + name + "': unknown; use S1 or S2");
}

}  // namespace criticality::bench
