// The SIMD fast path (cpu/sibling_steps.h, EstimatorOptions::simd) against the scalar code it
// mirrors: lanes follow core::SimulateVehicleSteps to within rounding (vector sin/cos/atan are
// within a few ulp of libm), and the pair matrix it leads to equals the reference's except for
// contacts within a millimetre: every first-collision step lies between the reference's with
// every box grown by 1 mm and with every box shrunk by 1 mm.
#include "cpu/sibling_steps.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "../test_scenes.h"
#include "bench/discrimination_scenes.h"
#include "bench/paper_scenes.h"
#include "cpu/cpu_backend.h"
#include "cpu/reference_backend.h"
#include "criticality/estimator.h"
#include "src/problem.h"

namespace criticality {
namespace {

using internal::BuildProblem;
using internal::Problem;

// Max |difference| of poses between SimulateSiblingSteps and SimulateVehicleSteps for the given
// paths of every profile over the whole horizon, from the initial state.
double MaxPoseDifference(const Problem& pb, const core::HypothesisSet& h,
                         const std::vector<int>& paths) {
  const int steps = pb.sim.n_steps;
  double worst = 0.0;
  for (int profile = 0; profile < h.n_profiles; ++profile) {
    internal::SiblingSpan span =
        internal::SpanOf(h, pb.sim, profile, 0, steps, static_cast<int>(paths.size()));
    std::vector<std::vector<double>> x(paths.size(), std::vector<double>(steps)), y = x, yaw = x,
                                                                                  c = x, sn = x;
    std::vector<double> rx(steps), ry(steps), ryaw(steps);
    for (size_t l = 0; l < paths.size(); ++l) {
      internal::SetLane(&span, static_cast<int>(l), paths[l],
                        core::InitialSimulationState(h, pb.sim), x[l].data(), y[l].data(),
                        yaw[l].data(), c[l].data(), sn[l].data());
    }
    internal::SimulateSiblingSteps(&span);
    for (size_t l = 0; l < paths.size(); ++l) {
      core::SimulationState st = core::InitialSimulationState(h, pb.sim);
      core::SimulateVehicleSteps(h, pb.sim, profile, paths[l], 0, steps, &st, rx.data(), ry.data(),
                                 ryaw.data());
      for (int n = 0; n < steps; ++n) {
        worst = std::max({worst, std::fabs(x[l][n] - rx[n]), std::fabs(y[l][n] - ry[n]),
                          std::fabs(yaw[l][n] - ryaw[n])});
        // the heading's cos/sin, from the local yaw's turned by the frame's
        worst = std::max({worst, std::fabs(c[l][n] - std::cos(ryaw[n])),
                          std::fabs(sn[l][n] - std::sin(ryaw[n]))});
      }
      worst = std::max(worst, std::fabs(span.state[l].s.v - st.s.v));
      EXPECT_EQ(span.state[l].instant, st.instant);
    }
  }
  return worst;
}

// Every path of each other vehicle the SIMD path takes against the scalar step; the number of
// vehicles checked.
int ExpectOthersFollowTheScalarStep(const Problem& pb, const std::string& what) {
  int checked = 0;
  for (const core::HypothesisSet& h : pb.cos) {
    if (!internal::SiblingStepsApply(h, pb.sim)) continue;
    std::vector<int> paths;
    for (int l = 0; l < h.n_paths; ++l) paths.push_back(l);
    EXPECT_LT(MaxPoseDifference(pb, h, paths), 1e-9) << what << " other vehicle";
    ++checked;
  }
  return checked;
}

std::vector<int> SpreadPaths(const core::HypothesisSet& h, int count) {
  std::vector<int> paths;
  for (int l = 0; l < count; ++l) paths.push_back((l * 97) % h.n_paths);
  return paths;
}

TEST(SiblingSteps, AppliesToVehiclesWithTheControllerOn) {
  const Problem pb = BuildProblem(bench::PaperSceneS1(), Params{});
  EXPECT_TRUE(internal::SiblingStepsApply(pb.ego, pb.sim));
  ASSERT_FALSE(pb.cos.empty());
  EXPECT_EQ(pb.cos[0].model, core::MotionModelKind::kOneTrack);
  EXPECT_TRUE(internal::SiblingStepsApply(pb.cos[0], pb.sim));
  Scene with_pedestrian = testing::RandomScene(2, 0, 2, false);
  const Problem pp = BuildProblem(with_pedestrian, Params{});
  ASSERT_FALSE(pp.cos.empty());
  EXPECT_EQ(pp.cos[0].model, core::MotionModelKind::kPedestrian);
  EXPECT_FALSE(internal::SiblingStepsApply(pp.cos[0], pp.sim));
  Params open_loop;
  open_loop.lateral_controller = false;
  const Problem ol = BuildProblem(bench::PaperSceneS1(), open_loop);
  EXPECT_FALSE(internal::SiblingStepsApply(ol.ego, ol.sim));
  EXPECT_NE(std::string(internal::SiblingStepsTarget()), "");
}

TEST(SiblingSteps, LanesFollowTheScalarStepWithinRounding) {
  std::vector<Scene> scenes = {bench::PaperSceneS1(), bench::PaperSceneS2()};
  for (unsigned seed = 1; seed <= 8; ++seed)
    scenes.push_back(testing::RandomScene(seed, 4, 2, seed % 2));
  // Slow egos: braking profiles cross the seam speed (the kinematic model, run lane by lane).
  Scene slow = bench::PaperSceneS1();
  slow.ego.state.speed_mps = 2.6;
  scenes.push_back(slow);
  for (const bench::DiscriminationScene& d : bench::DiscriminationScenes())
    scenes.push_back(d.scene);
  int checked = 0, checked_others = 0;
  for (const Params& params : {Params{}, ParamsPreset("paper-literal")}) {
    for (const Scene& s : scenes) {
      const Problem pb = BuildProblem(s, params);
      if (!internal::SiblingStepsApply(pb.ego, pb.sim)) continue;
      // 1, 3, 7 (one AVX-512 register, two AVX2 ones) and 11 lanes (more than one register).
      for (int count : {1, 3, 7, 11}) {
        EXPECT_LT(MaxPoseDifference(pb, pb.ego, SpreadPaths(pb.ego, count)), 1e-9)
            << s.ego.id << " " << count << " lanes";
      }
      ++checked;
      // The other vehicles: every path of each profile (one-track, friction-limited by default).
      for (const core::HypothesisSet& h : pb.cos) {
        if (!internal::SiblingStepsApply(h, pb.sim)) continue;
        std::vector<int> paths;
        for (int l = 0; l < h.n_paths; ++l) paths.push_back(l);
        EXPECT_LT(MaxPoseDifference(pb, h, paths), 1e-9) << s.ego.id << " other vehicle";
        ++checked_others;
      }
    }
  }
  EXPECT_GE(checked, 40);
  EXPECT_GE(checked_others, 100);
}

// Held poses (Params::collisions_at_world_steps with SUMO's 1 s and 0.1 s Euler steps): the
// lanes store the held pose between the world's steps as core::HoldPose does, across the spans
// of a tree (the held pose travels in the lane's state).
TEST(SiblingSteps, HeldPosesFollowTheScalarStepWithinRounding) {
  Params at_steps;
  at_steps.collisions_at_world_steps = true;
  int checked = 0;
  for (double world_step : {1.0, 0.1}) {
    for (unsigned seed = 1; seed <= 6; ++seed) {
      Scene s = testing::RandomScene(seed, 4, 0, seed % 2);
      s.euler_update_step_s = world_step;
      const Problem pb = BuildProblem(s, at_steps);
      ASSERT_EQ(pb.ego.pose_hold_steps, world_step == 1.0 ? 50 : 5);
      for (int count : {1, 7, 11})
        EXPECT_LT(MaxPoseDifference(pb, pb.ego, SpreadPaths(pb.ego, count)), 1e-9) << seed;
      checked += ExpectOthersFollowTheScalarStep(pb, "seed " + std::to_string(seed));
    }
  }
  EXPECT_GE(checked, 12);
  // The whole estimate, tree and all: the SIMD path agrees with the scalar one.
  EstimatorOptions scalar_opt;
  scalar_opt.simd = false;
  Estimator scalar(at_steps, scalar_opt), simd(at_steps);
  for (unsigned seed = 1; seed <= 6; ++seed) {
    Scene s = testing::RandomScene(seed, 4, 2, seed % 2);
    s.euler_update_step_s = 1.0;
    const Result a = scalar.Estimate(s), b = simd.Estimate(s);
    EXPECT_NEAR(a.p_collision, b.p_collision, 1e-6) << seed;
    EXPECT_NEAR(a.unavoidability, b.unavoidability, 1e-6) << seed;
  }
}

// Bodies on their path (Scene::bodies_on_path): the chord's shift and the course's heading in
// the lanes as in core::StorePose, on scenes whose vehicles turn.
TEST(SiblingSteps, BodiesOnTheirPathFollowTheScalarStepWithinRounding) {
  int checked = 0;
  double moved = 0.0;  // how far the switch moves some pose: or the check would prove little
  for (unsigned seed = 1; seed <= 8; ++seed) {
    Scene s = testing::RandomScene(seed, 4, 0, seed % 2);
    s.ego.state.yaw_rate_radps = 0.3;
    for (Vehicle& v : s.vehicles) v.state.yaw_rate_radps = -0.2;
    const Problem off = BuildProblem(s, Params{});
    s.bodies_on_path = true;
    const Problem pb = BuildProblem(s, Params{});
    for (int count : {1, 7, 11}) {
      EXPECT_LT(MaxPoseDifference(pb, pb.ego, SpreadPaths(pb.ego, count)), 1e-9) << seed;
    }
    checked += ExpectOthersFollowTheScalarStep(pb, "seed " + std::to_string(seed));
    std::vector<double> a(pb.sim.n_steps), b = a, c = a, d = a, e = a, f = a;
    core::SimulateHypothesis(pb.ego, pb.sim, 0, 0, a.data(), b.data(), c.data());
    core::SimulateHypothesis(off.ego, off.sim, 0, 0, d.data(), e.data(), f.data());
    for (int n = 0; n < pb.sim.n_steps; ++n)
      moved = std::max(moved, std::hypot(a[n] - d[n], b[n] - e[n]));
  }
  EXPECT_GE(checked, 8);
  EXPECT_GT(moved, 0.1);
}

TEST(SiblingSteps, CosSinMatchesLibm) {
  std::vector<double> a;
  for (int k = 0; k < 1003; ++k) a.push_back(-40.0 + 0.0797 * k);  // odd length: a tail
  std::vector<double> c(a.size()), s(a.size());
  internal::CosSin(a.data(), a.size(), c.data(), s.data());
  for (size_t k = 0; k < a.size(); ++k) {
    EXPECT_NEAR(c[k], std::cos(a[k]), 4e-16) << a[k];
    EXPECT_NEAR(s[k], std::sin(a[k]), 4e-16) << a[k];
  }
}

// Vectors whose angles are all within 0.35 rad take SinCos's Taylor series: it must be as
// exact as libm, within 2 ulps (a series cut one term short is off by 4 ulps at 0.35).
TEST(SiblingSteps, CosSinOfSmallAnglesIsWithinTwoUlpsOfLibm) {
  std::vector<double> a;
  for (int k = 0; k < 64; ++k) a.push_back(-0.35 + 0.7 * k / 63.0);  // whole vectors of 8, 16
  for (int k = 0; k < 64; ++k) a.push_back(0.35 * std::pow(0.5, k % 32) * (k < 32 ? 1 : -1));
  std::vector<double> c(a.size()), s(a.size());
  internal::CosSin(a.data(), a.size(), c.data(), s.data());
  auto ulp = [](double x) { return std::nextafter(std::fabs(x), 2.0) - std::fabs(x); };
  for (size_t k = 0; k < a.size(); ++k) {
    EXPECT_LE(std::fabs(c[k] - std::cos(a[k])), 2 * ulp(std::cos(a[k]))) << a[k];
    EXPECT_LE(std::fabs(s[k] - std::sin(a[k])), 2 * ulp(std::sin(a[k]))) << a[k];
  }
}

// The reference's pair matrix with every box's half length and half width changed by `grow`.
std::vector<std::int16_t> ReferenceMatrix(Problem pb, double grow) {
  pb.ego.half_length += grow;
  pb.ego.half_width += grow;
  for (core::HypothesisSet& h : pb.cos) {
    h.half_length += grow;
    h.half_width += grow;
  }
  ReferenceBackend ref;
  ref.GenerateTrajectories(pb);
  std::vector<std::int16_t> m;
  ref.RecognizeCollisions(pb, &m);
  return m;
}

int Never(std::int16_t s) { return s == 0 ? std::numeric_limits<int>::max() : s; }

// Returns the pairs whose first step differs from the reference's; adds the pairs to *pairs.
size_t ExpectWithinAMillimetre(const Scene& scene, const Params& params, const std::string& what,
                               size_t* pairs) {
  const Problem pb = BuildProblem(scene, params);
  const std::vector<std::int16_t> exact = ReferenceMatrix(pb, 0.0);
  const std::vector<std::int16_t> grown = ReferenceMatrix(pb, 1e-3);
  const std::vector<std::int16_t> shrunk = ReferenceMatrix(pb, -1e-3);
  CpuBackend simd(2, true);
  simd.GenerateTrajectories(pb);
  std::vector<std::int16_t> fast;
  simd.RecognizeCollisions(pb, &fast);
  EXPECT_EQ(fast.size(), exact.size()) << what;
  *pairs += exact.size();
  size_t outside = 0, differing = 0;
  for (size_t k = 0; k < fast.size() && k < exact.size(); ++k) {
    differing += fast[k] != exact[k];
    outside += Never(fast[k]) < Never(grown[k]) || Never(fast[k]) > Never(shrunk[k]);
  }
  EXPECT_EQ(outside, 0u) << what;
  return differing;
}

TEST(SiblingSteps, PairMatrixIsTheReferencesUpToGrazingContacts) {
  size_t differing = 0, pairs = 0;
  // (S2 is left out: its three reference matrices would triple the quick run's time here)
  std::vector<std::pair<std::string, Scene>> scenes = {{"S1", bench::PaperSceneS1()}};
  for (unsigned seed = 1; seed <= 8; ++seed)
    scenes.push_back({"seed " + std::to_string(seed), testing::RandomScene(seed, 4, 2, seed % 2)});
  for (const bench::DiscriminationScene& d : bench::DiscriminationScenes()) {
    if (d.name == "stopped-car-ttc-1.50" || d.name == "cut-in-ttc-1.0" ||
        d.name == "junction-car-crosses-ttc-1.3" || d.name == "pedestrian-crosses-ttc-1.2")
      scenes.push_back({d.name, d.scene});
  }
  Params coarse;  // at 0.05 s steps the stopped car at TTC 1.50 s is touched exactly at a step
  coarse.step_s = 0.05;
  for (const Params& params : {Params{}, coarse}) {
    for (const auto& [name, scene] : scenes) {
      differing += ExpectWithinAMillimetre(scene, params, name, &pairs);
    }
  }
  EXPECT_GT(pairs, 500000u);
  EXPECT_LT(differing, pairs / 1000);  // grazing contacts are rare
}

// |dp| <= 1e-6 on the paper's scenes and the random family (issue 23's bound), and the SIMD
// path is deterministic: the same scene twice gives the same bits.
TEST(SiblingSteps, ProbabilitiesAgreeAndRepeat) {
  std::vector<Scene> scenes = {bench::PaperSceneS1(), bench::PaperSceneS2()};
  for (unsigned seed = 1; seed <= 10; ++seed)
    scenes.push_back(testing::RandomScene(seed, seed <= 8 ? 4 : 0, 2, seed % 2 == 0));
  EstimatorOptions scalar_opt, simd_opt;
  scalar_opt.simd = false;
  scalar_opt.threads = simd_opt.threads = 2;
  Estimator scalar(Params{}, scalar_opt), simd(Params{}, simd_opt);
  int warned = 0;
  for (const Scene& s : scenes) {
    const Result a = scalar.Estimate(s), b = simd.Estimate(s), c = simd.Estimate(s);
    EXPECT_NEAR(a.p_collision, b.p_collision, 1e-6);
    EXPECT_NEAR(a.p_reference, b.p_reference, 1e-6);
    EXPECT_NEAR(a.unavoidability, b.unavoidability, 1e-6);
    EXPECT_EQ(b.p_collision, c.p_collision);
    EXPECT_EQ(b.first_collision_pmf, c.first_collision_pmf);
    warned += a.p_collision > 0.01;
  }
  EXPECT_GE(warned, 3);  // or agreement would prove little
}

}  // namespace
}  // namespace criticality
