// The car-following expectation the driver hands the estimator (plugin/car_following.h):
// values worked out by hand from the formula's physics, not from the code.
#include "plugin/scenes/car_following.h"

#include <gtest/gtest.h>

#include <vector>

#include "plugin/scenes/expected_accel.h"

namespace criticality::plugin {
namespace {

Leader Ahead(double gap_m, double speed_mps, double accel_mps2, double stop_m = -1.0) {
  Leader l;
  l.gap_m = gap_m;
  l.speed_mps = speed_mps;
  l.accel_mps2 = accel_mps2;
  if (stop_m >= 0.0) l.stop_distance_m = stop_m;
  return l;
}

TEST(CarFollowing, NothingToReactToWhenTheLeaderIsNotSlowerAndNotBraking) {
  EXPECT_FALSE(CarFollowingAccel(10.0, Ahead(5.0, 12.0, 0.0), 4.5).has_value());
  EXPECT_FALSE(CarFollowingAccel(10.0, Ahead(5.0, 10.0, 0.5), 4.5).has_value());
}

TEST(CarFollowing, StopsBehindAStoppedLeaderAtConstantDeceleration) {
  // 10 m/s, 20 m to go: v^2 / (2 d) = 100 / 40 = 2.5 m/s^2.
  const auto a = CarFollowingAccel(10.0, Ahead(20.0, 0.0, 0.0), 4.5);
  ASSERT_TRUE(a.has_value());
  EXPECT_DOUBLE_EQ(*a, -2.5);
}

TEST(CarFollowing, MatchesASlowerLeadersSpeedWithinTheGap) {
  // Closing at 6 m/s over 12 m: 36 / 24 = 1.5 m/s^2.
  const auto a = CarFollowingAccel(20.0, Ahead(12.0, 14.0, 0.0), 4.5);
  ASSERT_TRUE(a.has_value());
  EXPECT_DOUBLE_EQ(*a, -1.5);
}

TEST(CarFollowing, StopsBehindABrakingLeadersStoppingPoint) {
  // Both at 10 m/s, the leader braking at 2 m/s^2 stops in 25 m; 15 m gap: stop within 40 m,
  // 100 / 80 = 1.25 m/s^2.
  const auto a = CarFollowingAccel(10.0, Ahead(15.0, 10.0, -2.0), 4.5);
  ASSERT_TRUE(a.has_value());
  EXPECT_DOUBLE_EQ(*a, -1.25);
}

TEST(CarFollowing, NeverBeyondNormalBraking) {
  // 10 m/s, 5 m to a stopped car would need 10 m/s^2; and a gap inside minGap.
  EXPECT_DOUBLE_EQ(*CarFollowingAccel(10.0, Ahead(5.0, 0.0, 0.0), 4.5), -4.5);
  EXPECT_DOUBLE_EQ(*CarFollowingAccel(3.0, Ahead(-0.5, 0.0, 0.0), 4.5), -4.5);
  EXPECT_DOUBLE_EQ(*CarFollowingAccel(10.0, Ahead(5.0, 0.0, 0.0), 3.0), -3.0);
}

TEST(CarFollowing, StopsBehindALeaderThatMustStopAtALine) {
  // The leader, 5.8 m/s and speeding up, must stop 5 m ahead (a yield line): it stops there,
  // so the follower at 4 m/s with 3 m gap stops within 8 m, 16 / 16 = 1 m/s^2.
  const auto a = CarFollowingAccel(4.0, Ahead(3.0, 5.8, 2.1, 5.0), 4.5);
  ASSERT_TRUE(a.has_value());
  EXPECT_DOUBLE_EQ(*a, -1.0);
  // Without the line nothing asks for braking.
  EXPECT_FALSE(CarFollowingAccel(4.0, Ahead(3.0, 5.8, 2.1), 4.5).has_value());
  // A braking leader stopping short of its line: its own stopping point counts (10 m/s at
  // 5 m/s^2 stops in 10 m, the line is 30 m on): 100 / (2 * 20) = 2.5 m/s^2.
  EXPECT_DOUBLE_EQ(*CarFollowingAccel(10.0, Ahead(10.0, 10.0, -5.0, 30.0), 4.5), -2.5);
}

TEST(CarFollowing, ALineTheLeaderCannotStopAtNormallyDoesNotCount) {
  // 15 m/s, the line 5 m ahead: 22.5 m/s^2 to stop there. It will run it (or brake hard, which
  // the follower does not expect): the follower, not closing in, has nothing to react to.
  EXPECT_FALSE(CarFollowingAccel(10.0, Ahead(8.0, 15.0, 0.0, 5.0), 4.5).has_value());
  // Exactly a normal deceleration away (9 m/s: 81 / (2 * 4.5) = 9 m) it counts.
  EXPECT_TRUE(CarFollowingAccel(10.0, Ahead(8.0, 9.0, 0.0, 9.0), 4.5).has_value());
}

TEST(CarFollowing, FollowersOfLeadersWithAStopLineExpectThemToStop) {
  auto vehicle = [](const std::string& id, double speed) {
    ObjectSnapshot o;
    o.id = id;
    o.state.speed_mps = speed;
    return o;
  };
  std::vector<ObjectSnapshot> objects;
  objects.push_back(vehicle("leader", 1.2));  // a person with the leader's ID comes first
  objects.back().person = true;
  objects.push_back(vehicle("leader", 5.8));
  objects.back().stop_line = StopLine{StopLine::Reason::kYield, 5.0};
  objects.push_back(vehicle("follower", 4.0));
  objects.back().leader = Ahead(3.0, 5.8, 2.1);
  objects.back().leader->id = "leader";
  objects.push_back(vehicle("free", 4.0));  // its leader has no line
  objects.back().leader = Ahead(3.0, 5.8, 2.1);
  objects.back().leader->id = "follower";
  objects.push_back(vehicle("far", 4.0));  // its leader is not among the objects
  objects.back().leader = Ahead(3.0, 5.8, 2.1);
  objects.back().leader->id = "elsewhere";
  ExpectCarFollowing(&objects, 4.5);
  ASSERT_TRUE(objects[2].state.expected_accel_mps2.has_value());
  EXPECT_DOUBLE_EQ(*objects[2].state.expected_accel_mps2, -1.0);
  EXPECT_FALSE(objects[1].state.expected_accel_mps2.has_value());
  EXPECT_FALSE(objects[3].state.expected_accel_mps2.has_value());
  EXPECT_FALSE(objects[4].state.expected_accel_mps2.has_value());
}

TEST(CarFollowing, LooksFartherAtHigherSpeed) {
  EXPECT_DOUBLE_EQ(LeaderLookAhead(0.0), 20.0);
  EXPECT_DOUBLE_EQ(LeaderLookAhead(10.0), 50.0);  // 1 m/s^2 stops 10 m/s in 50 m
  EXPECT_DOUBLE_EQ(LeaderLookAhead(40.0), 250.0);
}

}  // namespace
}  // namespace criticality::plugin
