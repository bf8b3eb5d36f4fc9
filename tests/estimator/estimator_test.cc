// The estimator end to end on the CPU: counts, probabilities, p_cra extremes, determinism,
// lanes, pedestrians.
#include "criticality/estimator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "bench/paper_scenes.h"
#include "test_scenes.h"

namespace criticality {
namespace {

Result Estimate(const Scene& scene, Backend backend = Backend::kCpu, Params params = {}) {
  EstimatorOptions opt;
  opt.backend = backend;
  opt.keep_pair_matrix = true;
  Estimator estimator(params, opt);
  return estimator.Estimate(scene);
}

// A vehicle driving against the ego's direction at (x, y) in the ego frame.
Vehicle Oncoming(double x, double y) {
  Vehicle v;
  v.id = "oncoming";
  v.state.x_m = x;
  v.state.y_m = y;
  v.state.yaw_rad = 3.14159265358979;
  v.state.speed_mps = 20.0;
  return v;
}

TEST(Estimator, PaperCountsS1AndS2) {
  for (int profiles : {6, 5}) {
    Params params;
    params.profiles = profiles;
    const Result s1 = Estimate(bench::PaperSceneS1(), Backend::kCpu, params);
    const Result s2 = Estimate(bench::PaperSceneS2(), Backend::kCpu, params);
    EXPECT_EQ(s1.counts.ego_trajectories, profiles * 343);
    EXPECT_EQ(s1.counts.co_trajectories, 3 * profiles * 7);
    EXPECT_EQ(s1.counts.time_steps, 100);
    EXPECT_EQ(s2.counts.co_trajectories, 10 * profiles * 7);
    EXPECT_EQ(s1.counts.pose_combinations, profiles == 6 ? 25930800u : 18007500u);
    EXPECT_EQ(s2.counts.pose_combinations, profiles == 6 ? 86436000u : 60025000u);
  }
}

TEST(Estimator, EgoProbabilitiesSumToOne) {
  const Result r = Estimate(bench::PaperSceneS1());
  EXPECT_NEAR(std::accumulate(r.ego_probability.begin(), r.ego_probability.end(), 0.0), 1.0, 1e-12);
  for (double p : r.ego_probability) EXPECT_GT(p, 0.0);
}

TEST(Estimator, NoObjectsMeansNoRisk) {
  Scene scene = bench::PaperSceneS1();
  scene.vehicles.clear();
  const Result r = Estimate(scene);
  EXPECT_EQ(r.p_collision, 0.0);
  EXPECT_EQ(r.counts.co_trajectories, 0);
  EXPECT_EQ(r.collision_free_ego_trajectories, r.counts.ego_trajectories);
  ASSERT_FALSE(r.escape_routes.empty());
  // The most probable escape route is the reference: cruise in the middle of the own lane.
  EXPECT_EQ(r.escape_routes[0].profile_slip, 0.0);
  for (int s : r.escape_routes[0].sections) EXPECT_EQ(s, 3);
}

TEST(Estimator, EveryHypothesisCollidingGivesOne) {
  // A vehicle on top of the ego, moving with it: every pair overlaps at the first step.
  Scene scene = bench::PaperSceneS1();
  scene.vehicles.resize(1);
  scene.vehicles[0].state = scene.ego.state;
  scene.vehicles[0].state.x_m = 0.5;
  const Result r = Estimate(scene);
  EXPECT_NEAR(r.p_collision, 1.0, 1e-12);
  EXPECT_NEAR(r.first_collision_pmf[0], 1.0, 1e-12);
  EXPECT_EQ(r.collision_free_ego_trajectories, 0);
  EXPECT_NEAR(r.unavoidability, 1.0, 1e-12);
  EXPECT_NEAR(r.p_reference, 1.0, 1e-12);
  // Escape routes are never empty: the least colliding ones (here all collide for sure).
  ASSERT_EQ(r.escape_routes.size(), 10u);
  for (const EscapeRoute& e : r.escape_routes) EXPECT_NEAR(e.collision_probability, 1.0, 1e-12);
  for (std::int16_t s : r.first_collision_step) EXPECT_EQ(s, 1);
}

TEST(Estimator, ContributionsAndTimeDistributionAddUpToPcra) {
  const Result r = Estimate(bench::PaperSceneS2());
  ASSERT_GT(r.p_collision, 0.0);
  ASSERT_LT(r.p_collision, 1.0);
  double objects = 0.0;
  for (const ObjectResult& o : r.objects) {
    EXPECT_GE(o.contribution, 0.0);
    objects += o.contribution;
  }
  EXPECT_NEAR(objects, r.p_collision, 1e-12);
  EXPECT_NEAR(std::accumulate(r.first_collision_pmf.begin(), r.first_collision_pmf.end(), 0.0),
              r.p_collision, 1e-12);
  // Escape routes are collision-free and sorted by probability.
  for (size_t k = 0; k < r.escape_routes.size(); ++k) {
    const int i = r.escape_routes[k].ego_trajectory;
    EXPECT_EQ(r.ego_collision_probability[i], 0.0);
    for (int j = 0; j < r.counts.co_trajectories; ++j) {
      ASSERT_EQ(r.first_collision_step[static_cast<size_t>(i) * r.counts.co_trajectories + j], 0);
    }
    if (k > 0) {
      EXPECT_GE(r.escape_routes[k - 1].probability, r.escape_routes[k].probability);
    }
  }
}

TEST(Estimator, SameSceneGivesBitIdenticalResultsTwice) {
  const Scene scene = testing::RandomScene(5, 6, 3, true);
  for (Backend b : {Backend::kReference, Backend::kCpu}) {
    EstimatorOptions opt;
    opt.backend = b;
    opt.keep_pair_matrix = true;
    Estimator estimator(Params{}, opt);
    const Result a = estimator.Estimate(scene);
    const Result c = estimator.Estimate(scene);
    EXPECT_EQ(a.p_collision, c.p_collision);  // bit-identical, not near
    EXPECT_EQ(a.first_collision_step, c.first_collision_step);
    EXPECT_EQ(a.first_collision_pmf, c.first_collision_pmf);
    EXPECT_EQ(a.ego_collision_probability, c.ego_collision_probability);
    ASSERT_EQ(a.objects.size(), c.objects.size());
    for (size_t o = 0; o < a.objects.size(); ++o)
      EXPECT_EQ(a.objects[o].contribution, c.objects[o].contribution);
  }
}

TEST(Estimator, ThreadCountDoesNotChangeTheResult) {
  const Scene scene = bench::PaperSceneS1();
  Result base;
  for (int threads : {1, 2, 3, 7}) {
    EstimatorOptions opt;
    opt.threads = threads;
    opt.keep_pair_matrix = true;
    Estimator estimator(Params{}, opt);
    const Result r = estimator.Estimate(scene);
    if (threads == 1) {
      base = r;
      continue;
    }
    EXPECT_EQ(r.p_collision, base.p_collision) << threads;
    EXPECT_EQ(r.first_collision_step, base.first_collision_step) << threads;
  }
}

TEST(Estimator, MissingLanesGiveFewerPaths) {
  Scene scene = bench::PaperSceneS1();
  scene.vehicles.clear();
  scene.ego.lanes.left.reset();
  EXPECT_EQ(Estimate(scene).counts.ego_trajectories, 6 * 5 * 5 * 5);
  scene.ego.lanes.right.reset();
  EXPECT_EQ(Estimate(scene).counts.ego_trajectories, 6 * 3 * 3 * 3);
  scene.ego.lanes.own.reset();  // virtual own lane (RAA width)
  EXPECT_EQ(Estimate(scene).counts.ego_trajectories, 6 * 27);
}

TEST(Estimator, VehiclesAreAssociatedWithTheEgoLanes) {
  Scene scene = bench::PaperSceneS1();
  for (Vehicle& v : scene.vehicles) v.lanes.reset();  // use association
  Vehicle crossing;
  crossing.id = "crossing";
  crossing.state.x_m = 40.0;
  crossing.state.y_m = -15.0;
  crossing.state.yaw_rad = 1.5707963;
  crossing.state.speed_mps = 10.0;
  scene.vehicles.push_back(Oncoming(80.0, 3.5));
  scene.vehicles.push_back(crossing);
  const Result r = Estimate(scene);
  ASSERT_EQ(r.objects.size(), 5u);
  EXPECT_EQ(r.objects[0].lane, 0);   // lead
  EXPECT_EQ(r.objects[1].lane, 1);   // left
  EXPECT_EQ(r.objects[2].lane, -1);  // right-behind
  EXPECT_EQ(r.objects[3].lane, 1);   // oncoming in the left lane
  EXPECT_EQ(r.objects[4].lane, 2);   // crossing: no ego lane
  // From the ego's lanes, a vehicle in the left lane sees two lanes (5 paths), one in the
  // middle lane three (7); the oncoming one sees the ego lane on ITS left (5 paths); the crossing
  // one only its virtual lane (3 paths).
  EXPECT_EQ(r.objects[0].trajectories, 6 * 7);
  EXPECT_EQ(r.objects[1].trajectories, 6 * 5);
  EXPECT_EQ(r.objects[3].trajectories, 6 * 5);
  EXPECT_EQ(r.objects[4].trajectories, 6 * 3);
}

TEST(Estimator, CounterTrafficPenaltyLowersTheRiskFromCounterLanePaths) {
  // The ego's left lane carries oncoming traffic, with an oncoming car in it: only paths into
  // the counter lane can collide with it. A larger counter-traffic penalty makes those paths
  // less probable, so p_cra must drop.
  Scene scene = bench::PaperSceneS1();
  scene.vehicles.clear();
  scene.ego.lanes.left->counter_traffic = true;
  scene.vehicles.push_back(Oncoming(60.0, 3.5));
  Params mild, strict;
  mild.counter_traffic_penalty = 1.0;
  strict.counter_traffic_penalty = 10.0;
  const double p_mild = Estimate(scene, Backend::kCpu, mild).p_collision;
  const double p_strict = Estimate(scene, Backend::kCpu, strict).p_collision;
  EXPECT_GT(p_mild, 0.0);
  EXPECT_LT(p_strict, 0.5 * p_mild);
}

TEST(Estimator, PedestriansAreEstimated) {
  Scene scene = bench::PaperSceneS1();
  scene.vehicles.clear();
  Pedestrian p;
  p.id = "walker";
  p.state.x_m = 30.0;
  p.state.y_m = -3.0;
  p.state.yaw_rad = 1.5707963;  // walking towards the ego's lane
  p.state.speed_mps = 1.5;
  scene.pedestrians.push_back(p);
  const Result r = Estimate(scene);
  ASSERT_EQ(r.objects.size(), 1u);
  EXPECT_EQ(r.objects[0].kind, ObjectKind::kPedestrian);
  EXPECT_EQ(r.objects[0].trajectories, 6 * 7);
  EXPECT_GT(r.p_collision, 0.0);
  EXPECT_LT(r.p_collision, 1.0);
}

}  // namespace
}  // namespace criticality

namespace criticality {
namespace {
TEST(Estimator, BatchGivesWhatEachEstimateGives) {
  std::vector<Scene> scenes{bench::PaperSceneS1(), testing::RandomScene(3, 3, 1, true),
                            testing::RandomScene(10, 0, 0, false), bench::PaperSceneS2()};
  EstimatorOptions opt;
  opt.keep_pair_matrix = true;
  Estimator estimator(Params{}, opt);
  const std::vector<Result> batch = estimator.EstimateBatch(scenes);
  ASSERT_EQ(batch.size(), scenes.size());
  for (size_t k = 0; k < scenes.size(); ++k) {
    const Result one = estimator.Estimate(scenes[k]);
    EXPECT_EQ(batch[k].p_collision, one.p_collision) << k;
    EXPECT_EQ(batch[k].first_collision_step, one.first_collision_step) << k;
    EXPECT_EQ(batch[k].counts.pose_combinations, one.counts.pose_combinations) << k;
  }
  EXPECT_TRUE(estimator.EstimateBatch({}).empty());
}
}  // namespace
}  // namespace criticality
