// The core/ functions compiled by nvcc give the same answers on the device as on the host.
// Skips (with the reason) where no CUDA device is usable.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "bench/paper_scenes.h"
#include "core/geometry.h"
#include "cuda/core_kernels.cuh"
#include "cuda/device.cuh"
#include "src/problem.h"

namespace criticality {
namespace {

// A macro: GTEST_SKIP must run in the test body to end it.
#define SKIP_WITHOUT_DEVICE()                              \
  do {                                                     \
    std::string why;                                       \
    if (!cuda::DeviceAvailable(&why)) GTEST_SKIP() << why; \
  } while (0)

TEST(CoreOnDevice, BoxOverlapMatchesHost) {
  SKIP_WITHOUT_DEVICE();
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> pos(-4.0, 4.0), yaw(-core::kPi, core::kPi), half(0.1, 3.0);
  std::vector<core::OrientedBox<double>> a, b;
  for (int k = 0; k < 100000; ++k) {
    a.push_back(core::MakeBox(pos(rng), pos(rng), yaw(rng), half(rng), half(rng)));
    b.push_back(core::MakeBox(pos(rng), pos(rng), yaw(rng), half(rng), half(rng)));
  }
  const std::vector<std::uint8_t> device = cuda::BoxesOverlapOnDevice(a, b);
  for (size_t k = 0; k < a.size(); ++k) {
    ASSERT_EQ(device[k] != 0, core::BoxesOverlap(a[k], b[k])) << "pair " << k;
  }
}

TEST(CoreOnDevice, TrajectoriesMatchHostWithinMicrometres) {
  SKIP_WITHOUT_DEVICE();
  const internal::Problem pb = internal::BuildProblem(bench::PaperSceneS1(), Params{});
  for (const core::HypothesisSet* h : {&pb.ego, &pb.cos[0]}) {
    std::vector<double> x, y, yaw;
    cuda::SimulateOnDevice(*h, pb.sim, &x, &y, &yaw);
    std::vector<double> hx(pb.sim.n_steps), hy(pb.sim.n_steps), hyaw(pb.sim.n_steps);
    double worst = 0.0;
    for (int t = 0; t < h->Trajectories(); ++t) {
      core::SimulateHypothesis(*h, pb.sim, t / h->n_paths, t % h->n_paths, hx.data(), hy.data(),
                               hyaw.data());
      for (int n = 0; n < pb.sim.n_steps; ++n) {
        const size_t k = static_cast<size_t>(t) * pb.sim.n_steps + n;
        worst = std::fmax(worst, std::hypot(x[k] - hx[n], y[k] - hy[n]));
        worst = std::fmax(worst, std::fabs(yaw[k] - hyaw[n]));
      }
    }
    // Device libm may differ from glibc in the last bits; over 100 steps that stays far below
    // the 1 mm the CUDA backend is allowed.
    EXPECT_LT(worst, 1e-6);
  }
}

}  // namespace
}  // namespace criticality
