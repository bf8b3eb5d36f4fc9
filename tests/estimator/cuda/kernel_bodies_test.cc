// The CUDA backend's kernel bodies, run on the CPU over every thread index with the device's
// data layout (step-major poses, counting-sort risk, in-order reduction), must give what the
// CPU backend gives: the same pair matrix and the same risk outputs. This checks the GPU path's
// logic on every machine; on a GPU, cuda_backend_test checks the device itself.
#include "cuda/kernel_bodies.h"

#include <gtest/gtest.h>

#include <vector>

#include "../test_scenes.h"
#include "bench/paper_scenes.h"
#include "criticality/estimator.h"
#include "src/problem.h"

namespace criticality {
namespace {

struct Emulated {
  std::vector<std::int16_t> first;
  std::vector<double> out;  // steps, objects, p_cra
  std::vector<double> ego_col;
  std::vector<char> ego_hit;
};

// What CudaBackend::Run launches, as loops over the thread indices.
Emulated RunKernelBodies(const internal::Problem& pb) {
  const int n_ego = pb.EgoTrajectories(), n_co = pb.CoTrajectories(), steps = pb.Steps();
  const int n_obj = static_cast<int>(pb.cos.size());
  std::vector<core::HypothesisSet> sets{pb.ego};
  sets.insert(sets.end(), pb.cos.begin(), pb.cos.end());
  const size_t ne = static_cast<size_t>(n_ego) * steps, nc = static_cast<size_t>(n_co) * steps;
  std::vector<double> ex(ne), ey(ne), eyaw(ne), ec(ne), es(ne), cx(nc), cy(nc), cyaw(nc), cc(nc),
      cs(nc);
  for (int g = 0; g < n_ego + n_co; ++g) {
    cuda::TrajectoryBody(g, sets.data(), pb.co_object_of.data(), pb.co_offset.data(), n_ego, n_co,
                         pb.sim, ex.data(), ey.data(), eyaw.data(), cx.data(), cy.data(),
                         cyaw.data());
  }
  for (size_t k = 0; k < ne; ++k) cuda::TrigBody(k, eyaw.data(), ec.data(), es.data());
  for (size_t k = 0; k < nc; ++k) cuda::TrigBody(k, cyaw.data(), cc.data(), cs.data());
  std::vector<double> hl(n_co), hw(n_co);
  for (int j = 0; j < n_co; ++j) {
    hl[j] = pb.cos[pb.co_object_of[j]].half_length;
    hw[j] = pb.cos[pb.co_object_of[j]].half_width;
  }
  Emulated e;
  e.first.assign(static_cast<size_t>(n_ego) * n_co, -1);
  for (size_t k = 0; k < e.first.size(); ++k) {
    cuda::CollisionBody(k, n_ego, n_co, steps,
                        cuda::Poses{ex.data(), ey.data(), ec.data(), es.data()},
                        cuda::Poses{cx.data(), cy.data(), cc.data(), cs.data()}, pb.ego.half_length,
                        pb.ego.half_width, hl.data(), hw.data(), e.first.data());
  }
  std::vector<int> hist(static_cast<size_t>(n_ego) * (steps + 1)),
      events(static_cast<size_t>(n_ego) * n_co);
  std::vector<double> contrib(events.size()), mass(static_cast<size_t>(n_ego) * std::max(n_obj, 1));
  std::vector<double> by_step(ne), by_obj(static_cast<size_t>(n_ego) * std::max(n_obj, 1));
  e.ego_col.assign(n_ego, -1.0);
  e.ego_hit.assign(n_ego, 2);
  const cuda::RiskScratch w{hist.data(), events.data(), contrib.data(), mass.data()};
  for (int i = 0; i < n_ego; ++i) {
    cuda::RiskBody(i, n_co, steps, n_obj, e.first.data(), pb.co_probability.data(),
                   pb.co_object_of.data(), w, e.ego_col.data(), e.ego_hit.data(), by_step.data(),
                   by_obj.data());
  }
  e.out.assign(steps + n_obj + 1, -1.0);
  for (int q = 0; q <= steps + n_obj; ++q) {
    cuda::ReduceBody(q, n_ego, steps, n_obj, pb.ego_probability.data(), e.ego_col.data(),
                     by_step.data(), by_obj.data(), e.out.data());
  }
  return e;
}

void ExpectSameAsCpu(const Scene& scene, const std::string& what) {
  const internal::Problem pb = internal::BuildProblem(scene, Params{});
  const Emulated e = RunKernelBodies(pb);
  EstimatorOptions opt;
  opt.keep_pair_matrix = true;
  Estimator cpu(Params{}, opt);
  const Result r = cpu.Estimate(scene);
  ASSERT_EQ(e.first.size(), r.first_collision_step.size()) << what;
  EXPECT_TRUE(e.first == r.first_collision_step) << what << ": pair matrices differ";
  const int steps = pb.Steps(), n_obj = static_cast<int>(pb.cos.size());
  for (int n = 0; n < steps; ++n)
    EXPECT_EQ(e.out[n], r.first_collision_pmf[n]) << what << " step " << n;
  for (int o = 0; o < n_obj; ++o)
    EXPECT_EQ(e.out[steps + o], r.objects[o].contribution) << what << " object " << o;
  EXPECT_EQ(e.out[steps + n_obj], r.p_collision) << what;
  EXPECT_TRUE(e.ego_col == r.ego_collision_probability) << what;
  int free = 0;
  for (char h : e.ego_hit) free += h == 0;
  EXPECT_EQ(free, r.collision_free_ego_trajectories) << what;
}

TEST(CudaKernelBodies, PaperScenesMatchTheCpuBackendExactly) {
  ExpectSameAsCpu(bench::PaperSceneS1(), "S1");
  ExpectSameAsCpu(bench::PaperSceneS2(), "S2");
}

TEST(CudaKernelBodies, SeededRandomScenesMatchTheCpuBackendExactly) {
  for (unsigned seed = 1; seed <= 10; ++seed) {
    ExpectSameAsCpu(testing::RandomScene(seed, seed <= 8 ? 4 : 0, 2, seed % 2 == 0),
                    "seed " + std::to_string(seed));
  }
}

}  // namespace
}  // namespace criticality
