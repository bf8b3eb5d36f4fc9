// Every fast path is checked against the plain reference on the same inputs: the CPU fast path
// must give the same pair matrix (colliding pairs and first-collision steps) and p_cra.
#include <gtest/gtest.h>

#include "bench/paper_scenes.h"
#include "criticality/estimator.h"
#include "test_scenes.h"

namespace criticality {
namespace {

// Returns the number of colliding pairs, so callers can check their scenes exercise collisions.
size_t ExpectSameResult(const Scene& scene, const std::string& what) {
  EstimatorOptions ref_opt, cpu_opt;
  ref_opt.backend = Backend::kReference;
  ref_opt.keep_pair_matrix = cpu_opt.keep_pair_matrix = true;
  cpu_opt.backend = Backend::kCpu;
  cpu_opt.threads = 2;
  Estimator reference(Params{}, ref_opt), cpu(Params{}, cpu_opt);
  const Result a = reference.Estimate(scene);
  const Result b = cpu.Estimate(scene);
  EXPECT_EQ(a.first_collision_step.size(), b.first_collision_step.size()) << what;
  if (a.first_collision_step.size() != b.first_collision_step.size()) return 0;
  size_t differing = 0;
  for (size_t k = 0; k < a.first_collision_step.size(); ++k) {
    differing += a.first_collision_step[k] != b.first_collision_step[k];
  }
  EXPECT_EQ(differing, 0u) << what;
  EXPECT_NEAR(a.p_collision, b.p_collision, 1e-9) << what;
  EXPECT_EQ(a.collision_free_ego_trajectories, b.collision_free_ego_trajectories) << what;
  size_t colliding = 0;
  for (std::int16_t s : a.first_collision_step) colliding += s > 0;
  return colliding;
}

TEST(BackendsAgree, PaperSceneS1) { EXPECT_GT(ExpectSameResult(bench::PaperSceneS1(), "S1"), 0u); }

TEST(BackendsAgree, PaperSceneS2) { EXPECT_GT(ExpectSameResult(bench::PaperSceneS2(), "S2"), 0u); }

TEST(BackendsAgree, SeededRandomScenes) {
  // Dense and sparse, empty ones included, with pedestrians, crossing and oncoming traffic.
  int with_collisions = 0, without = 0;
  for (unsigned seed = 1; seed <= 10; ++seed) {
    const int max_objects = seed <= 8 ? 4 : 0;  // seeds 9 and 10: the ego alone
    const size_t colliding =
        ExpectSameResult(testing::RandomScene(seed, max_objects, max_objects / 2, seed % 2 == 0),
                         "seed " + std::to_string(seed));
    (colliding > 0 ? with_collisions : without) += 1;
  }
  // The family must exercise both outcomes, or agreement would prove little.
  EXPECT_GE(with_collisions, 3);
  EXPECT_GE(without, 1);
}

}  // namespace
}  // namespace criticality
