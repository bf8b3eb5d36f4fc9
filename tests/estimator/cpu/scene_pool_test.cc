// Estimator::EstimateBatch on the cpu backend's scene pool (cpu/scene_pool.h): a batch spread
// over worker threads gives every scene exactly its own Estimate(), in batch order, on any
// thread count, and an invalid scene's exception reaches the caller.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "../test_scenes.h"
#include "bench/discrimination_scenes.h"
#include "bench/paper_scenes.h"
#include "criticality/errors.h"
#include "criticality/estimator.h"

namespace criticality {
namespace {

// Small enough for a quick test (3 * 100 steps * 343 paths: still split over threads when
// alone in a batch).
Params SmallParams() {
  Params p;
  p.profiles = 3;
  return p;
}

// An ego with one vehicle 500 m ahead: out of reach, so the reach shortcut answers it.
Scene FarScene() {
  Scene s;
  s.ego.state.speed_mps = 12.0;
  s.ego.lanes = bench::StraightThreeLanes();
  Vehicle v;
  v.id = "far";
  v.state.x_m = 500.0;
  v.state.speed_mps = 12.0;
  s.vehicles.push_back(v);
  return s;
}

// Nine different scenes: more than four workers' first chunks of two, the last chunk partial.
// Of every kind: the paper's scenes, seeded random ones with pedestrians and crossing traffic,
// an ego alone, one answered by the reach shortcut, designed critical ones.
std::vector<Scene> MixedScenes() {
  std::vector<Scene> scenes{bench::PaperSceneS1(),
                            testing::RandomScene(3, 3, 1, true),
                            testing::RandomScene(10, 0, 0, false),
                            testing::RandomScene(7, 6, 2, true),
                            FarScene(),
                            bench::PaperSceneS2(),
                            testing::RandomScene(11, 4, 2, false)};
  for (const bench::DiscriminationScene& d : bench::DiscriminationScenes()) {
    if (d.name == "junction-car-crosses-ttc-1.3" || d.name == "pedestrian-crosses-ttc-1.2")
      scenes.push_back(d.scene);
  }
  return scenes;
}

EstimatorOptions Options(int threads, bool reach_shortcut) {
  EstimatorOptions o;
  o.threads = threads;
  o.reach_shortcut = reach_shortcut;
  o.keep_pair_matrix = true;  // the pair matrix must be the worker's, not lost on the way back
  return o;
}

// Every output but the times, bit for bit.
void ExpectSameEstimate(const Result& a, const Result& b, const std::string& what) {
  EXPECT_EQ(a.p_collision, b.p_collision) << what;
  EXPECT_EQ(a.p_reference, b.p_reference) << what;
  EXPECT_EQ(a.reference_ego_trajectory, b.reference_ego_trajectory) << what;
  EXPECT_EQ(a.unavoidability, b.unavoidability) << what;
  EXPECT_EQ(a.first_collision_pmf, b.first_collision_pmf) << what;
  EXPECT_EQ(a.collision_free_ego_trajectories, b.collision_free_ego_trajectories) << what;
  EXPECT_EQ(a.ego_probability, b.ego_probability) << what;
  EXPECT_EQ(a.ego_collision_probability, b.ego_collision_probability) << what;
  EXPECT_EQ(a.first_collision_step, b.first_collision_step) << what;
  EXPECT_EQ(a.answered_by_reach_shortcut, b.answered_by_reach_shortcut) << what;
  EXPECT_EQ(a.counts.ego_trajectories, b.counts.ego_trajectories) << what;
  EXPECT_EQ(a.counts.co_trajectories, b.counts.co_trajectories) << what;
  EXPECT_EQ(a.counts.pose_combinations, b.counts.pose_combinations) << what;
  ASSERT_EQ(a.objects.size(), b.objects.size()) << what;
  for (size_t o = 0; o < a.objects.size(); ++o) {
    const ObjectResult &x = a.objects[o], &y = b.objects[o];
    EXPECT_EQ(x.id, y.id) << what;
    EXPECT_EQ(x.contribution, y.contribution) << what << " " << x.id;
    EXPECT_EQ(x.first_trajectory, y.first_trajectory) << what << " " << x.id;
    EXPECT_EQ(x.trajectories, y.trajectories) << what << " " << x.id;
    EXPECT_EQ(x.lane, y.lane) << what << " " << x.id;
    EXPECT_EQ(x.out_of_reach, y.out_of_reach) << what << " " << x.id;
  }
  ASSERT_EQ(a.escape_routes.size(), b.escape_routes.size()) << what;
  for (size_t e = 0; e < a.escape_routes.size(); ++e) {
    const EscapeRoute &x = a.escape_routes[e], &y = b.escape_routes[e];
    const std::string route = what + " route " + std::to_string(e);
    EXPECT_EQ(x.ego_trajectory, y.ego_trajectory) << route;
    EXPECT_EQ(x.probability, y.probability) << route;
    EXPECT_EQ(x.collision_probability, y.collision_probability) << route;
    EXPECT_EQ(x.sections, y.sections) << route;
    EXPECT_EQ(x.speed_mps, y.speed_mps) << route;
    EXPECT_EQ(x.steer_rad, y.steer_rad) << route;
    EXPECT_EQ(x.x_m, y.x_m) << route;
    EXPECT_EQ(x.y_m, y.y_m) << route;
  }
}

TEST(ScenePool, BatchGivesEverySceneItsOwnEstimateOnAnyThreadCount) {
  const Params params = SmallParams();
  const std::vector<Scene> scenes = MixedScenes();
  ASSERT_EQ(scenes.size(), 9u) << "discrimination scenes renamed?";
  const std::vector<Scene> reversed(scenes.rbegin(), scenes.rend());
  for (bool reach_shortcut : {false, true}) {
    // The oracle: one estimate after the other on one thread.
    std::vector<Result> one_by_one;
    Estimator single(params, Options(1, reach_shortcut));
    for (const Scene& s : scenes) one_by_one.push_back(single.Estimate(s));
    // The scenes' results differ pairwise, so a result in another scene's place (or a scene
    // left out, or estimated twice) cannot pass the comparison below.
    for (size_t i = 0; i < scenes.size(); ++i) {
      for (size_t j = 0; j < i; ++j) {
        const Result &a = one_by_one[i], &b = one_by_one[j];
        EXPECT_FALSE(a.p_collision == b.p_collision && a.objects.size() == b.objects.size() &&
                     a.counts.co_trajectories == b.counts.co_trajectories &&
                     a.ego_probability == b.ego_probability)
            << "scenes " << j << " and " << i << " look alike";
      }
    }
    EXPECT_EQ(one_by_one[4].answered_by_reach_shortcut, reach_shortcut);

    for (int threads : {1, 2, 4}) {
      Estimator estimator(params, Options(threads, reach_shortcut));
      ASSERT_EQ(estimator.threads(), threads);
      const std::string what = std::to_string(threads) + " threads, reach shortcut " +
                               (reach_shortcut ? "on" : "off") + ", scene ";
      const std::vector<Result> batch = estimator.EstimateBatch(scenes);
      ASSERT_EQ(batch.size(), scenes.size());
      for (size_t k = 0; k < scenes.size(); ++k) {
        ExpectSameEstimate(batch[k], one_by_one[k], what + std::to_string(k));
      }
      // The same pool again, on another order: nothing of the first batch is left over (the
      // hand-out position, the results, the workers' estimators' buffers).
      const std::vector<Result> back = estimator.EstimateBatch(reversed);
      ASSERT_EQ(back.size(), scenes.size());
      for (size_t k = 0; k < scenes.size(); ++k) {
        ExpectSameEstimate(back[scenes.size() - 1 - k], one_by_one[k],
                           what + std::to_string(k) + " (reversed batch)");
      }
      // A batch of one, a batch of two (one chunk: one worker busy, the others idle) and an
      // empty batch.
      ExpectSameEstimate(estimator.EstimateBatch({scenes[5]}).at(0), one_by_one[5],
                         what + "5 alone");
      const std::vector<Result> two = estimator.EstimateBatch({scenes[3], scenes[0]});
      ASSERT_EQ(two.size(), 2u);
      ExpectSameEstimate(two[0], one_by_one[3], what + "3 of two");
      ExpectSameEstimate(two[1], one_by_one[0], what + "0 of two");
      EXPECT_TRUE(estimator.EstimateBatch({}).empty());
    }
  }
}

TEST(ScenePool, AFleetWhoseScenesShareTheirVehiclesGivesEverySceneItsOwnEstimate) {
  // Each vehicle is an object in six of the seven scenes: the batch simulates each once
  // (EstimatorOptions::shared_object_paths_mib, on by default) and copies it to the others,
  // whichever worker got there first (with the reach shortcut, the oncoming "g" starts beyond
  // most egos' final reach: the shortcut simulates and stores it, and the backend copies it
  // where it is kept); every scene must still get its own estimate.
  const Params params = SmallParams();
  const std::vector<Scene> scenes = testing::FleetScenes();
  EstimatorOptions unshared = Options(1, false);
  unshared.shared_object_paths_mib = 0;
  std::vector<Result> one_by_one;
  Estimator single(params, unshared);
  for (const Scene& s : scenes) one_by_one.push_back(single.Estimate(s));
  double p_max = 0.0;
  for (const Result& r : one_by_one) p_max = std::max(p_max, r.p_collision);
  EXPECT_GT(p_max, 0.0) << "the fleet should have collisions to get right";
  for (int threads : {1, 2, 4}) {
    for (bool reach_shortcut : {false, true}) {
      Estimator estimator(params, Options(threads, reach_shortcut));
      for (int round = 0; round < 2; ++round) {  // the second batch after the first's clear
        const std::vector<Result> batch = estimator.EstimateBatch(scenes);
        ASSERT_EQ(batch.size(), scenes.size());
        for (size_t k = 0; k < scenes.size(); ++k) {
          Result expected = one_by_one[k];
          if (reach_shortcut) expected = Estimator(params, Options(1, true)).Estimate(scenes[k]);
          ExpectSameEstimate(batch[k], expected,
                             std::to_string(threads) + " threads, round " + std::to_string(round) +
                                 ", scene " + std::to_string(k));
        }
      }
    }
  }
}

TEST(ScenePool, SmallSingleSceneGivesItsOwnEstimate) {
  // Two path sample instants: 3 * 100 * 49 ego hypothesis steps, small enough that a batch of
  // one runs on one thread instead of every thread; the result must not show which.
  Params params = SmallParams();
  params.path_sample_times_s = {1.0, 2.0};
  const Scene scene = bench::PaperSceneS1();
  const Result expected = Estimator(params, Options(1, false)).Estimate(scene);
  for (int threads : {2, 4}) {
    Estimator estimator(params, Options(threads, false));
    ExpectSameEstimate(estimator.EstimateBatch({scene}).at(0), expected,
                       std::to_string(threads) + " threads");
    EXPECT_EQ(estimator.Estimate(scene).p_collision, expected.p_collision);
  }
}

// The message Estimate() gives for an invalid scene.
std::string ErrorOf(const Params& params, const Scene& scene) {
  try {
    Estimator(params, Options(1, false)).Estimate(scene);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ScenePool, InvalidSceneInABatchThrowsToTheCaller) {
  const Params params = SmallParams();
  std::vector<Scene> valid = MixedScenes();
  valid.resize(7);
  Scene bad_speed = valid[1];
  bad_speed.ego.state.speed_mps = -1.0;
  Scene bad_vehicle = valid[0];  // S1: three vehicles
  bad_vehicle.vehicles.at(0).state.x_m = std::nan("");
  const std::string speed_error = ErrorOf(params, bad_speed);
  const std::string vehicle_error = ErrorOf(params, bad_vehicle);
  ASSERT_FALSE(speed_error.empty());
  ASSERT_FALSE(vehicle_error.empty());
  ASSERT_NE(speed_error, vehicle_error);

  std::vector<Result> expected;
  Estimator single(params, Options(1, false));
  for (const Scene& s : valid) expected.push_back(single.Estimate(s));

  for (int threads : {1, 2, 4}) {
    Estimator estimator(params, Options(threads, false));
    // The invalid scene in the caller's first chunk, in the middle and last: whichever worker
    // meets it, its exception must come out of EstimateBatch (not end the process from a pool
    // thread, not be swallowed into a default result).
    for (size_t at : {size_t{0}, size_t{3}, valid.size() - 1}) {
      std::vector<Scene> batch = valid;
      batch[at] = bad_speed;
      const std::string what =
          std::to_string(threads) + " threads, invalid at " + std::to_string(at);
      try {
        estimator.EstimateBatch(batch);
        ADD_FAILURE() << what << ": no exception";
      } catch (const InputError& e) {
        EXPECT_EQ(e.what(), speed_error) << what;
      }
    }
    // Two invalid scenes in chunks that workers hold at the same time: the first in batch
    // order is reported, whichever failed first. Behind a slow scene (S2) the first one fails
    // last in time (a pool keeping the first error it saw would report the other); behind a
    // quicker one (S1) than the second's (S2) it fails first (a pool keeping the last error
    // it saw would report the other).
    std::vector<Scene> first_fails_last = valid;  // chunks {S2, bad}, {bad, ...}
    first_fails_last[2] = bench::PaperSceneS2();
    first_fails_last[3] = bad_speed;
    first_fails_last[4] = bad_vehicle;
    std::vector<Scene> first_fails_first = valid;  // chunks {S1, bad}, {S2, bad}
    first_fails_first[2] = bench::PaperSceneS1();
    first_fails_first[3] = bad_speed;
    first_fails_first[4] = bench::PaperSceneS2();
    first_fails_first[5] = bad_vehicle;
    for (const std::vector<Scene>* batch : {&first_fails_last, &first_fails_first}) {
      for (int repeat = 0; repeat < 5; ++repeat) {
        try {
          estimator.EstimateBatch(*batch);
          ADD_FAILURE() << threads << " threads: no exception";
        } catch (const InputError& e) {
          EXPECT_EQ(e.what(), speed_error) << threads << " threads";
        }
      }
    }
    // The estimator still works after failed batches, with nothing of them left over.
    const std::vector<Result> after = estimator.EstimateBatch(valid);
    ASSERT_EQ(after.size(), valid.size());
    for (size_t k = 0; k < valid.size(); ++k) {
      ExpectSameEstimate(
          after[k], expected[k],
          std::to_string(threads) + " threads, after failures, scene " + std::to_string(k));
    }
  }
}

}  // namespace
}  // namespace criticality
