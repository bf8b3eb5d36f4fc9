// The car-following expectation the driver hands the estimator (plugin/car_following.h):
// values worked out by hand from the formula's physics, not from the code.
#include "plugin/car_following.h"

#include <gtest/gtest.h>

namespace criticality::plugin {
namespace {

TEST(CarFollowing, NothingToReactToWhenTheLeaderIsNotSlowerAndNotBraking) {
  EXPECT_FALSE(CarFollowingAccel(10.0, Leader{5.0, 12.0, 0.0}, 4.5).has_value());
  EXPECT_FALSE(CarFollowingAccel(10.0, Leader{5.0, 10.0, 0.5}, 4.5).has_value());
}

TEST(CarFollowing, StopsBehindAStoppedLeaderAtConstantDeceleration) {
  // 10 m/s, 20 m to go: v^2 / (2 d) = 100 / 40 = 2.5 m/s^2.
  const auto a = CarFollowingAccel(10.0, Leader{20.0, 0.0, 0.0}, 4.5);
  ASSERT_TRUE(a.has_value());
  EXPECT_DOUBLE_EQ(*a, -2.5);
}

TEST(CarFollowing, MatchesASlowerLeadersSpeedWithinTheGap) {
  // Closing at 6 m/s over 12 m: 36 / 24 = 1.5 m/s^2.
  const auto a = CarFollowingAccel(20.0, Leader{12.0, 14.0, 0.0}, 4.5);
  ASSERT_TRUE(a.has_value());
  EXPECT_DOUBLE_EQ(*a, -1.5);
}

TEST(CarFollowing, StopsBehindABrakingLeadersStoppingPoint) {
  // Both at 10 m/s, the leader braking at 2 m/s^2 stops in 25 m; 15 m gap: stop within 40 m,
  // 100 / 80 = 1.25 m/s^2.
  const auto a = CarFollowingAccel(10.0, Leader{15.0, 10.0, -2.0}, 4.5);
  ASSERT_TRUE(a.has_value());
  EXPECT_DOUBLE_EQ(*a, -1.25);
}

TEST(CarFollowing, NeverBeyondNormalBraking) {
  // 10 m/s, 5 m to a stopped car would need 10 m/s^2; and a gap inside minGap.
  EXPECT_DOUBLE_EQ(*CarFollowingAccel(10.0, Leader{5.0, 0.0, 0.0}, 4.5), -4.5);
  EXPECT_DOUBLE_EQ(*CarFollowingAccel(3.0, Leader{-0.5, 0.0, 0.0}, 4.5), -4.5);
  EXPECT_DOUBLE_EQ(*CarFollowingAccel(10.0, Leader{5.0, 0.0, 0.0}, 3.0), -3.0);
}

TEST(CarFollowing, LooksFartherAtHigherSpeed) {
  EXPECT_DOUBLE_EQ(LeaderLookAhead(0.0), 20.0);
  EXPECT_DOUBLE_EQ(LeaderLookAhead(10.0), 50.0);  // 1 m/s^2 stops 10 m/s in 50 m
  EXPECT_DOUBLE_EQ(LeaderLookAhead(40.0), 250.0);
}

}  // namespace
}  // namespace criticality::plugin
