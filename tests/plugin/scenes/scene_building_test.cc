// Scene building from SUMO's snapshots: range, order, and objects with invalid values (SUMO
// 1.15 reports some persons on walking areas with NaN position and angle) left out.
#include "plugin/scenes/scene_building.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "criticality/estimator.h"

namespace criticality::plugin {
namespace {

ObjectSnapshot Car(const std::string& id, double x, double y) {
  ObjectSnapshot s;
  s.id = id;
  s.state.x_m = x;
  s.state.y_m = y;
  s.state.speed_mps = 10.0;
  return s;
}

ObjectSnapshot Person(const std::string& id, double x, double y) {
  ObjectSnapshot s = Car(id, x, y);
  s.person = true;
  s.length_m = s.width_m = 0.5;
  s.state.speed_mps = 1.2;
  return s;
}

TEST(SceneBuilding, KeepsObjectsWithinRangeInIdOrder) {
  const ObjectSnapshot ego = Car("ego", 0, 0);
  const ObjectSnapshot b = Car("b", 30, 0), a = Car("a", -20, 3), far = Car("far", 81, 0);
  const ObjectSnapshot p = Person("p", 5, 5), self = Car("ego", 0, 0);
  std::vector<LeftOutObject> left_out;
  const Scene s = BuildScene(ego, {&b, &far, &a, &p, &self}, 80.0, &left_out);
  ASSERT_EQ(s.vehicles.size(), 2u);
  EXPECT_EQ(s.vehicles[0].id, "a");  // ID order, whatever order SUMO listed them in
  EXPECT_EQ(s.vehicles[1].id, "b");
  ASSERT_EQ(s.pedestrians.size(), 1u);
  EXPECT_EQ(s.pedestrians[0].id, "p");
  EXPECT_EQ(s.ego.id, "ego");
  EXPECT_TRUE(left_out.empty());
}

TEST(SceneBuilding, ObjectsWithNanValuesAreLeftOutAndNamed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const ObjectSnapshot ego = Car("ego", 0, 0);
  // As SUMO 1.15 reported a person on walking area :16125_w1_0: position and angle NaN.
  ObjectSnapshot walker = Person(":16125_w1_0 walker", nan, nan);
  walker.state.yaw_rad = nan;
  ObjectSnapshot fast = Car("fast", 10, 0);
  fast.state.speed_mps = std::numeric_limits<double>::infinity();
  ObjectSnapshot flat = Car("flat", 10, 3);
  flat.length_m = 0.0;
  ObjectSnapshot turning = Car("turning", 12, 0);
  turning.state.yaw_rate_radps = nan;
  const ObjectSnapshot fine = Car("fine", 20, 0), walker2 = Person("walker2", 3, 3);
  std::vector<LeftOutObject> left_out;
  const Scene s =
      BuildScene(ego, {&walker, &fast, &flat, &turning, &fine, &walker2}, 80.0, &left_out);
  ASSERT_EQ(s.vehicles.size(), 1u);
  EXPECT_EQ(s.vehicles[0].id, "fine");
  ASSERT_EQ(s.pedestrians.size(), 1u);
  EXPECT_EQ(s.pedestrians[0].id, "walker2");
  ASSERT_EQ(left_out.size(), 4u);
  EXPECT_TRUE(left_out[0].person);
  EXPECT_EQ(left_out[0].why, "state.x_m = nan");
  EXPECT_EQ(InvalidValues(fast), "state.speed_mps = inf");
  EXPECT_EQ(InvalidValues(flat), "size 0 x 1.8 m");
  EXPECT_EQ(InvalidValues(turning), "state.yaw_rate_radps = nan");
  // What is left is a scene the estimator takes: nothing invalid is sent on.
  Estimator estimator(Params{});
  EXPECT_NO_THROW(estimator.Estimate(s));
}

TEST(SceneBuilding, LanesWithNonFinitePointsMakeAnObjectInvalid) {
  ObjectSnapshot car = Car("car", 5, 0);
  Lane lane;
  for (int i = 0; i < 3; ++i) {
    lane.left.points[i] = Point2{10.0 * i, 1.6};
    lane.right.points[i] = Point2{10.0 * i, -1.6};
  }
  car.lanes.own = lane;
  EXPECT_EQ(InvalidValues(car), "");
  car.lanes.own->left.points[2].y = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(InvalidValues(car), "lanes with non-finite points");
}

}  // namespace
}  // namespace criticality::plugin
