// The expected acceleration as the reference hypothesis (Params::expected_accel_reference,
// ObjectState::expected_accel_mps2): a driver closing in on a stopped car is expected to
// brake for it. Without that expectation the paper's reference ("keep the current
// acceleration") runs into the stopped car, and both get warned.
#include <gtest/gtest.h>

#include "bench/paper_scenes.h"
#include "criticality/estimator.h"
#include "criticality/geometry.h"

namespace criticality {
namespace {

// The ego stopped in the middle lane of a straight three-lane road, a car of the same length
// coming up behind it at `speed` with `gap_m` between bumpers.
Scene StoppedEgoAndCarBehind(double length_m, double gap_m, double speed) {
  Scene scene;
  scene.ego.lanes = bench::StraightThreeLanes();
  scene.ego.length_m = length_m;
  Vehicle follower;
  follower.id = "follower";
  follower.length_m = length_m;
  follower.state.x_m = -(length_m + gap_m);
  follower.state.speed_mps = speed;
  scene.vehicles.push_back(follower);
  return scene;
}

// Waiting in a queue, a car coming up behind it at 10 m/s, 15 m between bumpers, not braking
// yet: stopping behind the ego 2.5 m back asks for 100 / (2 * 12.5) = 4 m/s^2.
Scene StoppedEgoCarComingUpBehind() { return StoppedEgoAndCarBehind(4.5, 15.0, 10.0); }

TEST(ExpectedAccel, AFollowerExpectedToBrakeIsNotAThreat) {
  Scene scene = StoppedEgoCarComingUpBehind();
  Estimator estimator(Params{});
  const Result ignorant = estimator.Estimate(scene);
  scene.vehicles[0].state.expected_accel_mps2 = -4.0;
  const Result expecting = estimator.Estimate(scene);
  // Keeping 10 m/s, the follower hits the ego within 1.5 s: most of its mass collides.
  EXPECT_GT(ignorant.p_collision, 0.5);
  // Braking as expected it stops behind; only its less likely hypotheses still collide.
  EXPECT_LT(expecting.p_collision, 0.2);
  EXPECT_LT(expecting.p_collision, 0.5 * ignorant.p_collision);
}

TEST(ExpectedAccel, AnEgoExpectedToBrakeKeepsItsReferenceClear) {
  // The ego at 10 m/s, a stopped car 15 m ahead (bumpers): keeping its speed it hits the car
  // after 1.5 s, within the 2 s horizon; braking at 4.5 m/s^2 (after the latency and the jerk
  // ramp) stops it about 3 m short.
  Scene scene;
  scene.ego.lanes = bench::StraightThreeLanes();
  scene.ego.state.speed_mps = 10.0;
  Vehicle stopped;
  stopped.id = "stopped";
  stopped.state.x_m = 0.5 * scene.ego.length_m + 15.0 + 2.25;
  stopped.length_m = 4.5;
  scene.vehicles.push_back(stopped);
  Estimator estimator(Params{});
  const Result ignorant = estimator.Estimate(scene);
  scene.ego.state.expected_accel_mps2 = -4.5;
  const Result expecting = estimator.Estimate(scene);
  EXPECT_GT(ignorant.p_reference, 0.9);
  EXPECT_LT(expecting.p_reference, 0.05);
  EXPECT_LT(expecting.p_collision, ignorant.p_collision);
}

// A person walking at 1.2 m/s straight toward the ego's lane, 0.6 m from the side of the ego
// passing at 5 m/s: walking on it steps into the ego's side within half a second. Expected to
// stop where its crossing begins, 0.3 m ahead (2.4 m/s^2), it stays clear of the ego but for
// its least likely hypotheses.
TEST(ExpectedAccel, AWalkerExpectedToStopAtTheKerbIsLessOfAThreat) {
  Scene scene;
  scene.ego.lanes = bench::StraightThreeLanes();
  scene.ego.state.speed_mps = 5.0;
  Pedestrian walker;
  walker.id = "walker";
  walker.state.x_m = 1.0;
  walker.state.y_m = -(0.5 * scene.ego.width_m + 0.6 + 0.5 * walker.width_m);
  walker.state.yaw_rad = 0.5 * kPi;  // toward the ego
  walker.state.speed_mps = 1.2;
  scene.pedestrians.push_back(walker);
  Estimator estimator(Params{});
  const Result walking_on = estimator.Estimate(scene);
  scene.pedestrians[0].state.expected_accel_mps2 = -2.4;
  const Result stopping = estimator.Estimate(scene);
  // Measured: 0.79 walking on, below 1e-4 stopping.
  EXPECT_GT(walking_on.p_collision, 0.5);
  EXPECT_LT(stopping.p_collision, 0.1);
  // The paper's reference (Params::expected_accel_reference off) keeps walking.
  Params off;
  off.expected_accel_reference = false;
  Scene walking = scene;
  walking.pedestrians[0].state.expected_accel_mps2.reset();
  EXPECT_EQ(Estimator(off).Estimate(scene).p_collision,
            Estimator(off).Estimate(walking).p_collision);
}

TEST(ExpectedAccel, OnlyALowerExpectationReplacesTheCurrentAcceleration) {
  Scene scene = StoppedEgoCarComingUpBehind();
  Estimator estimator(Params{});
  const Result plain = estimator.Estimate(scene);
  scene.vehicles[0].state.expected_accel_mps2 = 1.0;  // above the current 0: ignored
  EXPECT_EQ(estimator.Estimate(scene).p_collision, plain.p_collision);
}

TEST(ExpectedAccel, ThePaperLiteralPresetIgnoresIt) {
  Scene scene = StoppedEgoCarComingUpBehind();
  Estimator estimator(ParamsPreset("paper-literal"));
  const Result plain = estimator.Estimate(scene);
  scene.vehicles[0].state.expected_accel_mps2 = -4.0;
  EXPECT_EQ(estimator.Estimate(scene).p_collision, plain.p_collision);
  Params off;
  off.expected_accel_reference = false;
  Estimator without(off);
  const Result a = without.Estimate(scene);
  scene.vehicles[0].state.expected_accel_mps2.reset();
  EXPECT_EQ(without.Estimate(scene).p_collision, a.p_collision);
}

// Params::release_unexplained_braking: the ego at 10 m/s braking at 6 m/s^2 (it stops within
// about 10 m), a stopped car 16 m ahead (bumpers). Braking on, the reference stops short of
// it; released, it holds its speed and hits the car within the horizon. Only a caller that knows
// the ego's reasons to brake (ObjectState::braking_causes_known) releases it, and a known reason
// (here an expected -6 m/s^2 for the car ahead) keeps the braking.
TEST(ExpectedAccel, BrakingWithoutAKnownCauseIsReleasedOnlyWhereTheCausesAreKnown) {
  Scene scene;
  scene.ego.lanes = bench::StraightThreeLanes();
  scene.ego.state.speed_mps = 10.0;
  scene.ego.state.accel_mps2 = -6.0;
  Vehicle stopped;
  stopped.id = "stopped";
  stopped.state.x_m = 0.5 * scene.ego.length_m + 16.0 + 2.25;
  stopped.length_m = 4.5;
  scene.vehicles.push_back(stopped);
  Params release;
  release.release_unexplained_braking = true;
  const Result off = Estimator(Params{}).Estimate(scene);
  const Result unknown = Estimator(release).Estimate(scene);
  scene.ego.state.braking_causes_known = true;
  const Result released = Estimator(release).Estimate(scene);
  const Result default_params = Estimator(Params{}).Estimate(scene);
  scene.ego.state.expected_accel_mps2 = -6.0;
  const Result explained = Estimator(release).Estimate(scene);
  EXPECT_LT(off.p_reference, 0.05);
  EXPECT_EQ(unknown.p_collision, off.p_collision);  // causes unknown: the paper's reference
  EXPECT_EQ(default_params.p_collision, off.p_collision);  // the rule is off by default
  EXPECT_GT(released.p_reference, 0.9);
  EXPECT_GT(released.p_collision, off.p_collision);
  EXPECT_LT(explained.p_reference, 0.05);
}

// Params::expected_accel_at_once, as traced in a SUMO grid (bench/RESULTS.md, seventeenth
// stop): a car accelerating at +2.2 m/s^2 at 4.3 m/s towards a car standing 3 m ahead of its
// bumper, expected to brake at 4.5 m/s^2 (SUMO's follower stopped 1 m short). Holding +2.2
// m/s^2 through the 0.2 s latency it needs about 3.4 m to stop; braking at once, about 2.3 m.
// Catches a rule that is ignored (p stays), applied to the ego, or applied to an expectation
// above the current acceleration.
Scene FollowerAcceleratingTowardsAStandingCar() {
  Scene scene = StoppedEgoAndCarBehind(5.0, 3.0, 4.3);
  scene.vehicles[0].state.accel_mps2 = 2.2;
  scene.vehicles[0].state.expected_accel_mps2 = -4.5;
  return scene;
}

TEST(ExpectedAccel, AnExpectedBrakingActsAtOnceWhereTheRuleSaysSo) {
  Scene scene = FollowerAcceleratingTowardsAStandingCar();
  Params held;
  held.expected_accel_at_once = false;
  const Result at_once = Estimator(Params{}).Estimate(scene);
  const Result latency = Estimator(held).Estimate(scene);
  EXPECT_GT(latency.p_collision, 0.5);
  EXPECT_LT(at_once.p_collision, 0.2);
  // Not for the ego: its hypotheses keep its driver's latency (the rule changes nothing there).
  Scene ego_scene;
  ego_scene.ego.lanes = bench::StraightThreeLanes();
  ego_scene.ego.length_m = 5.0;
  ego_scene.ego.state.speed_mps = 4.3;
  ego_scene.ego.state.accel_mps2 = 2.2;
  ego_scene.ego.state.expected_accel_mps2 = -4.5;
  Vehicle standing;
  standing.id = "standing";
  standing.length_m = 5.0;
  standing.state.x_m = 5.0 + 3.0;
  ego_scene.vehicles.push_back(standing);
  const Result ego_at_once = Estimator(Params{}).Estimate(ego_scene);
  const Result ego_latency = Estimator(held).Estimate(ego_scene);
  EXPECT_GT(ego_latency.p_reference, 0.9);
  EXPECT_EQ(ego_at_once.p_collision, ego_latency.p_collision);
  // Only a lower expectation acts at once; one above the current acceleration changes nothing.
  scene.vehicles[0].state.expected_accel_mps2 = 3.0;
  EXPECT_EQ(Estimator(Params{}).Estimate(scene).p_collision,
            Estimator(held).Estimate(scene).p_collision);
}

}  // namespace
}  // namespace criticality
