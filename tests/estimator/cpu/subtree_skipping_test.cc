// Ego subtrees out of reach (cpu/cpu_backend.h, EstimatorOptions::skip_out_of_reach): a tree
// node whose reach, from its parent's end state to the horizon, meets no object is neither
// simulated nor checked. The pair matrix must be the one every path simulated gives, in scenes
// where some subtrees are skipped and others collide, and on the random family.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "bench/paper_scenes.h"
#include "cpu/cpu_backend.h"
#include "src/problem.h"
#include "../test_scenes.h"

namespace criticality {
namespace {

struct Recognition {
  std::vector<std::int16_t> matrix;
  int skipped, checked;
  int below_first;  // tree nodes below the first level, over every profile
};

Recognition Recognize(const Scene& scene, bool simd, bool skip, const Params& params = {},
                      CpuBackend* reused = nullptr) {
  const internal::Problem pb = internal::BuildProblem(scene, params);
  CpuBackend own(2, simd, skip);
  CpuBackend& backend = reused ? *reused : own;
  backend.GenerateTrajectories(pb);
  Recognition r;
  backend.RecognizeCollisions(pb, &r.matrix);
  r.skipped = backend.SkippedNodes();
  r.checked = backend.CheckedNodes();
  r.below_first = 0;
  for (int k = 1, level = pb.ego.n_lateral; k < pb.ego.n_instants; ++k) {
    level *= pb.ego.n_lateral;
    r.below_first += pb.ego.n_profiles * level;
  }
  return r;
}

size_t Colliding(const std::vector<std::int16_t>& m) {
  size_t n = 0;
  for (std::int16_t s : m) n += s > 0;
  return n;
}

// The ego at 15 m/s on a straight road, a car standing 40 m ahead in its lane: accelerating
// hypotheses reach it within 2 s, braking ones are far behind it by the last sample instant.
Scene StandingCarAhead() {
  Scene s;
  s.ego.id = "ego";
  s.ego.state.speed_mps = 15.0;
  s.ego.lanes = bench::StraightThreeLanes();
  Vehicle v;
  v.id = "standing";
  v.state.x_m = 40.0;
  v.lanes = bench::StraightThreeLanes();
  s.vehicles.push_back(v);
  return s;
}

TEST(SubtreeSkipping, SubtreesOutOfReachAreSkippedAndThePairMatrixStaysTheSame) {
  for (bool simd : {false, true}) {
    const Recognition skip = Recognize(StandingCarAhead(), simd, true);
    const Recognition all = Recognize(StandingCarAhead(), simd, false);
    EXPECT_EQ(skip.matrix, all.matrix) << "simd " << simd;
    EXPECT_GT(Colliding(skip.matrix), 0u);  // the accelerating paths hit it
    EXPECT_GT(skip.skipped, 0) << "simd " << simd;
    // Not everything: some subtrees reach the car.
    EXPECT_LT(skip.skipped, skip.below_first);
    EXPECT_GT(skip.checked, 0);
    EXPECT_EQ(all.skipped, 0);
  }
}

TEST(SubtreeSkipping, TheRandomFamilyAndThePaperScenesKeepTheirPairMatrix) {
  std::vector<Scene> scenes = {bench::PaperSceneS1(), StandingCarAhead()};
  for (unsigned seed = 1; seed <= 12; ++seed)
    scenes.push_back(testing::RandomScene(seed, 4, 2, seed % 2 == 0));
  int partly_skipped = 0;  // random scenes where some subtrees, not all, were skipped
  size_t colliding = 0;
  for (size_t k = 0; k < scenes.size(); ++k) {
    for (bool simd : {false, true}) {
      const Recognition skip = Recognize(scenes[k], simd, true);
      const Recognition all = Recognize(scenes[k], simd, false);
      EXPECT_EQ(skip.matrix, all.matrix) << "scene " << k << " simd " << simd;
      if (k >= 2 && skip.skipped > 0 && skip.skipped < skip.below_first) ++partly_skipped;
      colliding += Colliding(skip.matrix);
    }
  }
  EXPECT_GT(partly_skipped, 0);
  EXPECT_GT(colliding, 0u);
}

// Two sample instants within one step leave a tree level whose span has no step: its nodes end
// where their parents end, and the reach of their children must start there (not from a pose
// of an earlier level, stored on another path or left from an earlier scene). A standing car
// 40 m ahead, reached by some subtrees and not by others, and one backend reused over the
// scenes.
TEST(SubtreeSkipping, LevelsWithoutAStepKeepThePairMatrix) {
  const Scene scene = StandingCarAhead();
  for (bool simd : {false, true}) {
    CpuBackend reused(2, simd, true);
    for (const std::vector<double>& times :
         {std::vector<double>{0.995, 1.0, 2.0}, std::vector<double>{1.0, 1.005, 2.0},
          std::vector<double>{1.0, 1.5, 2.0}}) {
      Params params;
      params.path_sample_times_s = times;
      const Recognition skip = Recognize(scene, simd, true, params, &reused);
      const Recognition all = Recognize(scene, simd, false, params);
      EXPECT_EQ(skip.matrix, all.matrix) << "simd " << simd << " first instant " << times[0];
      EXPECT_GT(Colliding(all.matrix), 0u);
      EXPECT_GT(skip.skipped, 0) << times[0];
      EXPECT_LT(skip.skipped, skip.below_first) << times[0];
    }
  }
}

}  // namespace
}  // namespace criticality
