// Stop obligations (Vehicle::stop_line, Params::stop_obligations): a car that must stop before
// the ego's road (a red light, a yield line) is expected to stop there, so an ego crossing on
// green behind the line is not warned; the same car without the obligation, or one that can no
// longer stop comfortably and does not brake (a red-light runner), still is.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "bench/paper_scenes.h"
#include "criticality/errors.h"
#include "criticality/estimator.h"
#include "criticality/scene_io.h"
#include "test_scenes.h"

namespace criticality {
namespace {

// The ego at 50 km/h on a straight three-lane road (own lane |y| <= 1.75 m). A car from the
// right at 8 m/s, heading across the road, whose path meets the ego's about 1.4 s from now; the
// line where it must stop lies 2.5 m right of the ego's lane centre, `to_line` ahead of its
// front bumper.
Scene CrossingScene(double to_line, double crossing_accel = 0.0) {
  Scene s;
  s.ego.state.speed_mps = 13.9;
  s.ego.lanes = bench::StraightThreeLanes();
  Vehicle v;
  v.id = "crossing";
  v.length_m = 4.5;
  v.width_m = 1.8;
  v.state.x_m = 21.5;
  v.state.y_m = -2.5 - to_line - 0.5 * v.length_m;
  v.state.yaw_rad = 0.5 * 3.14159265358979;
  v.state.speed_mps = 8.0;
  v.state.accel_mps2 = crossing_accel;
  s.vehicles.push_back(v);
  return s;
}

using testing::PCollision;

TEST(StopObligation, RedLightAheadOfACrossingCarMakesTheCrossingSafe) {
  // 9.5 m to the line at 8 m/s: 3.4 m/s^2 stops it, comfortable (AASHTO).
  Scene free_to_go = CrossingScene(9.5);
  const double p_free = PCollision(free_to_go);
  Scene red = free_to_go;
  red.vehicles[0].stop_line = StopLine{StopLine::Reason::kRedLight, 9.5};
  const double p_red = PCollision(red);
  Scene yield = free_to_go;
  yield.vehicles[0].stop_line = StopLine{StopLine::Reason::kYield, 9.5};
  // Above the driver's warning release (0.8 x 0.9): the ego's own braking hypotheses avoid it.
  EXPECT_GT(p_free, 0.8) << "without an obligation the crossing car is a likely collision";
  EXPECT_LT(p_red, 0.1) << "with a red light it stops before the ego's road";
  EXPECT_DOUBLE_EQ(PCollision(yield), p_red) << "a yield line obliges it in the same way";
  // The reference backend builds the same problem.
  EXPECT_NEAR(PCollision(red, Params{}, Backend::kReference), p_red, 1e-9);
}

TEST(StopObligation, ViolationProbabilityIsTheWeightOfDrivingOn) {
  Scene red = CrossingScene(9.5);
  red.vehicles[0].stop_line = StopLine{StopLine::Reason::kRedLight, 9.5};
  Params always_violates;
  always_violates.stop_violation_probability = 1.0;
  // Acting on the line at once (the default) starts the violators' hypotheses from the
  // stopping deceleration too: without it they are those of a car without a line.
  always_violates.stop_obligation_at_once = false;
  EXPECT_NEAR(PCollision(red, always_violates), PCollision(CrossingScene(9.5)), 0.05)
      << "violating with certainty: as without a line (but for the one braking profile that "
         "the stopping profile replaced)";
  Params twice;
  twice.stop_violation_probability = 2.0 * Params{}.stop_violation_probability;
  EXPECT_GT(PCollision(red, twice), PCollision(red));
}

TEST(StopObligation, ARunnerThatCannotStopComfortablyAndDoesNotBrakeStaysCritical) {
  // 5 m to the line at 8 m/s needs 6.4 m/s^2: a driver who does not brake now will not stop.
  Scene runner = CrossingScene(5.0);
  const double p_free = PCollision(runner);
  runner.vehicles[0].stop_line = StopLine{StopLine::Reason::kRedLight, 5.0};
  EXPECT_GT(p_free, 0.8);
  EXPECT_DOUBLE_EQ(PCollision(runner), p_free);
  // The same car braking at 5 m/s^2 already (at least half the 6.4 needed) complies.
  Scene braking = CrossingScene(5.0, -5.0);
  braking.vehicles[0].stop_line = StopLine{StopLine::Reason::kRedLight, 5.0};
  EXPECT_LT(PCollision(braking), 0.1);
}

TEST(StopObligation, ALineTooCloseToStopAtAfterTheLatencyIsStillKeptWhereTheCarActsAtOnce) {
  // As traced on a SUMO grid (bench/RESULTS.md, eighteenth stop): a car accelerating at +2.1
  // m/s^2 at 5 m/s towards its yield line 3.9 m ahead. From now 3.2 m/s^2 stops it there
  // (comfortable: the obligation is credible), but held at +2.1 m/s^2 through the 0.2 s latency
  // and ramped down at the jerk limit it overshoots the line whatever it then brakes.
  Scene late = CrossingScene(3.9, 2.1);
  late.vehicles[0].state.speed_mps = 5.0;
  // SUMO's passenger car type: its emergency deceleration is the hardest profile.
  late.vehicles[0].type.accel_mps2 = 2.6;
  late.vehicles[0].type.decel_mps2 = 4.5;
  late.vehicles[0].type.emergency_decel_mps2 = 9.0;
  const double p_free = PCollision(late);
  late.vehicles[0].stop_line = StopLine{StopLine::Reason::kYield, 3.9};
  Params held;
  held.stop_obligation_at_once = false;
  EXPECT_GT(p_free, 0.8) << "without a line the car crosses in front of the ego";
  EXPECT_DOUBLE_EQ(PCollision(late, held), p_free)
      << "held through the latency no profile stops it at the line: the line is dropped";
  EXPECT_LT(PCollision(late), 0.1) << "acting on the line from now, it stops there";
  // The reference backend builds the same problem.
  EXPECT_NEAR(PCollision(late, Params{}, Backend::kReference), PCollision(late), 1e-9);
}

TEST(StopObligation, AnotherVehicleStopsAsHardAsItsTypeDoesAsAMatterOfCourse) {
  // The same car a step later: 5.3 m/s, 3.4 m to the line, needs 4.1 m/s^2 (more than the
  // comfortable 3.4) and does not brake yet. SUMO's drivers brake up to their type's decel
  // (4.5 m/s^2 for a passenger car) to stop at a line.
  Scene later = CrossingScene(3.4, 2.3);
  later.vehicles[0].state.speed_mps = 5.3;
  later.vehicles[0].type.accel_mps2 = 2.6;
  later.vehicles[0].type.emergency_decel_mps2 = 9.0;
  const double p_free = PCollision(later);
  later.vehicles[0].stop_line = StopLine{StopLine::Reason::kYield, 3.4};
  EXPECT_GT(p_free, 0.8);
  EXPECT_DOUBLE_EQ(PCollision(later), p_free)
      << "a type that brakes no harder than comfortable: the obligation is not credible";
  later.vehicles[0].type.decel_mps2 = 4.5;
  EXPECT_LT(PCollision(later), 0.1) << "its type brakes at 4.5 m/s^2: it stops at the line";
  Params held;
  held.stop_obligation_at_once = false;
  EXPECT_DOUBLE_EQ(PCollision(later, held), p_free) << "without the rule: only 3.4 m/s^2 counts";
}

TEST(StopObligation, ACarAlreadyStoppingBeforeTheLineKeepsItsOwnBraking) {
  // Braking at 5 m/s^2 from 8 m/s stops it within 6.4 m: before a line 6.6 m ahead. Its
  // current acceleration complies; the gentler stop exactly at the line is not made the
  // reference (it would bring the car closer to the ego than it is going).
  Scene braking = CrossingScene(6.6, -5.0);
  const double p_free = PCollision(braking);
  braking.vehicles[0].stop_line = StopLine{StopLine::Reason::kRedLight, 6.6};
  EXPECT_EQ(PCollision(braking), p_free) << p_free;
}

TEST(StopObligation, PaperLiteralAndSwitchedOffIgnoreTheLine) {
  Scene red = CrossingScene(9.5);
  red.vehicles[0].stop_line = StopLine{StopLine::Reason::kRedLight, 9.5};
  Params off;
  off.stop_obligations = false;
  EXPECT_DOUBLE_EQ(PCollision(red, off), PCollision(CrossingScene(9.5)));
  const Params literal = ParamsPreset("paper-literal");
  EXPECT_DOUBLE_EQ(PCollision(red, literal), PCollision(CrossingScene(9.5), literal));
}

TEST(StopObligation, SceneFilesKeepTheLine) {
  Scene red = CrossingScene(9.5);
  red.vehicles[0].stop_line = StopLine{StopLine::Reason::kYellowLight, 9.5};
  std::stringstream file;
  WriteScene(file, red);
  const Scene back = ReadScene(file);
  ASSERT_TRUE(back.vehicles[0].stop_line.has_value());
  EXPECT_EQ(back.vehicles[0].stop_line->reason, StopLine::Reason::kYellowLight);
  EXPECT_EQ(back.vehicles[0].stop_line->distance_m, 9.5);
  // After the ego line it is the ego's (Ego::stop_line); after a pedestrian it is an error.
  std::stringstream ego("criticality-scene 1\nego e 0 0 0 0 0 0 0 4.5 1.8 -\nstop red 3\n");
  const Scene own = ReadScene(ego);
  ASSERT_TRUE(own.ego.stop_line.has_value());
  EXPECT_EQ(own.ego.stop_line->distance_m, 3.0);
  std::stringstream bad(
      "criticality-scene 1\nego e 0 0 0 0 0 0 0 4.5 1.8 -\npedestrian p 0 0 0 1 0 0 0 .5 .5\n"
      "stop red 3\n");
  EXPECT_THROW(ReadScene(bad), InputError) << "a stop line belongs to a vehicle or the ego";
}

TEST(StopObligation, NegativeDistanceIsRejected) {
  Scene red = CrossingScene(9.5);
  red.vehicles[0].stop_line = StopLine{StopLine::Reason::kRedLight, -1.0};
  EXPECT_THROW(PCollision(red), InputError);
}

// Params::ego_stop_obligations: the ego at 8 m/s must yield at a line 10 m ahead (3.2 m/s^2
// stops it there, comfortable), and a car stands 15 m beyond its front. Keeping its speed, the
// ego hits the car within the horizon; complying, its reference stops at the line. A line
// 2 m ahead (16 m/s^2 needed, not braking) is no credible stop and changes nothing; the
// option is off by default.
TEST(StopObligation, TheEgosOwnCredibleStopIsItsReference) {
  Scene s;
  s.ego.lanes = bench::StraightThreeLanes();
  s.ego.state.speed_mps = 8.0;
  Vehicle standing;
  standing.id = "standing";
  standing.length_m = 4.5;
  standing.state.x_m = 0.5 * s.ego.length_m + 15.0 + 0.5 * standing.length_m;
  s.vehicles.push_back(standing);
  Params on;
  on.ego_stop_obligations = true;
  const Result free_ego = Estimator(on).Estimate(s);
  s.ego.stop_line = StopLine{StopLine::Reason::kYield, 10.0};
  const Result complying = Estimator(on).Estimate(s);
  const Result default_params = Estimator(Params{}).Estimate(s);
  s.ego.stop_line->distance_m = 2.0;
  const Result too_late = Estimator(on).Estimate(s);
  EXPECT_GT(free_ego.p_reference, 0.9);
  EXPECT_LT(complying.p_reference, 0.05);
  EXPECT_LT(complying.p_collision, free_ego.p_collision);
  EXPECT_EQ(default_params.p_collision, free_ego.p_collision);
  EXPECT_EQ(too_late.p_collision, free_ego.p_collision);
}

}  // namespace
}  // namespace criticality
