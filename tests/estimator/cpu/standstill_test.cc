// A standstill for good (cpu/sibling_steps.cc: a lane at speed, acceleration and yaw rate 0
// whose demand stays <= 0 stores the same pose to the end of its span) and still subtrees
// (cpu/cpu_backend.h: every path below a tree node holds one pose, so each trajectory's first
// hit is looked for once along the node's first path to the horizon): an ego waiting in a
// queue, a car coming up behind it. The poses must be the scalar step's, the pair matrix the
// reference's, with hits after the first sample instant (found beyond the still node's span)
// in every braking path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "bench/paper_scenes.h"
#include "core/chronological_risk.h"
#include "cpu/cpu_backend.h"
#include "cpu/reference_backend.h"
#include "cpu/sibling_steps.h"
#include "src/problem.h"
#include "src/risk_assessment.h"

namespace criticality {
namespace {

using internal::BuildProblem;
using internal::Problem;

// The ego stands in its lane (its SUMO acceleration `accel` as it came to rest), a car stands
// 2 m ahead of it, one comes up behind at 9 m/s (13.5 m behind its rear: at constant speed it
// hits at 1.5 s, after the first sample instant at 1 s; braking, it stops short), and one
// passes in the left lane.
Scene WaitingInAQueue(double accel) {
  Scene s;
  s.ego.id = "ego";
  s.ego.state.accel_mps2 = accel;
  s.ego.lanes = bench::StraightThreeLanes();
  Vehicle ahead;
  ahead.id = "ahead";
  ahead.state.x_m = 6.5;
  ahead.lanes = bench::StraightThreeLanes();
  Vehicle behind;
  behind.id = "behind";
  behind.state.x_m = -18.0;
  behind.state.speed_mps = 9.0;
  behind.lanes = bench::StraightThreeLanes();
  Vehicle passing;
  passing.id = "passing";
  passing.state.x_m = -12.0;
  passing.state.y_m = 3.5;
  passing.state.speed_mps = 8.0;
  passing.lanes = bench::StraightThreeLanes();
  s.vehicles = {ahead, behind, passing};
  return s;
}

TEST(Standstill, AWaitingEgoHoldsThePoseOfTheScalarStep) {
  // -0.8 m/s^2: the first step still moves it back (by a * tau^2 / 2), then it stands.
  const Problem pb = BuildProblem(WaitingInAQueue(-0.8), Params{});
  const core::HypothesisSet& h = pb.ego;
  ASSERT_TRUE(internal::SiblingStepsApply(h, pb.sim));
  const int steps = pb.sim.n_steps;
  int braking = 0, driving = 0;
  for (int profile = 0; profile < h.n_profiles; ++profile) {
    const int lanes = std::min(h.n_paths, 11);  // more than one register of 8
    internal::SiblingSpan span = internal::SpanOf(h, pb.sim, profile, 0, steps, lanes);
    std::vector<std::vector<double>> x(lanes, std::vector<double>(steps)), y = x, yaw = x, c = x,
                                     sn = x;
    for (int l = 0; l < lanes; ++l) {
      internal::SetLane(&span, l, (l * 37) % h.n_paths, core::InitialSimulationState(h, pb.sim),
                        x[l].data(), y[l].data(), yaw[l].data(), c[l].data(), sn[l].data());
    }
    internal::SimulateSiblingSteps(&span);
    const bool brakes = h.profile_target[profile] <= 0.0;
    for (int l = 0; l < lanes; ++l) {
      std::vector<double> rx(steps), ry(steps), ryaw(steps);
      core::SimulationState st = core::InitialSimulationState(h, pb.sim);
      core::SimulateVehicleSteps(h, pb.sim, profile, span.path[l], 0, steps, &st, rx.data(),
                                 ry.data(), ryaw.data());
      for (int n = 0; n < steps; ++n) {
        ASSERT_NEAR(x[l][n], rx[n], 1e-12) << "profile " << profile << " step " << n;
        ASSERT_NEAR(y[l][n], ry[n], 1e-12) << "profile " << profile << " step " << n;
        ASSERT_NEAR(yaw[l][n], ryaw[n], 1e-12) << "profile " << profile << " step " << n;
        ASSERT_NEAR(c[l][n], std::cos(ryaw[n]), 1e-12);
        ASSERT_NEAR(sn[l][n], std::sin(ryaw[n]), 1e-12);
      }
      if (brakes) {
        // The pose after the first step (moved back from the start), held bit for bit.
        EXPECT_LT(rx[0], h.X_WL.x - 1e-5) << "profile " << profile;
        for (int n = 1; n < steps; ++n) {
          ASSERT_EQ(x[l][n], x[l][0]);
          ASSERT_EQ(y[l][n], y[l][0]);
          ASSERT_EQ(c[l][n], c[l][0]);
          ASSERT_EQ(sn[l][n], sn[l][0]);
        }
        EXPECT_EQ(span.state[l].s.v, 0.0);
      } else {
        EXPECT_GT(x[l][steps - 1], x[l][0] + 1.0) << "profile " << profile;  // it drives off
      }
    }
    (brakes ? braking : driving) += 1;
  }
  EXPECT_GE(braking, 3);
  EXPECT_GE(driving, 1);
}

size_t ExpectReferenceMatrix(const Scene& scene, bool simd, int* still_nodes) {
  const Problem pb = BuildProblem(scene, Params{});
  ReferenceBackend ref;
  ref.GenerateTrajectories(pb);
  std::vector<std::int16_t> expected;
  ref.RecognizeCollisions(pb, &expected);
  CpuBackend cpu(2, simd);
  cpu.GenerateTrajectories(pb);
  std::vector<std::int16_t> got;
  cpu.RecognizeCollisions(pb, &got);
  *still_nodes = cpu.StillNodes();
  EXPECT_EQ(got, expected) << "simd " << simd;
  // Hits beyond the first sample instant on braking paths: the still scan went past the span.
  const Params defaults;
  const int n_co = pb.CoTrajectories();
  const long first_span_end = std::lround(defaults.path_sample_times_s[0] / defaults.step_s);
  size_t late_braking_hits = 0;
  for (int i = 0; i < pb.EgoTrajectories(); ++i) {
    if (pb.ego.profile_target[i / pb.ego.n_paths] > 0.0) continue;
    for (int j = 0; j < n_co; ++j)
      late_braking_hits += expected[static_cast<size_t>(i) * n_co + j] > first_span_end;
  }
  return late_braking_hits;
}

TEST(Standstill, StillSubtreesGiveTheReferencesPairMatrix) {
  for (double accel : {0.0, -0.8}) {
    for (bool simd : {false, true}) {
      int still = 0;
      const size_t late = ExpectReferenceMatrix(WaitingInAQueue(accel), simd, &still);
      EXPECT_GT(still, 0) << "accel " << accel << " simd " << simd;
      // Every braking path of the 1,500 or more is hit late by some car-behind hypothesis.
      EXPECT_GT(late, 1000u) << "accel " << accel;
    }
  }
}

// The same queue turned about the ego by `angle` and seen at SUMO's 0.1 s steps (poses held
// between the world's steps, HypothesisSet::pose_hold_steps): the ego's held pose keeps the
// cos/sin of its heading, which the SIMD step's angle addition may give a last bit apart (at
// a heading of pi it does).
Scene TurnedQueueAtWorldSteps(double angle) {
  Scene s = WaitingInAQueue(0.0);
  s.euler_update_step_s = 0.1;
  s.ego.state.yaw_rad = angle;
  const double c = std::cos(angle), sn = std::sin(angle);
  for (Vehicle& v : s.vehicles) {
    const double x = v.state.x_m, y = v.state.y_m;
    v.state.x_m = c * x - sn * y;
    v.state.y_m = sn * x + c * y;
    v.state.yaw_rad += angle;
  }
  return s;
}

// A waiting ego's braking subtrees are still whatever its heading, with held poses too: with
// the SIMD step's last-bit cos/sin stored after a held first pose, none was, and each of its
// braking profiles walked its whole tree against every car.
TEST(Standstill, AWaitingEgoIsStillAtHeldPosesWhateverItsHeading) {
  for (double angle : {-core::kPi, 2.0, 0.0}) {
    const Scene scene = TurnedQueueAtWorldSteps(angle);
    const Problem pb = BuildProblem(scene, Params{});
    ASSERT_GT(pb.ego.pose_hold_steps, 1);
    int still = 0;
    const size_t late = ExpectReferenceMatrix(scene, true, &still);
    // Every node of every braking profile's tree (it stands from the first step), no other.
    int braking = 0, nodes = 0;
    for (int profile = 0; profile < pb.ego.n_profiles; ++profile)
      braking += pb.ego.profile_target[profile] <= 0.0;
    for (int k = 0, level = 1; k < pb.ego.n_instants; ++k) nodes += (level *= pb.ego.n_lateral);
    EXPECT_EQ(still, braking * nodes) << "angle " << angle;
    EXPECT_GT(late, 1000u) << "angle " << angle;
  }
}

// An ego that brakes to a standstill within the horizon (6 m/s: the hardest profiles stop
// within 0.7 s) has still nodes below the first level; one too fast to stop (20 m/s) has
// none. Both give the reference's matrix.
TEST(Standstill, OnlyPathsThatComeToRestAreStill) {
  for (double speed : {6.0, 20.0}) {
    Scene moving = WaitingInAQueue(0.0);
    moving.ego.state.speed_mps = speed;
    moving.vehicles[0].state.x_m = 30.0;
    int still = -1;
    ExpectReferenceMatrix(moving, true, &still);
    if (speed < 10.0) {
      EXPECT_GT(still, 0);
    } else {
      EXPECT_EQ(still, 0);
    }
  }
}

// The risk stage splits a row equal to the row before it (the paths of a still subtree) as
// that row: every row's collision probability, the first-collision pmf and the objects'
// contributions must be what core::SplitEgoRisk gives row by row, summed in row order.
TEST(Standstill, EqualRowsOfThePairMatrixGetEachRowsSplit) {
  const Problem pb = BuildProblem(WaitingInAQueue(0.0), Params{});
  CpuBackend cpu(1, true);
  cpu.GenerateTrajectories(pb);
  std::vector<std::int16_t> m;
  cpu.RecognizeCollisions(pb, &m);
  const int n_ego = pb.EgoTrajectories(), n_co = pb.CoTrajectories(), steps = pb.Steps();
  const int n_obj = static_cast<int>(pb.cos.size());
  Result r;
  Params params;
  params.max_escape_routes = 0;
  internal::AssessRisk(pb, params, m.data(), 1, &r);
  std::vector<int> histogram(steps + 1), events(n_co);
  std::vector<double> contribution(n_co), hit_mass(n_obj), by_step(steps), by_object(n_obj);
  std::vector<double> pmf(steps, 0.0), share(n_obj, 0.0);
  double p = 0.0;
  int equal_to_the_last = 0;
  for (int i = 0; i < n_ego; ++i) {
    const std::int16_t* row = &m[static_cast<size_t>(i) * n_co];
    int n_events = 0;
    const double col = core::SplitEgoRisk(row, n_co, steps, n_obj, pb.co_probability.data(),
                                          pb.co_object_of.data(), histogram.data(), events.data(),
                                          contribution.data(), hit_mass.data(), by_step.data(),
                                          by_object.data(), &n_events);
    if (n_events == 0) continue;
    ASSERT_EQ(r.ego_collision_probability[i], col) << "row " << i;
    const double w = pb.ego_probability[i];
    p += w * col;
    for (int n = 0; n < steps; ++n) {
      if (by_step[n] != 0.0) pmf[n] += w * by_step[n];
    }
    for (int o = 0; o < n_obj; ++o) {
      if (by_object[o] != 0.0) share[o] += w * by_object[o];
    }
    equal_to_the_last += i > 0 && std::equal(row, row + n_co, row - n_co);
  }
  EXPECT_GT(equal_to_the_last, 1000);  // the still subtrees' rows
  EXPECT_GT(p, 0.0);
  EXPECT_EQ(r.p_collision, p);
  EXPECT_EQ(r.first_collision_pmf, pmf);
  for (int o = 0; o < n_obj; ++o) EXPECT_EQ(r.objects[o].contribution, share[o]) << o;
}

}  // namespace
}  // namespace criticality
