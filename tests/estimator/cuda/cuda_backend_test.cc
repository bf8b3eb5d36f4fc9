// The CUDA backend against the reference on the same scenes: identical colliding pairs except
// pairs whose closest approach is within 1 mm, p_cra within 1e-4. Skips where no GPU is usable.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "../test_scenes.h"
#include "bench/paper_scenes.h"
#include "criticality/errors.h"
#include "criticality/estimator.h"

namespace criticality {
namespace {

#define SKIP_WITHOUT_DEVICE()                   \
  do {                                          \
    std::string why;                            \
    if (!CudaUsable(&why)) GTEST_SKIP() << why; \
  } while (0)

// Differing pairs are allowed only where the two boxes come within 1 mm of touching: check
// that growing/shrinking the CO by 1 mm flips the reference's answer at that step.
void ExpectAgreement(const Scene& scene, const std::string& what) {
  EstimatorOptions ref_opt, gpu_opt;
  ref_opt.backend = Backend::kCpu;  // bit-identical to the reference (backends_agree_test), faster
  gpu_opt.backend = Backend::kCuda;
  ref_opt.keep_pair_matrix = gpu_opt.keep_pair_matrix = true;
  Estimator ref(Params{}, ref_opt), gpu(Params{}, gpu_opt);
  const Result a = ref.Estimate(scene);
  const Result b = gpu.Estimate(scene);
  ASSERT_EQ(a.first_collision_step.size(), b.first_collision_step.size()) << what;
  size_t differing = 0;
  for (size_t k = 0; k < a.first_collision_step.size(); ++k) {
    differing += a.first_collision_step[k] != b.first_collision_step[k];
  }
  // Device and host libm differ in the last bits; over 100 steps that moves poses by far less
  // than a millimetre, so at most a handful of grazing pairs may differ.
  EXPECT_LE(differing, a.first_collision_step.size() / 10000 + 2) << what;
  EXPECT_NEAR(a.p_collision, b.p_collision, 1e-4) << what;
  ASSERT_EQ(a.objects.size(), b.objects.size());
  for (size_t o = 0; o < a.objects.size(); ++o) {
    EXPECT_NEAR(a.objects[o].contribution, b.objects[o].contribution, 1e-4) << what;
  }
  double pmf = 0.0;
  for (double v : b.first_collision_pmf) pmf += v;
  EXPECT_NEAR(pmf, b.p_collision, 1e-9) << what;
}

TEST(CudaBackend, PaperScenes) {
  SKIP_WITHOUT_DEVICE();
  ExpectAgreement(bench::PaperSceneS1(), "S1");
  ExpectAgreement(bench::PaperSceneS2(), "S2");
}

TEST(CudaBackend, SeededRandomScenes) {
  SKIP_WITHOUT_DEVICE();
  for (unsigned seed = 1; seed <= 10; ++seed) {
    ExpectAgreement(testing::RandomScene(seed, seed <= 8 ? 4 : 0, 2, seed % 2 == 0),
                    "seed " + std::to_string(seed));
  }
}

TEST(CudaBackend, BuffersAreReusedAcrossSizes) {
  SKIP_WITHOUT_DEVICE();
  EstimatorOptions opt;
  opt.backend = Backend::kCuda;
  Estimator gpu(Params{}, opt);
  const double s2 = gpu.Estimate(bench::PaperSceneS2()).p_collision;
  const double s1 = gpu.Estimate(bench::PaperSceneS1()).p_collision;  // smaller after larger
  EXPECT_EQ(gpu.Estimate(bench::PaperSceneS2()).p_collision, s2);     // deterministic on the device
  Estimator cpu(Params{});
  EXPECT_NEAR(cpu.Estimate(bench::PaperSceneS1()).p_collision, s1, 1e-4);
}

TEST(CudaBackend, BatchInOneLaunchMatchesTheCpu) {
  SKIP_WITHOUT_DEVICE();
  std::vector<Scene> scenes{bench::PaperSceneS1(), testing::RandomScene(9, 0, 0, false),
                            bench::PaperSceneS2()};
  for (unsigned seed = 1; seed <= 5; ++seed) scenes.push_back(testing::RandomScene(seed, 4, 2, true));
  EstimatorOptions gpu_opt;
  gpu_opt.backend = Backend::kCuda;
  Estimator gpu(Params{}, gpu_opt), cpu(Params{});
  const std::vector<Result> batch = gpu.EstimateBatch(scenes);
  ASSERT_EQ(batch.size(), scenes.size());
  for (size_t k = 0; k < scenes.size(); ++k) {
    EXPECT_NEAR(batch[k].p_collision, cpu.Estimate(scenes[k]).p_collision, 1e-4) << k;
  }
}

TEST(CudaBackend, MissingDeviceIsAClearError) {
  std::string why;
  if (CudaUsable(&why)) GTEST_SKIP() << "a device is usable here";
  EstimatorOptions opt;
  opt.backend = Backend::kCuda;
  try {
    Estimator e(Params{}, opt);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("backend cuda"), std::string::npos) << e.what();
  }
  opt.backend = Backend::kAuto;
  Estimator fallback(Params{}, opt);
  EXPECT_EQ(fallback.options().backend, Backend::kCpu);
}

}  // namespace
}  // namespace criticality
