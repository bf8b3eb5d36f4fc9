// The CUDA backend's kernel bodies, run on the CPU over every thread index with the device's
// data layout (step-major poses, counting-sort risk, in-order reduction), must give what the
// CPU backend gives: the same pair matrix and the same risk outputs. This checks the GPU path's
// logic on every machine; on a GPU, cuda_backend_test checks the device itself.
#include "cuda/kernel_bodies.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "../test_scenes.h"
#include "bench/discrimination_scenes.h"
#include "bench/paper_scenes.h"
#include "criticality/estimator.h"
#include "cuda/batch_layout.h"
#include "src/problem.h"
#include "src/risk_assessment.h"

namespace criticality {
namespace {

struct Emulated {
  cuda::BatchHost batch;
  std::vector<std::int16_t> first;
  std::vector<double> out;  // per problem: steps, objects, p_cra
  std::vector<double> ego_col;
  std::vector<char> ego_hits;  // CollisionBody's marks: the hits the host reads
};

// The risk kernels CudaBackend launches: a warp per ego hypothesis and per output (RiskRowBody,
// ReduceWarpBody, their lanes emulated one after another), or a thread for each (RiskBody,
// ReduceBody: where a row's scratch does not fit in shared memory, or to compare).
enum class Risk { kWarpPerRow, kThreadPerRow };

// What CudaBackend::RunBatch launches, as loops over the thread indices.
Emulated RunKernelBodies(const std::vector<const internal::Problem*>& problems,
                         Risk risk = Risk::kWarpPerRow) {
  Emulated e;
  e.batch = cuda::MakeBatch(problems);
  const cuda::BatchHost& h = e.batch;
  const cuda::BatchLayout b = h.HostView();
  const size_t ne = static_cast<size_t>(h.TotalEgo()) * h.steps;
  const size_t nc = static_cast<size_t>(h.TotalCo()) * h.steps;
  std::vector<double> ex(ne), ey(ne), eyaw(ne), ec(ne), es(ne), cx(nc), cy(nc), cyaw(nc), cc(nc),
      cs(nc);
  for (int g = 0; g < h.TotalEgo() + h.TotalCo(); ++g) {
    cuda::TrajectoryBody(g, h.sets.data(), b, problems.front()->sim, ex.data(), ey.data(),
                         eyaw.data(), cx.data(), cy.data(), cyaw.data());
  }
  for (size_t k = 0; k < ne; ++k) cuda::TrigBody(k, eyaw.data(), ec.data(), es.data());
  for (size_t k = 0; k < nc; ++k) cuda::TrigBody(k, cyaw.data(), cc.data(), cs.data());
  const size_t blocks = static_cast<size_t>(cuda::BoundsBlocks(h.steps)) * 4;
  std::vector<double> ego_bounds(blocks * h.TotalEgo()), co_bounds(blocks * h.TotalCo());
  for (int t = 0; t < h.TotalEgo(); ++t)
    cuda::BoundsBody(t, h.TotalEgo(), h.steps, ex.data(), ey.data(), ego_bounds.data());
  for (int t = 0; t < h.TotalCo(); ++t)
    cuda::BoundsBody(t, h.TotalCo(), h.steps, cx.data(), cy.data(), co_bounds.data());
  e.first.assign(h.TotalPairs(), -1);
  e.ego_hits.assign(h.TotalEgo(), 0);
  for (long long k = 0; k < h.TotalPairs(); ++k) {
    cuda::CollisionBody(k, b, cuda::Poses{ex.data(), ey.data(), ec.data(), es.data()},
                        cuda::Poses{cx.data(), cy.data(), cc.data(), cs.data()}, ego_bounds.data(),
                        co_bounds.data(), e.first.data(), e.ego_hits.data());
  }
  const size_t ego_obj = std::max<long long>(h.TotalEgoObj(), 1);
  std::vector<int> hist(static_cast<size_t>(h.TotalEgo()) * (h.steps + 1)), events(h.TotalPairs());
  std::vector<double> contrib(h.TotalPairs()), mass(ego_obj), by_step(ne), by_obj(ego_obj);
  e.ego_col.assign(h.TotalEgo(), -1.0);
  if (risk == Risk::kThreadPerRow) {
    const cuda::RiskScratch w{hist.data(), events.data(), contrib.data(), mass.data()};
    for (int g = 0; g < h.TotalEgo(); ++g) {
      cuda::RiskBody(g, b, e.first.data(), h.p_co.data(), e.ego_hits.data(), w, e.ego_col.data(),
                     by_step.data(), by_obj.data());
    }
  } else {
    int max_obj = 0;
    for (int p = 0; p < h.problems; ++p)
      max_obj = std::max(max_obj, h.obj_base[p + 1] - h.obj_base[p]);
    // One warp's shared memory, filled with garbage: the body must clear what it reads.
    std::vector<double> shared(cuda::RiskRowBytes(h.steps, max_obj) / sizeof(double), 1e300);
    const cuda::RiskRowScratch s = cuda::RiskRowScratchAt(shared.data(), h.steps, max_obj);
    for (int g = 0; g < h.TotalEgo(); ++g) {
      cuda::RiskRowBody(cuda::HostWarp{}, g, b, e.first.data(), h.p_co.data(), e.ego_hits.data(),
                        events.data(), s, e.ego_col.data(), by_step.data(), by_obj.data());
    }
  }
  e.out.assign(h.TotalOut(), -1.0);
  if (risk == Risk::kThreadPerRow) {
    for (int q = 0; q < h.TotalOut(); ++q) {
      cuda::ReduceBody(q, b, h.p_ego.data(), e.ego_col.data(), by_step.data(), by_obj.data(),
                       e.out.data());
    }
  } else {
    std::vector<double> term(cuda::kWarp, 1e300);
    std::vector<int> counts(cuda::kWarp, 1);
    for (int q = 0; q < h.TotalOut(); ++q) {
      cuda::ReduceWarpBody(cuda::HostWarp{}, q, b, h.p_ego.data(), e.ego_col.data(), by_step.data(),
                           by_obj.data(), cuda::ReduceScratch{term.data(), counts.data()},
                           e.out.data());
    }
  }
  return e;
}

// Runs the scenes as one batch through the kernel bodies and compares every problem's part
// with a separate CPU estimate of its scene.
// Both risk kernels are checked.
void ExpectBatchSameAsCpu(const std::vector<Scene>& scenes, const std::string& what,
                          const Params& params = Params{}) {
  std::vector<internal::Problem> problems;
  for (const Scene& scene : scenes) problems.push_back(internal::BuildProblem(scene, params));
  std::vector<const internal::Problem*> views;
  for (const internal::Problem& pb : problems) views.push_back(&pb);
  EstimatorOptions opt;
  opt.keep_pair_matrix = true;
  opt.simd = false;  // the kernel bodies run the scalar core, as the scalar fast path does
  Estimator cpu(params, opt);
  std::vector<Result> cpu_results;
  for (const Scene& scene : scenes) cpu_results.push_back(cpu.Estimate(scene));
  for (const Risk risk : {Risk::kWarpPerRow, Risk::kThreadPerRow}) {
    const Emulated e = RunKernelBodies(views, risk);
    const cuda::BatchHost& h = e.batch;
    for (size_t p = 0; p < scenes.size(); ++p) {
      const std::string where =
          what + (risk == Risk::kWarpPerRow ? " (warp per row)" : " (thread per row)") +
          ", problem " + std::to_string(p);
      const Result& r = cpu_results[p];
      const std::vector<std::int16_t> first(e.first.begin() + h.pair_base[p],
                                            e.first.begin() + h.pair_base[p + 1]);
      EXPECT_TRUE(first == r.first_collision_step) << where << ": pair matrices differ";
      const int steps = h.steps, n_obj = static_cast<int>(problems[p].cos.size());
      const double* out = e.out.data() + h.out_base[p];
      for (int n = 0; n < steps; ++n)
        EXPECT_EQ(out[n], r.first_collision_pmf[n]) << where << " step " << n;
      for (int o = 0; o < n_obj; ++o)
        EXPECT_EQ(out[steps + o], r.objects[o].contribution) << where << " object " << o;
      const std::vector<double> col(e.ego_col.begin() + h.ego_base[p],
                                    e.ego_col.begin() + h.ego_base[p + 1]);
      int free = 0;
      for (int g = h.ego_base[p]; g < h.ego_base[p + 1]; ++g) free += e.ego_hits[g] == 0;
      EXPECT_EQ(free, r.collision_free_ego_trajectories) << where;
      // The outputs for decisions, from the device's per-ego results through the host code the
      // CUDA backend runs after its kernels (FinishDecisionOutputs, which also rounds a sum
      // that came out a few ulps above 1 to 1).
      Result d;
      d.p_collision = out[steps + n_obj];
      d.ego_collision_probability = col;
      internal::FinishDecisionOutputs(problems[p], params,
                                      std::vector<char>(e.ego_hits.begin() + h.ego_base[p],
                                                        e.ego_hits.begin() + h.ego_base[p + 1]),
                                      &d);
      EXPECT_EQ(d.p_collision, r.p_collision) << where;
      EXPECT_TRUE(d.ego_collision_probability == r.ego_collision_probability) << where;
      EXPECT_EQ(d.p_reference, r.p_reference) << where;
      EXPECT_EQ(d.unavoidability, r.unavoidability) << where;
      EXPECT_EQ(d.collision_free_ego_trajectories, r.collision_free_ego_trajectories) << where;
      ASSERT_EQ(d.escape_routes.size(), r.escape_routes.size()) << where;
      for (size_t k = 0; k < r.escape_routes.size(); ++k) {
        EXPECT_EQ(d.escape_routes[k].ego_trajectory, r.escape_routes[k].ego_trajectory) << where;
        EXPECT_EQ(d.escape_routes[k].x_m, r.escape_routes[k].x_m) << where;
      }
    }
  }
}

TEST(CudaKernelBodies, PaperScenesMatchTheCpuBackendExactly) {
  ExpectBatchSameAsCpu({bench::PaperSceneS1()}, "S1 alone");
  ExpectBatchSameAsCpu({bench::PaperSceneS2()}, "S2 alone");
}

TEST(CudaKernelBodies, OneBatchOfMixedScenesMatchesTheCpuBackendExactly) {
  // Different sizes in one batch, an ego alone (no pairs) in the middle, pedestrians.
  std::vector<Scene> scenes{bench::PaperSceneS1(), bench::PaperSceneS2(),
                            testing::RandomScene(9, 0, 0, false)};
  for (unsigned seed = 1; seed <= 6; ++seed)
    scenes.push_back(testing::RandomScene(seed, 4, 2, seed % 2 == 0));
  ExpectBatchSameAsCpu(scenes, "mixed batch");
}

TEST(CudaKernelBodies, VehiclesThatLeaveTheSceneMatchTheCpuBackendExactly) {
  // Params::route_end_leaves: the ego and some vehicles leave at their route's end.
  std::vector<Scene> scenes;
  for (unsigned seed = 11; seed <= 14; ++seed) {
    Scene s = testing::RandomScene(seed, 4, 1, true);
    s.ego.state.route_end_m = 4.0 * seed - 30.0 > 0.0 ? 4.0 * seed - 30.0 : 0.0;
    for (size_t i = 0; i < s.vehicles.size(); i += 2) s.vehicles[i].state.route_end_m = 3.0 + i;
    scenes.push_back(s);
  }
  ExpectBatchSameAsCpu(scenes, "leaving batch");
}

TEST(CudaKernelBodies, HeldPosesAndStoppedBodiesMatchTheCpuBackendExactly) {
  // The world's 1 s and 0.5 s steps (held poses), with and without Params::euler_stops.
  std::vector<Scene> scenes;
  for (unsigned seed = 1; seed <= 4; ++seed) {
    Scene s = testing::RandomScene(seed, 4, 2, seed % 2 == 0);
    s.euler_update_step_s = seed % 2 ? 1.0 : 0.5;
    scenes.push_back(s);
  }
  ExpectBatchSameAsCpu(scenes, "held poses batch");
  Params stops;
  stops.euler_stops = true;
  ExpectBatchSameAsCpu(scenes, "held poses batch, stopped bodies stay", stops);
}

TEST(CudaKernelBodies, BodiesOnTheirWayMatchTheCpuBackendExactly) {
  std::vector<Scene> scenes;
  for (unsigned seed = 1; seed <= 4; ++seed)
    scenes.push_back(testing::WithTurningWays(testing::RandomScene(seed, 4, 1, seed % 2 == 0), 3.0));
  ExpectBatchSameAsCpu(scenes, "ways batch");
  Params lateral;  // the experiment of lateral paths beside the way
  lateral.way_lateral_paths = true;
  ExpectBatchSameAsCpu(scenes, "ways batch, lateral paths", lateral);
  Params ego;  // the experiment of an ego on its way
  ego.ego_on_way = true;
  for (Scene& s : scenes) s.ego.way = testing::TurningWay(s.ego.length_m, 2.5);
  ExpectBatchSameAsCpu(scenes, "ways batch, ego on its way", ego);
  ego.way_lateral_paths = true;  // its path tree beside the way
  ExpectBatchSameAsCpu(scenes, "ways batch, ego on its way, lateral paths", ego);
}

TEST(CudaKernelBodies, OtherParametersAndDiscriminationScenesMatchTheCpuBackendExactly) {
  // Another step partition (odd instants, shorter horizon) and the paper-literal models: the
  // kernel bodies take everything from the hypothesis sets and the layout.
  std::vector<Scene> scenes{bench::PaperSceneS1()};
  for (const bench::DiscriminationScene& d : bench::DiscriminationScenes()) {
    if (d.name == "pedestrian-crosses-ttc-1.2" || d.name == "junction-car-crosses-ttc-1.3" ||
        d.name == "motorway-neighbours-alongside")
      scenes.push_back(d.scene);
  }
  ASSERT_EQ(scenes.size(), 4u) << "discrimination scenes renamed?";
  Params odd;
  odd.step_s = 0.03;
  odd.horizon_s = 1.5;
  odd.path_sample_times_s = {0.31, 0.77, 1.49};
  ExpectBatchSameAsCpu(scenes, "odd step and instants", odd);
  ExpectBatchSameAsCpu(scenes, "paper-literal", ParamsPreset("paper-literal"));
}

TEST(CudaKernelBodies, ProblemsWithCarriagesAreFoldedAndAssessedOnTheHostAsTheCpuDoes) {
  // The CUDA backend's path for long bodies (estimator/ALGORITHM.md "Long and articulated
  // bodies"): the kernels simulate and check every set, carriages included; the problem's
  // slice of the pair matrix is then folded and assessed on the host (AssessBodies), in a
  // batch beside problems assessed by the risk kernels.
  const std::vector<Scene> scenes{testing::WithTrailers(bench::PaperSceneS1(), RoadUser::kHeavy),
                                  bench::PaperSceneS1(),
                                  testing::WithTrailers(bench::PaperSceneS2(), RoadUser::kRail)};
  const Params params;
  std::vector<internal::Problem> problems;
  for (const Scene& scene : scenes) problems.push_back(internal::BuildProblem(scene, params));
  std::vector<const internal::Problem*> views;
  for (const internal::Problem& pb : problems) views.push_back(&pb);
  const Emulated e = RunKernelBodies(views);
  const cuda::BatchHost& h = e.batch;
  EstimatorOptions opt;
  opt.keep_pair_matrix = true;
  opt.simd = false;  // the kernel bodies run the scalar core, as the scalar fast path does
  Estimator cpu(params, opt);
  for (size_t p = 0; p < scenes.size(); ++p) {
    const Result r = cpu.Estimate(scenes[p]);
    std::vector<std::int16_t> first(e.first.begin() + h.pair_base[p],
                                    e.first.begin() + h.pair_base[p + 1]);
    ASSERT_EQ(problems[p].HasCarriages(), p != 1) << p;
    Result d;
    internal::AssessBodies(problems[p], params, &first, 1, &d);
    EXPECT_TRUE(first == r.first_collision_step) << "problem " << p << ": pair matrices differ";
    EXPECT_EQ(d.p_collision, r.p_collision) << p;
    EXPECT_EQ(d.p_reference, r.p_reference) << p;
    EXPECT_EQ(d.first_collision_pmf, r.first_collision_pmf) << p;
    ASSERT_EQ(d.objects.size(), r.objects.size()) << p;
    ASSERT_EQ(d.objects.size(), scenes[p].vehicles.size()) << p;
    for (size_t o = 0; o < r.objects.size(); ++o)
      EXPECT_EQ(d.objects[o].contribution, r.objects[o].contribution) << p << " " << o;
  }
  EXPECT_GT(problems[0].CoTrajectories(), problems[0].ObjectTrajectories());
}

TEST(CudaKernelBodies, ProblemOfSkipsEmptyRanges) {
  const long long base[] = {0, 5, 5, 5, 9, 12};  // problems 1 and 2 are empty
  EXPECT_EQ(cuda::ProblemOf(base, 5, 0LL), 0);
  EXPECT_EQ(cuda::ProblemOf(base, 5, 4LL), 0);
  EXPECT_EQ(cuda::ProblemOf(base, 5, 5LL), 3);
  EXPECT_EQ(cuda::ProblemOf(base, 5, 8LL), 3);
  EXPECT_EQ(cuda::ProblemOf(base, 5, 9LL), 4);
  EXPECT_EQ(cuda::ProblemOf(base, 5, 11LL), 4);
}

// The bounds of a block are its centres' least and greatest x and y (a last, shorter block
// included), and BlockApart holds only where every step of the block is farther apart than the
// gap in x or in y: random walks, some close and some far, step-major as on the device.
TEST(CudaKernelBodies, BlocksApartHaveEveryStepApart) {
  const int steps = 23, total = 40;  // 3 blocks, the last of 3 steps
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> start(-30.0, 30.0), move(-1.5, 1.5);
  std::vector<double> x(static_cast<size_t>(steps) * total), y(x.size());
  for (int t = 0; t < total; ++t) {
    double px = start(rng), py = start(rng);
    for (int n = 0; n < steps; ++n) {
      px += move(rng);
      py += move(rng);
      x[static_cast<size_t>(n) * total + t] = px;
      y[static_cast<size_t>(n) * total + t] = py;
    }
  }
  const int blocks = cuda::BoundsBlocks(steps);
  ASSERT_EQ(blocks, 3);
  std::vector<double> bounds(static_cast<size_t>(blocks) * 4 * total);
  for (int t = 0; t < total; ++t)
    cuda::BoundsBody(t, total, steps, x.data(), y.data(), bounds.data());
  const double gap = 4.0;
  int apart = 0, near = 0;
  for (int i = 0; i < total; ++i) {
    for (int j = 0; j < total; ++j) {
      for (int block = 0; block < blocks; ++block) {
        const int begin = block * cuda::kBoundsBlock,
                  end = std::min(steps, begin + cuda::kBoundsBlock);
        double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
        for (int n = begin; n < end; ++n) {
          x0 = std::min(x0, x[static_cast<size_t>(n) * total + i]);
          x1 = std::max(x1, x[static_cast<size_t>(n) * total + i]);
          y0 = std::min(y0, y[static_cast<size_t>(n) * total + i]);
          y1 = std::max(y1, y[static_cast<size_t>(n) * total + i]);
        }
        EXPECT_EQ(bounds[static_cast<size_t>(4 * block) * total + i], x0);
        EXPECT_EQ(bounds[static_cast<size_t>(4 * block + 1) * total + i], x1);
        EXPECT_EQ(bounds[static_cast<size_t>(4 * block + 2) * total + i], y0);
        EXPECT_EQ(bounds[static_cast<size_t>(4 * block + 3) * total + i], y1);
        bool every_step_apart = true;
        for (int n = begin; n < end; ++n) {
          const size_t a = static_cast<size_t>(n) * total + i,
                       c = static_cast<size_t>(n) * total + j;
          every_step_apart &= std::fabs(x[c] - x[a]) > gap || std::fabs(y[c] - y[a]) > gap;
        }
        const bool skipped =
            cuda::BlockApart(bounds.data(), total, i, bounds.data(), total, j, block, gap);
        EXPECT_TRUE(!skipped || every_step_apart) << i << " " << j << " block " << block;
        apart += skipped;
        near += !every_step_apart;
      }
    }
  }
  EXPECT_GT(apart, 0);  // both kinds occur, so both sides were checked
  EXPECT_GT(near, 0);
}
}  // namespace
}  // namespace criticality
