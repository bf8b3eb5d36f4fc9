// The exact reach shortcut (src/reach_filter.h): the ego's reach bound holds for every
// simulated ego hypothesis, and the shortcut changes nothing in the result on scenes whose
// objects sit at the edge of reach (same p_cra, contributions, pair matrix of the kept objects,
// escape routes; no dropped object has a colliding pair in the full estimate), and the result
// says when the shortcut answered it (Result::answered_by_reach_shortcut).
#include "src/reach_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "bench/paper_scenes.h"
#include "core/oriented_box.h"
#include "core/trajectory_generation.h"
#include "criticality/estimator.h"
#include "test_scenes.h"

namespace criticality {
namespace {

using internal::BuildProblem;
using internal::EgoReachBound;

double Uni(std::mt19937_64& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

// Lanes: straight three lanes, a curved own lane, or none (virtual lane).
LaneSet SomeLanes(std::mt19937_64& rng) {
  const unsigned kind = rng() % 3;
  if (kind == 0) return bench::StraightThreeLanes();
  if (kind == 1) return LaneSet{};
  const double c = Uni(rng, -0.01, 0.01);  // curvature-ish: y = c x^2
  Lane own;
  for (int i = 0; i < 3; ++i) {
    const double x = 25.0 * i;
    own.left.points[i] = Point2{x, c * x * x + 1.75};
    own.right.points[i] = Point2{x, c * x * x - 1.75};
  }
  LaneSet set;
  set.own = own;
  return set;
}

// Params a user may choose, within what ValidateParams accepts.
Params SomeParams(std::mt19937_64& rng) {
  Params p;
  p.friction = Uni(rng, 0.3, 1.3);
  p.max_steer_rad = Uni(rng, 0.3, 1.2);
  p.max_steer_rate_radps = Uni(rng, 0.5, 3.0);
  p.step_s = rng() % 2 ? 0.02 : 0.05;
  p.horizon_s = rng() % 2 ? 2.0 : 3.0;
  p.jerk_mps3 = Uni(rng, 10.0, 80.0);
  p.latency_s = Uni(rng, 0.0, 0.3);
  p.profiles = 3 + static_cast<int>(rng() % 4);
  p.euler_stops = rng() % 2 == 0;  // with held poses: a hypothesis that stops stays
  return p;
}

Ego SomeEgo(std::mt19937_64& rng) {
  Ego e;
  // Low speeds (kinematic model, the seam) as often as high ones.
  e.state.speed_mps = rng() % 2 ? Uni(rng, 0.0, 4.0) : Uni(rng, 4.0, 40.0);
  e.state.accel_mps2 = Uni(rng, -9.0, 4.0);
  e.state.yaw_rate_radps = Uni(rng, -0.6, 0.6);
  e.state.sideslip_rad = Uni(rng, -0.05, 0.05);
  e.length_m = Uni(rng, 3.5, 6.0);
  e.width_m = Uni(rng, 1.5, 2.2);
  e.lanes = SomeLanes(rng);
  return e;
}

// Every field of an escape route, including its manoeuvre (the shortcut once answered from a
// problem that had lost the ego's profile and lane tables).
void ExpectSameRoute(const EscapeRoute& a, const EscapeRoute& b, const std::string& what) {
  EXPECT_EQ(a.ego_trajectory, b.ego_trajectory) << what;
  EXPECT_EQ(a.sections, b.sections) << what;
  EXPECT_EQ(a.target_lanes, b.target_lanes) << what;
  EXPECT_EQ(a.profile_slip, b.profile_slip) << what;
  EXPECT_EQ(a.profile_accel_mps2, b.profile_accel_mps2) << what;
  EXPECT_EQ(a.probability, b.probability) << what;
  EXPECT_EQ(a.collision_probability, b.collision_probability) << what;
  EXPECT_EQ(a.speed_mps, b.speed_mps) << what;
  EXPECT_EQ(a.lateral_offset_m, b.lateral_offset_m) << what;
  EXPECT_EQ(a.steer_rad, b.steer_rad) << what;
  EXPECT_EQ(a.x_m, b.x_m) << what;
}

// An ego alone with the trial's params: every other trial as a simulator's Euler update moves
// it (poses shifted by the speed change; every sixth at whole steps, held poses), every third
// as SUMO draws bodies in a turn (the chord's poses lie off the centre's), every fourth on its
// way through a tight turn (with Params::ego_on_way; the way up to 0.6 m beside it, so that it
// keeps that offset).
Scene SomeEgoScene(std::mt19937_64& rng, int trial) {
  Scene scene;
  scene.ego = SomeEgo(rng);
  if (trial % 2) scene.euler_update_step_s = Uni(rng, 0.05, 1.0);
  if (trial % 6 == 3) scene.euler_update_step_s = rng() % 2 ? 1.0 : 0.5;  // held poses
  scene.bodies_on_path = trial % 3 == 0;
  if (trial % 4 == 1) {
    Way way = testing::TurningWay(scene.ego.length_m, Uni(rng, 1.5, 4.0));
    const double beside = Uni(rng, -0.6, 0.6);
    for (Point2& q : way.points) q.y += beside;
    if (rng() % 2) {  // a left turn
      for (Point2& q : way.points) q.y = -q.y;
    }
    scene.ego.way = way;
  }
  return scene;
}

// SomeParams with the ego on its way where it brings one (SomeEgoScene), on one path or with
// its path tree beside the way.
Params SomeEgoParams(std::mt19937_64& rng) {
  Params p = SomeParams(rng);
  p.ego_on_way = true;
  p.way_lateral_paths = rng() % 2 == 0;  // its path tree beside the way, or one path on it
  return p;
}

TEST(ReachFilter, EgoReachBoundHoldsForEverySimulatedEgoHypothesis) {
  std::mt19937_64 rng(20261124);
  double tightest = 1e9;  // smallest margin between the bound and a hypothesis at the horizon
  int on_way = 0;         // trials with the ego on its way
  int stays = 0;          // trials with held poses where a stopped hypothesis stays
  for (int trial = 0; trial < 40; ++trial) {
    const Params params = SomeEgoParams(rng);
    const Scene scene = SomeEgoScene(rng, trial);
    const internal::Problem pb = BuildProblem(scene, params);
    on_way += pb.ego.on_way;
    stays += pb.ego.pose_hold_steps > 1 && pb.ego.hold_stops;
    const std::vector<double> bound = EgoReachBound(pb.ego, pb.sim);
    const int steps = pb.sim.n_steps;
    std::vector<double> x(steps), y(steps), yaw(steps);
    for (int t = 0; t < pb.ego.Trajectories(); ++t) {
      core::SimulateHypothesis(pb.ego, pb.sim, t / pb.ego.n_paths, t % pb.ego.n_paths, x.data(),
                               y.data(), yaw.data());
      for (int n = 0; n < steps; ++n) {
        const double d = std::hypot(x[n] - scene.ego.state.x_m, y[n] - scene.ego.state.y_m);
        ASSERT_LE(d, bound[n + 1]) << "trial " << trial << " hypothesis " << t << " step " << n;
      }
      tightest = std::min(tightest, bound[steps] - std::hypot(x[steps - 1], y[steps - 1]));
    }
  }
  // The bound is a bound, not a guess far out: some hypothesis comes within a few metres.
  EXPECT_LT(tightest, 6.0);
  EXPECT_GE(on_way, 8);
  EXPECT_GE(stays, 2);
}

// From a state the simulation reached (a tree node's start, cpu/cpu_backend.h), the bound
// holds for the rest of the hypothesis, and EgoReachAfter is its last value in closed form.
TEST(ReachFilter, EgoReachBoundFromALaterStateHoldsForTheRestOfEachHypothesis) {
  std::mt19937_64 rng(20261202);
  double tightest = 1e9;
  int on_way = 0;
  for (int trial = 0; trial < 30; ++trial) {
    const Params params = SomeEgoParams(rng);
    const internal::Problem pb = BuildProblem(SomeEgoScene(rng, trial), params);
    on_way += pb.ego.on_way;
    const int steps = pb.sim.n_steps;
    std::vector<double> x(steps), y(steps), yaw(steps);
    for (int t = 0; t < pb.ego.Trajectories(); t += 7) {
      const int profile = t / pb.ego.n_paths, path = t % pb.ego.n_paths;
      for (int n0 : {steps / 3, 2 * steps / 3}) {
        core::SimulationState st = core::InitialSimulationState(pb.ego, pb.sim);
        core::SimulateVehicleSteps(pb.ego, pb.sim, profile, path, 0, n0, &st, x.data(), y.data(),
                                   yaw.data());
        const core::SimulationState at = st;
        core::SimulateVehicleSteps(pb.ego, pb.sim, profile, path, n0, steps, &st, x.data(),
                                   y.data(), yaw.data());
        const std::vector<double> bound = internal::EgoReachBoundFrom(
            pb.ego, pb.sim, at.s.v, std::hypot(at.s.ax, at.s.ay), steps - n0);
        for (int n = n0; n < steps; ++n) {  // pose n is n - n0 + 1 steps after pose n0 - 1
          // The bound is exact for a straight step at the top rate (the distance and the bound
          // then differ in their last bits; the filter adds kMarginM of 1 mm to it).
          const double d = std::hypot(x[n] - x[n0 - 1], y[n] - y[n0 - 1]);
          ASSERT_LE(d, bound[n - n0 + 1] * (1.0 + 1e-12) + 1e-12)
              << "trial " << trial << " hypothesis " << t << " from " << n0 << " step " << n;
        }
        tightest = std::min(tightest, bound.back() - std::hypot(x[steps - 1] - x[n0 - 1],
                                                                y[steps - 1] - y[n0 - 1]));
        const double closed = internal::EgoReachAfter(pb.ego, pb.sim, at.s.v,
                                                      std::hypot(at.s.ax, at.s.ay), steps - n0);
        EXPECT_NEAR(closed, bound.back(), 1e-9 * (1.0 + bound.back()));
      }
    }
  }
  EXPECT_LT(tightest, 6.0);  // a bound, not a guess far out
  EXPECT_GE(on_way, 6);
}

// A scene whose objects sit around the edge of the ego's reach: at the bound's distance plus
// the bounding radii, plus or minus a few metres, heading anywhere.
Scene EdgeScene(std::mt19937_64& rng, const Params& params) {
  Scene s;
  s.ego = SomeEgo(rng);
  s.ego.state.x_m = Uni(rng, -50.0, 50.0);
  s.ego.state.y_m = Uni(rng, -50.0, 50.0);
  s.ego.state.yaw_rad = Uni(rng, -3.1, 3.1);
  const internal::Problem pb = BuildProblem(s, params);
  const double reach = EgoReachBound(pb.ego, pb.sim).back();
  const int vehicles = 1 + static_cast<int>(rng() % 5);
  for (int i = 0; i < vehicles; ++i) {
    Vehicle v;
    v.id = "v" + std::to_string(i);
    v.length_m = Uni(rng, 3.0, 12.0);
    v.width_m = Uni(rng, 1.5, 2.6);
    const double r = core::BoundingRadius(0.5 * s.ego.length_m, 0.5 * s.ego.width_m) +
                     core::BoundingRadius(0.5 * v.length_m, 0.5 * v.width_m);
    const double bearing = Uni(rng, -3.14159, 3.14159);
    const double d = reach + r + Uni(rng, -5.0, 25.0);
    v.state.x_m = s.ego.state.x_m + d * std::cos(bearing);
    v.state.y_m = s.ego.state.y_m + d * std::sin(bearing);
    // Towards the ego (most critical), away, or across.
    const unsigned heading = rng() % 3;
    v.state.yaw_rad = bearing +
                      (heading == 0   ? 3.14159
                       : heading == 1 ? 0.0
                                      : 1.5708) +
                      Uni(rng, -0.3, 0.3);
    v.state.speed_mps = Uni(rng, 0.0, 30.0);
    v.state.accel_mps2 = Uni(rng, -4.0, 3.0);
    v.state.yaw_rate_radps = Uni(rng, -0.3, 0.3);
    if (rng() % 2) v.lanes = SomeLanes(rng);
    s.vehicles.push_back(v);
  }
  const int pedestrians = static_cast<int>(rng() % 3);
  for (int i = 0; i < pedestrians; ++i) {
    Pedestrian p;
    p.id = "p" + std::to_string(i);
    const double r = core::BoundingRadius(0.5 * s.ego.length_m, 0.5 * s.ego.width_m) +
                     core::BoundingRadius(0.25, 0.25);
    const double bearing = Uni(rng, -3.14159, 3.14159);
    const double d = reach + r + Uni(rng, -1.0, 8.0);
    p.state.x_m = s.ego.state.x_m + d * std::cos(bearing);
    p.state.y_m = s.ego.state.y_m + d * std::sin(bearing);
    p.state.yaw_rad = bearing + 3.14159 + Uni(rng, -0.5, 0.5);
    p.state.speed_mps = Uni(rng, 0.0, 2.7);
    s.pedestrians.push_back(p);
  }
  return s;
}

// The objects' paths simulated in SIMD lanes (EstimatorOptions::simd, the default) decide as
// the scalar step does, on scenes whose objects sit around the edge of the ego's reach.
TEST(ReachFilter, SimdLanesDecideAsTheScalarStep) {
  std::mt19937_64 rng(20261203);
  int dropped = 0, kept = 0;
  for (int trial = 0; trial < 150; ++trial) {
    Params params = SomeParams(rng);
    params.horizon_s = 2.0;
    params.step_s = 0.05;
    Scene scene = EdgeScene(rng, params);
    if (trial % 3 == 0) scene.euler_update_step_s = Uni(rng, 0.05, 1.0);
    const internal::Problem pb = BuildProblem(scene, params);
    const std::vector<char> scalar = internal::OutOfReach(pb, false);
    EXPECT_EQ(internal::OutOfReach(pb, true), scalar) << "trial " << trial;
    for (char d : scalar) (d ? dropped : kept)++;
  }
  EXPECT_GT(dropped, 20);
  EXPECT_GT(kept, 20);
}

TEST(ReachFilter, ShortcutGivesTheFullEstimateAtTheEdgeOfReach) {
  std::mt19937_64 rng(424242);
  int dropped = 0, kept_colliding = 0, kept_clear = 0, answered_without_trajectories = 0;
  for (int trial = 0; trial < 150; ++trial) {
    Params params = SomeParams(rng);
    params.horizon_s = 2.0;  // keep the full estimates quick
    params.step_s = 0.05;
    Scene scene = EdgeScene(rng, params);
    if (trial % 3 == 0) scene.euler_update_step_s = Uni(rng, 0.05, 1.0);
    EstimatorOptions full_opt, cut_opt;
    full_opt.threads = cut_opt.threads = 2;
    full_opt.keep_pair_matrix = cut_opt.keep_pair_matrix = true;
    cut_opt.reach_shortcut = true;
    Estimator full(params, full_opt), cut(params, cut_opt);
    const Result a = full.Estimate(scene);
    const Result b = cut.Estimate(scene);
    const std::string what = "trial " + std::to_string(trial);
    ASSERT_EQ(a.objects.size(), b.objects.size()) << what;
    EXPECT_EQ(a.p_collision, b.p_collision) << what;
    EXPECT_EQ(a.first_collision_pmf, b.first_collision_pmf) << what;
    EXPECT_EQ(a.ego_collision_probability, b.ego_collision_probability) << what;
    EXPECT_EQ(a.collision_free_ego_trajectories, b.collision_free_ego_trajectories) << what;
    ASSERT_EQ(a.escape_routes.size(), b.escape_routes.size()) << what;
    EXPECT_EQ(a.p_reference, b.p_reference) << what;
    EXPECT_EQ(a.unavoidability, b.unavoidability) << what;
    for (size_t k = 0; k < a.escape_routes.size(); ++k) {
      ExpectSameRoute(a.escape_routes[k], b.escape_routes[k], what);
    }
    const int n_ego = a.counts.ego_trajectories;
    const int a_cols = a.counts.co_trajectories, b_cols = b.counts.co_trajectories;
    bool any_kept = false;
    for (size_t o = 0; o < a.objects.size(); ++o) {
      const ObjectResult& fo = a.objects[o];
      const ObjectResult& co = b.objects[o];
      EXPECT_EQ(fo.id, co.id) << what;
      EXPECT_EQ(fo.contribution, co.contribution) << what << " " << fo.id;
      bool collides = false;
      for (int i = 0; i < n_ego; ++i) {
        for (int j = 0; j < fo.trajectories; ++j) {
          const std::int16_t full_step =
              a.first_collision_step[static_cast<size_t>(i) * a_cols + fo.first_trajectory + j];
          collides = collides || full_step > 0;
          if (!co.out_of_reach) {
            ASSERT_EQ(
                full_step,
                b.first_collision_step[static_cast<size_t>(i) * b_cols + co.first_trajectory + j])
                << what << " " << fo.id;
          }
        }
      }
      if (co.out_of_reach) {
        ++dropped;
        EXPECT_FALSE(collides) << what << ": " << fo.id << " was dropped but collides";
        EXPECT_EQ(co.trajectories, 0) << what;
      } else {
        any_kept = true;
        ++(collides ? kept_colliding : kept_clear);
      }
    }
    if (!any_kept) {
      ++answered_without_trajectories;
      EXPECT_EQ(b.counts.co_trajectories, 0) << what;
      EXPECT_TRUE(b.first_collision_step.empty()) << what;
    }
    // The batch path gives the same.
    const std::vector<Result> batch = cut.EstimateBatch({scene, scene});
    EXPECT_EQ(batch[1].p_collision, a.p_collision) << what;
    EXPECT_EQ(batch[1].objects.size(), b.objects.size()) << what;
  }
  // The scenes exercise both sides of the edge.
  EXPECT_GE(dropped, 40);
  EXPECT_GE(kept_colliding, 10);
  EXPECT_GE(kept_clear, 10);
  EXPECT_GE(answered_without_trajectories, 5);
  std::printf("dropped %d, kept colliding %d, kept clear %d, answered without trajectories %d\n",
              dropped, kept_colliding, kept_clear, answered_without_trajectories);
}

TEST(ReachFilter, AnEgoWithNoObjectInReachIsAnsweredWithoutTrajectories) {
  // One vehicle 500 m away (the full estimate simulates and checks it), and the same ego alone.
  Scene far;
  far.ego.state.speed_mps = 12.0;
  far.ego.lanes = bench::StraightThreeLanes();
  Vehicle v;
  v.id = "far";
  v.state.x_m = 500.0;
  v.state.speed_mps = 12.0;
  far.vehicles.push_back(v);
  Scene alone = far;
  alone.vehicles.clear();
  EstimatorOptions full_opt, cut_opt;
  cut_opt.reach_shortcut = true;
  Estimator full(Params{}, full_opt), cut(Params{}, cut_opt);
  const Result a = full.Estimate(far);
  for (const Scene* scene : {&far, &alone}) {
    const Result b = cut.Estimate(*scene);
    EXPECT_EQ(b.p_collision, 0.0);
    EXPECT_EQ(a.first_collision_pmf, b.first_collision_pmf);
    EXPECT_EQ(a.collision_free_ego_trajectories, b.collision_free_ego_trajectories);
    EXPECT_EQ(a.ego_probability, b.ego_probability);
    EXPECT_EQ(a.ego_collision_probability, b.ego_collision_probability);
    ASSERT_EQ(a.escape_routes.size(), b.escape_routes.size());
    EXPECT_EQ(a.p_reference, b.p_reference);
    EXPECT_EQ(a.unavoidability, b.unavoidability);
    for (size_t k = 0; k < a.escape_routes.size(); ++k) {
      ExpectSameRoute(a.escape_routes[k], b.escape_routes[k], "no object in reach");
    }
    EXPECT_EQ(b.times.trajectory_ms, 0.0);  // no trajectory generated
    EXPECT_EQ(b.objects.size(), scene->vehicles.size());
  }
  EXPECT_GT(a.times.trajectory_ms, 0.0);  // the full estimate simulated every hypothesis
  ASSERT_EQ(a.objects.size(), 1u);
  const Result b = cut.Estimate(far);
  EXPECT_TRUE(b.objects[0].out_of_reach);
  EXPECT_EQ(b.objects[0].contribution, 0.0);
  EXPECT_EQ(b.objects[0].trajectories, 0);
}

TEST(ReachFilter, ResultSaysWhetherTheShortcutAnsweredIt) {
  // The flag callers (the SUMO driver) count shortcut answers by: true exactly when the
  // shortcut left no object and skipped the trajectories, on Estimate and on EstimateBatch
  // (the sequential path on one thread, the scene pool on two).
  Scene far;
  far.ego.state.speed_mps = 12.0;
  far.ego.lanes = bench::StraightThreeLanes();
  Vehicle v;
  v.id = "v";
  v.state.x_m = 500.0;
  v.state.speed_mps = 12.0;
  far.vehicles.push_back(v);
  Scene alone = far;  // no object at all: nothing left either
  alone.vehicles.clear();
  Scene near = far;  // 30 m ahead at the same speed: in reach, simulated
  near.vehicles[0].state.x_m = 30.0;
  Scene one_far_one_near = far;  // one left out, one left: still simulated
  one_far_one_near.vehicles.push_back(near.vehicles[0]);
  one_far_one_near.vehicles.back().id = "w";
  const std::vector<Scene> scenes{far, alone, near, one_far_one_near};
  for (int threads : {1, 2}) {
    EstimatorOptions full_opt, cut_opt;
    full_opt.threads = cut_opt.threads = threads;
    cut_opt.reach_shortcut = true;
    Estimator full(Params{}, full_opt), cut(Params{}, cut_opt);
    const std::string what = std::to_string(threads) + " threads";
    const Result far_cut = cut.Estimate(far);
    EXPECT_TRUE(far_cut.answered_by_reach_shortcut) << what;
    EXPECT_EQ(far_cut.times.trajectory_ms, 0.0) << what;  // it did skip the trajectories
    EXPECT_TRUE(cut.Estimate(alone).answered_by_reach_shortcut) << what;
    const Result near_cut = cut.Estimate(near);
    EXPECT_FALSE(near_cut.answered_by_reach_shortcut) << what;
    EXPECT_GT(near_cut.times.trajectory_ms, 0.0) << what;
    const Result mixed_cut = cut.Estimate(one_far_one_near);
    EXPECT_FALSE(mixed_cut.answered_by_reach_shortcut) << what;
    EXPECT_TRUE(mixed_cut.objects.at(0).out_of_reach) << what;  // the shortcut did drop one
    EXPECT_FALSE(full.Estimate(far).answered_by_reach_shortcut) << what;
    EXPECT_FALSE(full.Estimate(alone).answered_by_reach_shortcut) << what;

    const std::vector<Result> cut_batch = cut.EstimateBatch(scenes);
    const std::vector<Result> full_batch = full.EstimateBatch(scenes);
    ASSERT_EQ(cut_batch.size(), scenes.size());
    ASSERT_EQ(full_batch.size(), scenes.size());
    EXPECT_TRUE(cut_batch[0].answered_by_reach_shortcut) << what;
    EXPECT_TRUE(cut_batch[1].answered_by_reach_shortcut) << what;
    EXPECT_FALSE(cut_batch[2].answered_by_reach_shortcut) << what;
    EXPECT_FALSE(cut_batch[3].answered_by_reach_shortcut) << what;
    for (const Result& r : full_batch) EXPECT_FALSE(r.answered_by_reach_shortcut) << what;
    // A batch of one goes another way (every thread on it): the flag must be set there too.
    EXPECT_TRUE(cut.EstimateBatch({far}).at(0).answered_by_reach_shortcut) << what;
    EXPECT_FALSE(cut.EstimateBatch({near}).at(0).answered_by_reach_shortcut) << what;
  }
}

}  // namespace
}  // namespace criticality
