// The CUDA backend's batch sizing (cuda/batch_layout.h), on the host: what a problem takes on the
// device and how a batch over the budget is cut into chunks. No GPU needed.
#include <gtest/gtest.h>

#include <cstdint>
#include <utility>
#include <vector>

#include "bench/paper_scenes.h"
#include "criticality/params.h"
#include "cuda/batch_layout.h"
#include "src/problem.h"

namespace criticality {
namespace {

using Chunks = std::vector<std::pair<size_t, size_t>>;

TEST(BatchMemory, AProblemTakesAtLeastItsPosesAndFourteenBytesAPair) {
  const Params params;
  for (const Scene& scene : {bench::PaperSceneS1(), bench::PaperSceneS2()}) {
    const internal::Problem pb = internal::BuildProblem(scene, params);
    const std::uint64_t ego = pb.EgoTrajectories(), co = pb.CoTrajectories(), steps = pb.Steps();
    // Poses (x, y, yaw, cos, sin), the pair matrix with the risk's scratch, the histogram and
    // the sums by step: what the device allocates for sure.
    const std::uint64_t floor = (ego + co) * steps * 5 * 8 + ego * co * 14 +
                                ego * ((steps + 1) * 4 + steps * 8);
    const std::uint64_t bytes = cuda::DeviceBytes(pb);
    EXPECT_GE(bytes, floor);
    EXPECT_LE(bytes, floor + floor / 4);  // the rest is small beside it
    // The estimator's own limit counts 2 bytes a pair: the device needs more than that.
    EXPECT_GT(bytes, internal::WorkloadBytes(ego, co, steps, pb.cos.size()));
  }
  EXPECT_GT(cuda::DeviceBytes(internal::BuildProblem(bench::PaperSceneS2(), params)),
            cuda::DeviceBytes(internal::BuildProblem(bench::PaperSceneS1(), params)));
}

TEST(BatchMemory, ChunksStayWithinTheBudgetInOrderAndCoverEveryProblem) {
  EXPECT_EQ(cuda::BatchChunks({4, 4, 4, 4}, 100), (Chunks{{0, 4}}));
  EXPECT_EQ(cuda::BatchChunks({4, 4, 4, 4}, 8), (Chunks{{0, 2}, {2, 4}}));
  EXPECT_EQ(cuda::BatchChunks({4, 4, 4, 4}, 11), (Chunks{{0, 2}, {2, 4}}));
  EXPECT_EQ(cuda::BatchChunks({4, 4, 4, 4}, 12), (Chunks{{0, 3}, {3, 4}}));
  // A problem over the budget is a chunk of its own; the others go on around it.
  EXPECT_EQ(cuda::BatchChunks({3, 20, 3, 3}, 10), (Chunks{{0, 1}, {1, 2}, {2, 4}}));
  EXPECT_EQ(cuda::BatchChunks({4, 4}, 1), (Chunks{{0, 1}, {1, 2}}));
  EXPECT_TRUE(cuda::BatchChunks({}, 10).empty());
}

}  // namespace
}  // namespace criticality
