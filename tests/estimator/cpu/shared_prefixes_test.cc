// The CPU backend simulates a section-tree node once, on its group's first path; the other
// paths of the group get the shared prefix only when EgoTrajectories() asks for it
// (cpu/cpu_backend.h). Every path's poses must then be the reference's, also after the backend
// has been reused for another scene.
#include <gtest/gtest.h>

#include <vector>

#include "bench/paper_scenes.h"
#include "cpu/cpu_backend.h"
#include "cpu/reference_backend.h"
#include "src/problem.h"
#include "../test_scenes.h"

namespace criticality {
namespace {

// The scalar fast path's poses are the reference's bit for bit (cpu/cpu_backend.h).
void ExpectSamePoses(const internal::TrajectoryStore& a, const internal::TrajectoryStore& b) {
  ASSERT_EQ(a.trajectories, b.trajectories);
  ASSERT_EQ(a.steps, b.steps);
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.y, b.y);
  EXPECT_EQ(a.yaw, b.yaw);
}

TEST(SharedPrefixes, EveryEgoPathHasTheReferencesPosesAlsoWhenTheBackendIsReused) {
  const std::vector<Scene> scenes = {bench::PaperSceneS1(), testing::RandomScene(3, 4, 2, true),
                                     bench::PaperSceneS2()};
  CpuBackend backend(2, /*simd=*/false, /*skip_out_of_reach=*/false);
  for (const Scene& scene : scenes) {
    const internal::Problem pb = internal::BuildProblem(scene, Params{});
    ReferenceBackend reference;
    reference.GenerateTrajectories(pb);
    backend.GenerateTrajectories(pb);
    ExpectSamePoses(backend.EgoTrajectories(), reference.EgoTrajectories());
    ExpectSamePoses(backend.EgoTrajectories(), reference.EgoTrajectories());  // asked twice
    ExpectSamePoses(backend.CoTrajectories(), reference.CoTrajectories());
  }
}

TEST(SharedPrefixes, CollisionRecognitionNeedsNoCopiedPrefix) {
  // The pair matrix comes out the same whether EgoTrajectories() was asked for first or not.
  const internal::Problem pb = internal::BuildProblem(bench::PaperSceneS1(), Params{});
  CpuBackend lazy(1, true), eager(1, true);
  lazy.GenerateTrajectories(pb);
  eager.GenerateTrajectories(pb);
  (void)eager.EgoTrajectories();
  std::vector<std::int16_t> a, b;
  lazy.RecognizeCollisions(pb, &a);
  eager.RecognizeCollisions(pb, &b);
  EXPECT_EQ(a, b);
  size_t hits = 0;
  for (std::int16_t s : a) hits += s > 0;
  EXPECT_GT(hits, 0u);
}

}  // namespace
}  // namespace criticality
