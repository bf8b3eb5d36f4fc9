// The estimator end to end on the CPU: counts, probabilities, p_cra extremes, determinism,
// lanes, pedestrians, batches, and the outputs for decisions (p_reference, unavoidability,
// escape routes).
#include "criticality/estimator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "bench/discrimination_scenes.h"
#include "bench/paper_scenes.h"
#include "core/chronological_risk.h"
#include "cpu/reference_backend.h"
#include "src/problem.h"
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
    EXPECT_EQ(r.first_collision_pmf, base.first_collision_pmf) << threads;
    ASSERT_EQ(r.objects.size(), base.objects.size());
    for (size_t o = 0; o < r.objects.size(); ++o)
      EXPECT_EQ(r.objects[o].contribution, base.objects[o].contribution) << threads;
  }
}

// p_cra, the first-collision pmf and the objects' shares are the row-by-row definition: each
// ego hypothesis's split (core::SplitEgoRisk) weighted by p_EGO and added up in row order,
// every step and object included; bit for bit, on 1 and 2 threads.
TEST(Estimator, RiskSumsAreTheRowByRowDefinition) {
  const Scene scene = bench::PaperSceneS2();
  const internal::Problem pb = internal::BuildProblem(scene, Params{});
  const int n_co = pb.CoTrajectories(), steps = pb.Steps();
  const int n_obj = static_cast<int>(pb.cos.size());
  for (int threads : {1, 2}) {
    EstimatorOptions opt;
    opt.threads = threads;
    opt.keep_pair_matrix = true;
    Estimator estimator(Params{}, opt);
    const Result r = estimator.Estimate(scene);
    ASSERT_EQ(r.counts.co_trajectories, n_co);
    ASSERT_EQ(r.objects.size(), static_cast<size_t>(n_obj));
    double p = 0.0;
    std::vector<double> pmf(steps, 0.0), share(n_obj, 0.0);
    std::vector<int> histogram(steps + 1), events(n_co);
    std::vector<double> contribution(n_co), hit_mass(n_obj), by_step(steps), by_object(n_obj);
    int rows_hit = 0;
    for (int i = 0; i < pb.EgoTrajectories(); ++i) {
      int n_events = 0;
      const double col = core::SplitEgoRisk(
          r.first_collision_step.data() + static_cast<size_t>(i) * n_co, n_co, steps, n_obj,
          pb.co_probability.data(), pb.co_object_of.data(), histogram.data(), events.data(),
          contribution.data(), hit_mass.data(), by_step.data(), by_object.data(), &n_events);
      if (n_events == 0) continue;
      ++rows_hit;
      const double pe = pb.ego_probability[i];
      p += pe * col;
      for (int n = 0; n < steps; ++n) pmf[n] += pe * by_step[n];
      for (int o = 0; o < n_obj; ++o) share[o] += pe * by_object[o];
    }
    ASSERT_GT(rows_hit, 1);
    EXPECT_EQ(r.p_collision, p) << threads;
    EXPECT_EQ(r.first_collision_pmf, pmf) << threads;
    for (int o = 0; o < n_obj; ++o) EXPECT_EQ(r.objects[o].contribution, share[o]) << o;
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
  // Scenes of different sizes and kinds in one batch (an ego alone, pedestrians, crossing
  // traffic), each compared with an independent estimate: a separate estimator with the
  // reference backend on the same scene. Mixing up the scenes' parts would show as other
  // object ids, counts or risks; the batch reversed must give the results reversed.
  std::vector<Scene> scenes{bench::PaperSceneS1(), testing::RandomScene(3, 3, 1, true),
                            testing::RandomScene(10, 0, 0, false),
                            testing::RandomScene(7, 6, 2, true)};
  for (const bench::DiscriminationScene& d : bench::DiscriminationScenes()) {
    if (d.name == "junction-car-crosses-ttc-1.3" || d.name == "pedestrian-crosses-ttc-1.2")
      scenes.push_back(d.scene);
  }
  ASSERT_EQ(scenes.size(), 6u) << "discrimination scenes renamed?";
  EstimatorOptions opt;
  opt.keep_pair_matrix = true;
  Estimator estimator(Params{}, opt);
  const std::vector<Result> batch = estimator.EstimateBatch(scenes);
  ASSERT_EQ(batch.size(), scenes.size());
  EstimatorOptions ref_opt = opt;
  ref_opt.backend = Backend::kReference;
  for (size_t k = 0; k < scenes.size(); ++k) {
    Estimator independent(Params{}, ref_opt);
    const Result one = independent.Estimate(scenes[k]);
    EXPECT_EQ(batch[k].p_collision, one.p_collision) << k;
    EXPECT_EQ(batch[k].p_reference, one.p_reference) << k;
    EXPECT_EQ(batch[k].unavoidability, one.unavoidability) << k;
    EXPECT_EQ(batch[k].first_collision_step, one.first_collision_step) << k;
    EXPECT_EQ(batch[k].counts.pose_combinations, one.counts.pose_combinations) << k;
    ASSERT_EQ(batch[k].objects.size(), one.objects.size()) << k;
    for (size_t o = 0; o < one.objects.size(); ++o) {
      EXPECT_EQ(batch[k].objects[o].id, one.objects[o].id) << k;
      EXPECT_EQ(batch[k].objects[o].contribution, one.objects[o].contribution) << k;
    }
    ASSERT_EQ(batch[k].escape_routes.size(), one.escape_routes.size()) << k;
    for (size_t e = 0; e < one.escape_routes.size(); ++e) {
      EXPECT_EQ(batch[k].escape_routes[e].ego_trajectory, one.escape_routes[e].ego_trajectory);
    }
  }
  // The scenes differ, so the check above can tell them apart.
  EXPECT_NE(batch[0].counts.co_trajectories, batch[3].counts.co_trajectories);
  EXPECT_NE(batch[0].p_collision, batch[4].p_collision);
  const std::vector<Scene> reversed(scenes.rbegin(), scenes.rend());
  const std::vector<Result> back = estimator.EstimateBatch(reversed);
  for (size_t k = 0; k < scenes.size(); ++k) {
    EXPECT_EQ(back[scenes.size() - 1 - k].p_collision, batch[k].p_collision) << k;
    EXPECT_EQ(back[scenes.size() - 1 - k].first_collision_step, batch[k].first_collision_step);
  }
  EXPECT_TRUE(estimator.EstimateBatch({}).empty());
}
}  // namespace
}  // namespace criticality

namespace criticality {
namespace {

// p_reference, unavoidability and the escape routes, against their definitions.
void ExpectDecisionOutputs(const Scene& scene, const Params& params, const std::string& what) {
  EstimatorOptions opt;
  opt.keep_pair_matrix = true;
  Estimator estimator(params, opt);
  const Result r = estimator.Estimate(scene);
  const int n_ego = r.counts.ego_trajectories;
  const std::vector<double>& col = r.ego_collision_probability;
  // The reference is the first most probable ego hypothesis.
  const int ref =
      static_cast<int>(std::max_element(r.ego_probability.begin(), r.ego_probability.end()) -
                       r.ego_probability.begin());
  EXPECT_EQ(r.reference_ego_trajectory, ref) << what;
  EXPECT_EQ(r.p_reference, col[ref]) << what;
  EXPECT_EQ(r.unavoidability, *std::min_element(col.begin(), col.end())) << what;
  // Ranked by collision probability, then probability; as many as asked for.
  ASSERT_EQ(r.escape_routes.size(), std::min<size_t>(n_ego, params.max_escape_routes)) << what;
  EXPECT_EQ(r.escape_routes.front().collision_probability, r.unavoidability) << what;
  for (size_t k = 1; k < r.escape_routes.size(); ++k) {
    const EscapeRoute &a = r.escape_routes[k - 1], &b = r.escape_routes[k];
    EXPECT_TRUE(
        a.collision_probability < b.collision_probability ||
        (a.collision_probability == b.collision_probability && a.probability >= b.probability))
        << what << " route " << k;
  }
  // No unreported hypothesis beats the last reported one.
  const EscapeRoute& last = r.escape_routes.back();
  std::vector<bool> reported(n_ego, false);
  for (const EscapeRoute& e : r.escape_routes) reported[e.ego_trajectory] = true;
  for (int i = 0; i < n_ego; ++i) {
    if (reported[i]) continue;
    EXPECT_TRUE(col[i] > last.collision_probability ||
                (col[i] == last.collision_probability && r.ego_probability[i] <= last.probability))
        << what << " hypothesis " << i;
  }
  // Each route's manoeuvre is its hypothesis' trajectory, as the reference backend stores it.
  const internal::Problem pb = internal::BuildProblem(scene, params);
  ReferenceBackend reference;
  reference.GenerateTrajectories(pb);
  const internal::TrajectoryStore& ego = reference.EgoTrajectories();
  for (const EscapeRoute& e : r.escape_routes) {
    const int i = e.ego_trajectory;
    EXPECT_EQ(e.collision_probability, col[i]);
    EXPECT_EQ(e.probability, r.ego_probability[i]);
    EXPECT_EQ(e.profile, i / pb.ego.n_paths);
    EXPECT_EQ(e.profile_accel_mps2, pb.ego_profile_accel[e.profile]);
    ASSERT_EQ(e.sections.size(), params.path_sample_times_s.size());
    for (size_t k = 0; k < e.sections.size(); ++k) {
      EXPECT_EQ(e.target_lanes[k], pb.ego_sample_lane[e.sections[k]]);
    }
    ASSERT_EQ(static_cast<int>(e.x_m.size()), r.counts.time_steps);
    for (int n = 0; n < r.counts.time_steps; ++n) {
      ASSERT_EQ(e.x_m[n], ego.x[ego.Offset(i) + n]) << what << " route " << i << " step " << n;
      ASSERT_EQ(e.y_m[n], ego.y[ego.Offset(i) + n]);
      ASSERT_EQ(e.yaw_rad[n], ego.yaw[ego.Offset(i) + n]);
      EXPECT_NEAR(e.time_s[n], (n + 1) * params.step_s, 1e-12);
    }
  }
}

TEST(Estimator, DecisionOutputsFollowTheirDefinitions) {
  ExpectDecisionOutputs(bench::PaperSceneS1(), Params{}, "S1");
  ExpectDecisionOutputs(bench::PaperSceneS2(), ParamsPreset("paper-literal"), "S2 paper-literal");
  for (unsigned seed = 1; seed <= 6; ++seed) {
    ExpectDecisionOutputs(testing::RandomScene(seed, 4, 2, true), Params{},
                          "random " + std::to_string(seed));
  }
  for (const bench::DiscriminationScene& d : bench::DiscriminationScenes()) {
    ExpectDecisionOutputs(d.scene, Params{}, d.name);
  }
  Params few;
  few.max_escape_routes = 3;
  ExpectDecisionOutputs(bench::PaperSceneS1(), few, "S1, 3 routes");
}

TEST(Estimator, EscapeRouteRecordsTheManoeuvreADriverWouldFollow) {
  // A stopped car 30 m ahead at 20 m/s (time to collision 1.5 s): keeping on collides
  // (p_reference 1), emergency braking or an early lane change escape (unavoidability 0), so
  // the best routes are collision-free. The most probable collision-free lane change steers
  // towards the new lane, counter-steers, ends about a lane width off the own-lane centre,
  // within the friction circle and only after the steering latency.
  const std::vector<bench::DiscriminationScene> all = bench::DiscriminationScenes();
  const auto it = std::find_if(all.begin(), all.end(), [](const bench::DiscriminationScene& d) {
    return d.name == "stopped-car-ttc-1.50";
  });
  ASSERT_NE(it, all.end());
  Params params;
  params.max_escape_routes = 200;
  Estimator estimator(params);
  const Result r = estimator.Estimate(it->scene);
  EXPECT_NEAR(r.p_reference, 1.0, 1e-9);
  EXPECT_EQ(r.unavoidability, 0.0);
  EXPECT_EQ(r.escape_routes.front().collision_probability, 0.0);
  const auto lane_change =
      std::find_if(r.escape_routes.begin(), r.escape_routes.end(), [](const EscapeRoute& e) {
        return e.collision_probability == 0.0 && e.target_lanes.front() != 0;
      });
  ASSERT_NE(lane_change, r.escape_routes.end());
  const EscapeRoute& best = *lane_change;
  const double side = best.target_lanes.front();
  EXPECT_NEAR(best.lateral_offset_m.back() * side, 3.5, 1.2);
  const auto [lo, hi] = std::minmax_element(best.steer_rad.begin(), best.steer_rad.end());
  EXPECT_GT(side > 0 ? *hi : -*lo, 0.01);   // steers towards the new lane
  EXPECT_GT(side > 0 ? -*lo : *hi, 0.005);  // and counter-steers to straighten up
  for (size_t n = 0; n < best.steer_rad.size(); ++n) {
    EXPECT_LE(std::hypot(best.accel_mps2[n], best.lateral_accel_mps2[n]), 9.81 * (1 + 1e-9));
    if (best.time_s[n] < 0.3 - 1e-9) {
      EXPECT_EQ(best.steer_rad[n], 0.0);  // steering latency: the lane centre, straight
    }
  }
  EXPECT_EQ(best.speed_mps.size(), best.time_s.size());
}

TEST(Estimator, MainObjectIsTheLargestShareAndNoneWithoutAny) {
  Result r;
  EXPECT_EQ(MainObject(r), nullptr);
  for (const auto& [id, share] : {std::pair<const char*, double>{"a", 0.0}, {"b", 0.3},
                                  {"c", 0.5}, {"d", 0.5}, {"e", 0.1}}) {
    ObjectResult o;
    o.id = id;
    o.contribution = share;
    r.objects.push_back(o);
  }
  ASSERT_NE(MainObject(r), nullptr);
  EXPECT_EQ(MainObject(r)->id, "c");  // the first of equal shares
  for (ObjectResult& o : r.objects) o.contribution = 0.0;
  EXPECT_EQ(MainObject(r), nullptr);
}

}  // namespace
}  // namespace criticality
