// What the closed loop commands: never less braking than SUMO's own choice, the route's
// deceleration after the latency and within the jerk limit, never beyond emergencyDecel; the
// lateral plan read from an escape route; the route choice with and without steering.
#include "plugin/act/avoidance_manoeuvre.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace criticality::plugin {
namespace {

constexpr double kDt = 0.1;

SpeedInputs Braking(double route_accel, double elapsed, double previous) {
  SpeedInputs in;
  in.speed_mps = 30.0;
  in.own_speed_mps = 30.0;
  in.route_accel_mps2 = route_accel;
  in.emergency_decel_mps2 = 9.0;
  in.elapsed_s = elapsed;
  in.previous_accel_mps2 = previous;
  return in;
}

TEST(ClosedLoopSpeed, NothingDuringTheBrakeLatency) {
  const BrakeModel m{0.2, 30.0};
  EXPECT_FALSE(ClosedLoopSpeed(Braking(-9.0, 0.0, 0.0), m, kDt).command);
  EXPECT_FALSE(ClosedLoopSpeed(Braking(-9.0, 0.1, 0.0), m, kDt).command);
  EXPECT_TRUE(ClosedLoopSpeed(Braking(-9.0, 0.2, 0.0), m, kDt).command);
}

TEST(ClosedLoopSpeed, RampsAtTheJerkLimitUpToTheRoutesDeceleration) {
  const BrakeModel m{0.2, 30.0};
  double a = 0.0;
  std::vector<double> seen;
  for (int k = 0; k < 6; ++k) {
    const SpeedCommand c = ClosedLoopSpeed(Braking(-7.0, 0.2 + 0.1 * k, a), m, kDt);
    ASSERT_TRUE(c.command);
    a = c.accel_mps2;
    seen.push_back(a);
  }
  EXPECT_NEAR(seen[0], -3.0, 1e-12);  // 30 m/s^3 x 0.1 s
  EXPECT_NEAR(seen[1], -6.0, 1e-12);
  EXPECT_NEAR(seen[2], -7.0, 1e-12);  // the route's, not more
  EXPECT_NEAR(seen[5], -7.0, 1e-12);
}

TEST(ClosedLoopSpeed, NeverBeyondTheEmergencyDeceleration) {
  const BrakeModel m{0.0, 1000.0};
  const SpeedCommand c = ClosedLoopSpeed(Braking(-12.0, 1.0, -9.0), m, kDt);
  ASSERT_TRUE(c.command);
  EXPECT_DOUBLE_EQ(c.accel_mps2, -9.0);
  EXPECT_NEAR(c.speed_mps, 30.0 - 0.9, 1e-12);
}

TEST(ClosedLoopSpeed, NeverWeakerThanSumosOwnChoice) {
  const BrakeModel m{0.0, 30.0};
  SpeedInputs in = Braking(-3.0, 1.0, -3.0);
  in.own_speed_mps = 29.5;  // SUMO (or a scenario's forced speed) brakes harder than the route
  const SpeedCommand c = ClosedLoopSpeed(in, m, kDt);
  ASSERT_TRUE(c.command);
  EXPECT_DOUBLE_EQ(c.speed_mps, 29.5);
  // SUMO's own choice asks for 50 m/s^2 (30 -> 25 m/s in 0.1 s): the vehicle brakes at its
  // emergencyDecel (9), no harder.
  in.own_speed_mps = 25.0;
  EXPECT_NEAR(ClosedLoopSpeed(in, m, kDt).speed_mps, 30.0 - 0.9, 1e-12);
  in.own_speed_mps = std::numeric_limits<double>::infinity();
  EXPECT_NEAR(ClosedLoopSpeed(in, m, kDt).speed_mps, 29.7, 1e-12);
}

TEST(ClosedLoopSpeed, NeverBelowZero) {
  const BrakeModel m{0.0, 30.0};
  SpeedInputs in = Braking(-9.0, 1.0, -9.0);
  in.speed_mps = 0.3;
  EXPECT_DOUBLE_EQ(ClosedLoopSpeed(in, m, kDt).speed_mps, 0.0);
}

TEST(ClosedLoopSpeed, NothingBeforeTheFirstBrakingWhenTheRouteDoesNotBrake) {
  const BrakeModel m{0.2, 30.0};
  EXPECT_FALSE(ClosedLoopSpeed(Braking(0.5, 2.0, 0.0), m, kDt).command);
  EXPECT_FALSE(ClosedLoopSpeed(Braking(0.0, 2.0, 0.0), m, kDt).command);
}

TEST(ClosedLoopSpeed, OnceActiveARouteThatStopsBrakingRampsTheBrakeOffAndSumoTakesOver) {
  const BrakeModel m{0.2, 30.0};
  SpeedInputs in = Braking(2.0, 2.0, -7.0);
  in.active = true;
  SpeedCommand c = ClosedLoopSpeed(in, m, kDt);
  ASSERT_TRUE(c.command);
  EXPECT_NEAR(c.accel_mps2, -4.0, 1e-12);  // ramped off at the jerk limit, not dropped
  EXPECT_NEAR(c.speed_mps, 29.6, 1e-12);
  in.previous_accel_mps2 = -1.0;
  c = ClosedLoopSpeed(in, m, kDt);
  ASSERT_TRUE(c.command);  // still commanded: no switching within an engagement
  EXPECT_NEAR(c.accel_mps2, 2.0, 1e-12);
  EXPECT_DOUBLE_EQ(c.speed_mps, 30.0);  // ours (30.2) above SUMO's own: SUMO's wins
}

EscapeRoute LaneChangeLeft() {
  EscapeRoute r;
  for (int n = 0; n < 20; ++n) {
    const double t = 0.1 * (n + 1);
    r.time_s.push_back(t);
    // 3.5 m to the left over 2 s, linear; the boundary (1.75 m) is crossed at 1.0 s. Its
    // sections lie in the left lane from the start (as the estimator reports them).
    const double off = std::min(3.5, 3.5 * t / 2.0);
    r.lateral_offset_m.push_back(off);
    r.target_lanes.push_back(1);
  }
  return r;
}

TEST(LateralPlanOf, ReadsTheLaneChangeFromTheRoute) {
  const LateralPlan p = LateralPlanOf(LaneChangeLeft(), 3.5);
  EXPECT_EQ(p.direction, 1);
  EXPECT_NEAR(p.cross_s, 1.0, 1e-12);     // half the lane width reached
  EXPECT_NEAR(p.duration_s, 1.8, 1e-12);  // 90 % of 3.5 m reached
  EXPECT_NEAR(p.final_offset_m, 3.5, 1e-12);
  EscapeRoute right = LaneChangeLeft();
  for (double& x : right.lateral_offset_m) x = -x;
  for (int& l : right.target_lanes) l = -l;
  EXPECT_EQ(LateralPlanOf(right, 3.5).direction, -1);
  EXPECT_NEAR(LateralPlanOf(right, 3.5).cross_s, 1.0, 1e-12);
  EXPECT_NEAR(LateralPlanOf(right, 3.5).duration_s, 1.8, 1e-12);
  // A wider lane is crossed later.
  EXPECT_NEAR(LateralPlanOf(LaneChangeLeft(), 5.0).cross_s, 1.5, 1e-12);
}

TEST(LateralPlanOf, ARouteInItsLaneHasNoDirection) {
  EscapeRoute r = LaneChangeLeft();
  for (int& l : r.target_lanes) l = 0;
  EXPECT_EQ(LateralPlanOf(r, 3.5).direction, 0);
}

TEST(ChooseRoute, TheBestRankedUnlessItSteersAndSteeringIsOff) {
  EscapeRoute steer = LaneChangeLeft();
  steer.ego_trajectory = 7;
  EscapeRoute keep = LaneChangeLeft();
  for (int& l : keep.target_lanes) l = 0;
  keep.ego_trajectory = 3;
  const std::vector<EscapeRoute> ranked{steer, keep};
  EXPECT_EQ(ChooseRoute(ranked, true)->ego_trajectory, 7);
  EXPECT_EQ(ChooseRoute(ranked, false)->ego_trajectory, 3);
  EXPECT_EQ(ChooseRoute({steer}, false), nullptr);
  EXPECT_EQ(ChooseRoute({}, true), nullptr);
}

}  // namespace
}  // namespace criticality::plugin

namespace criticality::plugin {
namespace {

TEST(MainThreatBehind, TheLargestContributorDecides) {
  Scene scene;
  scene.ego.state.yaw_rad = 1.5707963267948966;  // heading +y
  Vehicle behind, ahead;
  behind.id = "behind";
  behind.state.y_m = -20.0;
  ahead.id = "ahead";
  ahead.state.y_m = 30.0;
  scene.vehicles = {behind, ahead};
  Result r;
  r.objects.resize(2);
  r.objects[0].id = "behind";
  r.objects[1].id = "ahead";
  EXPECT_FALSE(MainThreatBehind(scene, r));  // nobody contributes
  r.objects[0].contribution = 0.6;
  r.objects[1].contribution = 0.3;
  EXPECT_TRUE(MainThreatBehind(scene, r));
  r.objects[1].contribution = 0.7;
  EXPECT_FALSE(MainThreatBehind(scene, r));
  // Pedestrians count too; behind the ego's rear along the heading, whatever the side.
  scene.ego.length_m = 4.5;
  Pedestrian p;
  p.id = "walker";
  p.state.x_m = 5.0;
  p.state.y_m = -3.0;
  scene.pedestrians = {p};
  r.objects.push_back(ObjectResult{});
  r.objects.back().id = "walker";
  r.objects.back().contribution = 0.9;
  EXPECT_TRUE(MainThreatBehind(scene, r));
  // Beside the ego's body is not behind it, though behind its centre: a cyclist beside a 16.5 m
  // truck's trailer (truck_right_hook), whom the truck's braking lets pass ahead.
  scene.ego.length_m = 16.5;
  scene.pedestrians[0].state.x_m = 2.0;
  scene.pedestrians[0].state.y_m = -7.0;
  EXPECT_FALSE(MainThreatBehind(scene, r));
  scene.pedestrians[0].state.y_m = -8.5;
  EXPECT_TRUE(MainThreatBehind(scene, r));
}

}  // namespace
}  // namespace criticality::plugin
