// Hypothesis set-up and scoring (paper Sec. IV-B-2, IV-D-1): probabilities per object sum to 1,
// the reference hypothesis is the most probable, penalties act as documented.
#include "src/problem.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

#include "bench/paper_scenes.h"
#include "core/hypothesis_set.h"
#include "test_scenes.h"

namespace criticality::internal {
namespace {

TEST(Problem, ProbabilitiesOfEachObjectSumToOne) {
  for (unsigned seed = 11; seed < 19; ++seed) {
    const Scene scene = testing::RandomScene(seed, 5, 3, false);
    const Problem pb = BuildProblem(scene, Params{});
    EXPECT_NEAR(std::accumulate(pb.ego_probability.begin(), pb.ego_probability.end(), 0.0), 1.0,
                1e-12);
    for (size_t o = 0; o < pb.cos.size(); ++o) {
      double sum = 0.0;
      for (int j = pb.co_offset[o]; j < pb.co_offset[o + 1]; ++j) {
        EXPECT_GT(pb.co_probability[j], 0.0);
        sum += pb.co_probability[j];
      }
      EXPECT_NEAR(sum, 1.0, 1e-12) << "seed " << seed << " object " << o;
    }
  }
}

TEST(Problem, ReferenceHypothesisIsTheMostProbable) {
  // Cruising (zero slip) along the own lane's centre at every sample instant.
  const Problem pb = BuildProblem(bench::PaperSceneS1(), Params{});
  const auto best = std::max_element(pb.ego_probability.begin(), pb.ego_probability.end());
  const int i = static_cast<int>(best - pb.ego_probability.begin());
  EXPECT_EQ(pb.ego.profile_target[i / pb.ego.n_paths], 0.0);
  for (int k = 0; k < pb.ego.n_instants; ++k)
    EXPECT_EQ(core::SectionOfPath(pb.ego, i % pb.ego.n_paths, k), 3);
}

TEST(Problem, PaperLiteralPenalisesSectionChanges) {
  Params p = ParamsPreset("paper-literal");
  const Problem pb = BuildProblem(bench::PaperSceneS1(), p);
  const int cruise = p.profiles - 2;  // the zero profile
  auto prob = [&](int s0, int s1, int s2) {
    return pb.ego_probability[cruise * pb.ego.n_paths + s0 * 49 + s1 * 7 + s2];
  };
  // Straight into the left lane beats left-then-back (same mean offset at the samples after).
  EXPECT_GT(prob(5, 5, 5), prob(5, 3, 5));
  p.complexity_penalty = 0.0;
  const Problem flat = BuildProblem(bench::PaperSceneS1(), p);
  const double ratio_flat = flat.ego_probability[cruise * 343 + 5 * 49 + 3 * 7 + 5] /
                            flat.ego_probability[cruise * 343 + 5 * 49 + 5 * 7 + 5];
  const double ratio = prob(5, 3, 5) / prob(5, 5, 5);
  EXPECT_LT(ratio, ratio_flat);
}

TEST(Problem, PaperLiteralProfilesForEgoAreSlipsAndForOthersAccelerations) {
  const Problem pb = BuildProblem(bench::PaperSceneS1(), ParamsPreset("paper-literal"));
  EXPECT_EQ(pb.ego.model, core::MotionModelKind::kTwoTrack);
  EXPECT_FALSE(pb.ego.force_profiles);
  EXPECT_EQ(pb.ego.profile_target[0], -0.1);
  EXPECT_EQ(pb.ego.profile_target[5], 0.1);
  EXPECT_EQ(pb.cos[0].model, core::MotionModelKind::kOneTrack);
  EXPECT_EQ(pb.cos[0].profile_target[0], -9.7);
  EXPECT_EQ(pb.cos[0].profile_target[5], 9.7);
}

}  // namespace
}  // namespace criticality::internal
