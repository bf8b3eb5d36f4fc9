// Vehicles that leave the simulation (ObjectState::route_end_m, Params::route_end_leaves): SUMO
// removes a vehicle whose route ends, at full speed, often just before a junction. Its
// hypotheses carried on across the junction into the traffic that had the green light.
#include <gtest/gtest.h>

#include <cmath>

#include "bench/paper_scenes.h"
#include "core/trajectory_generation.h"
#include "criticality/errors.h"
#include "criticality/estimator.h"
#include "src/problem.h"
#include "test_scenes.h"

namespace criticality {
namespace {

// The ego at 50 km/h on a straight three-lane road; a car from the right at 11.6 m/s, heading
// across the road, its front 10 m from the ego's lane (whose path it meets in about 1.4 s).
Scene ArrivingCrossingScene() {
  Scene s;
  s.ego.state.speed_mps = 13.9;
  s.ego.lanes = bench::StraightThreeLanes();
  Vehicle v;
  v.id = "arriving";
  v.state.x_m = 21.5;
  v.state.y_m = -1.75 - 10.0 - 2.25;
  v.state.yaw_rad = 0.5 * core::kPi;
  v.state.speed_mps = 11.6;
  s.vehicles.push_back(v);
  return s;
}

using testing::PCollision;

TEST(RouteEnd, ACarWhoseRouteEndsBeforeTheEgosRoadIsNoThreat) {
  const Scene driving_on = ArrivingCrossingScene();
  Scene leaving = driving_on;
  leaving.vehicles[0].state.route_end_m = 6.0;  // its front reaches the route's end 4 m short
  const double p_on = PCollision(driving_on), p_leaving = PCollision(leaving);
  EXPECT_GT(p_on, 0.8);  // above the driver's warning release (0.8 x 0.9)
  EXPECT_LT(p_leaving, 0.01);
  // Off: as if it drove on; paper-literal ignores it too.
  Params off;
  off.route_end_leaves = false;
  EXPECT_EQ(PCollision(leaving, off), p_on);
  EXPECT_FALSE(ParamsPreset("paper-literal").route_end_leaves);
  // A route that ends beyond the ego's road changes nothing it could hit before.
  Scene far = driving_on;
  far.vehicles[0].state.route_end_m = 60.0;
  EXPECT_GT(PCollision(far), 0.8);
  // The reference backend builds and checks the same.
  EXPECT_NEAR(PCollision(leaving, Params{}, Backend::kReference), p_leaving, 1e-12);
  EXPECT_NEAR(PCollision(far, Params{}, Backend::kReference), PCollision(far), 1e-12);
}

TEST(RouteEnd, AnEgoWhoseRouteEndsBeforeTheCrossingIsNotWarned) {
  Scene leaving = ArrivingCrossingScene();
  ASSERT_GT(PCollision(leaving), 0.8);
  leaving.ego.state.route_end_m = 8.0;  // it leaves before the crossing car reaches its lane
  const Result r = Estimator(Params{}).Estimate(leaving);
  EXPECT_LT(r.p_collision, 0.01);
  EXPECT_NEAR(PCollision(leaving, Params{}, Backend::kReference), r.p_collision, 1e-12);
  // Its escape routes still report where it drives, not where it went when it left.
  ASSERT_FALSE(r.escape_routes.empty());
  for (double x : r.escape_routes[0].x_m) EXPECT_LT(std::fabs(x), 100.0);
}

TEST(RouteEnd, PosesAfterLeavingLieFarFromEverything) {
  const internal::Problem pb = internal::BuildProblem(ArrivingCrossingScene(), Params{});
  core::HypothesisSet co = pb.cos[0];
  ASSERT_EQ(co.leave_distance, HUGE_VAL);
  const int steps = pb.sim.n_steps;
  std::vector<double> x0(steps), y0(steps), yaw0(steps), x(steps), y(steps), yaw(steps);
  core::SimulateHypothesis(co, pb.sim, 0, 0, x0.data(), y0.data(), yaw0.data());
  co.leave_distance = 5.0;
  core::SimulateHypothesis(co, pb.sim, 0, 0, x.data(), y.data(), yaw.data());
  // Every step is checked on one side or the other of the leaving point (both sides must be
  // reached, so neither branch can go unexercised).
  int stayed = 0, left = 0;
  for (int n = 0; n < steps; ++n) {
    const double travelled = std::fabs(y0[n] - co.X_WL.y);  // it drives straight along +y
    if (travelled < 4.9) {
      EXPECT_EQ(x[n], x0[n]) << n;
      EXPECT_EQ(y[n], y0[n]) << n;
      ++stayed;
    } else if (travelled > 5.1) {
      EXPECT_EQ(x[n], -core::kGoneX) << n;
      ++left;
    }
  }
  EXPECT_GT(stayed, 2);
  EXPECT_GT(left, steps / 2);
  EXPECT_GE(stayed + left, steps - 1);  // at most the one step that straddles 5 m
  // The ego leaves to the other side: two that have left never overlap.
  core::HypothesisSet ego = pb.ego;
  ego.leave_distance = 0.0;
  core::SimulateHypothesis(ego, pb.sim, 0, 0, x.data(), y.data(), yaw.data());
  EXPECT_EQ(x[0], core::kGoneX);
}

TEST(RouteEnd, ANegativeOrNonFiniteRouteEndIsRejected) {
  Scene bad = ArrivingCrossingScene();
  bad.vehicles[0].state.route_end_m = -1.0;
  try {
    Estimator(Params{}).Estimate(bad);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("scene.vehicles[0] ('arriving').state.route_end_m = -1"),
              std::string::npos)
        << e.what();
  }
  bad.vehicles[0].state.route_end_m = std::nan("");
  EXPECT_THROW(Estimator(Params{}).Estimate(bad), InputError);
}

}  // namespace
}  // namespace criticality
