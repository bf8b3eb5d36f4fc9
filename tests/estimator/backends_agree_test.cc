// Every fast path is checked against the plain reference on the same inputs: the CPU fast path
// (scalar, EstimatorOptions::simd false; the SIMD lanes are checked in
// cpu/sibling_steps_test.cc) must give the same pair matrix (colliding pairs and first-collision steps), hence the same
// risk outputs, bit for bit, on every scene family (S1, S2, the seeded random family, the
// discrimination scenes, crowded scenes without collisions), with the default parameters, the
// paper-literal ones and parameters that move the fast path's step partition (odd sampling
// instants, four instants, another step, a shorter horizon).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "bench/discrimination_scenes.h"
#include "bench/paper_scenes.h"
#include "criticality/estimator.h"
#include "test_scenes.h"

namespace criticality {
namespace {

// Returns the number of colliding pairs, so callers can check what their scenes exercise.
size_t ExpectSameResult(const Scene& scene, const Params& params, const std::string& what) {
  EstimatorOptions ref_opt, cpu_opt;
  ref_opt.backend = Backend::kReference;
  ref_opt.keep_pair_matrix = cpu_opt.keep_pair_matrix = true;
  cpu_opt.backend = Backend::kCpu;
  cpu_opt.threads = 2;
  cpu_opt.simd = false;  // the scalar fast path; the SIMD one: cpu/sibling_steps_test.cc
  Estimator reference(params, ref_opt), cpu(params, cpu_opt);
  const Result a = reference.Estimate(scene);
  const Result b = cpu.Estimate(scene);
  EXPECT_EQ(a.first_collision_step.size(), b.first_collision_step.size()) << what;
  if (a.first_collision_step.size() != b.first_collision_step.size()) return 0;
  size_t differing = 0;
  for (size_t k = 0; k < a.first_collision_step.size(); ++k) {
    differing += a.first_collision_step[k] != b.first_collision_step[k];
  }
  EXPECT_EQ(differing, 0u) << what;
  // Same pair matrix, same host risk code: the outputs are bit-identical.
  EXPECT_EQ(a.p_collision, b.p_collision) << what;
  EXPECT_EQ(a.p_reference, b.p_reference) << what;
  EXPECT_EQ(a.unavoidability, b.unavoidability) << what;
  EXPECT_EQ(a.collision_free_ego_trajectories, b.collision_free_ego_trajectories) << what;
  EXPECT_EQ(a.first_collision_pmf, b.first_collision_pmf) << what;
  EXPECT_EQ(a.escape_routes.size(), b.escape_routes.size()) << what;
  for (size_t k = 0; k < a.escape_routes.size() && k < b.escape_routes.size(); ++k) {
    EXPECT_EQ(a.escape_routes[k].ego_trajectory, b.escape_routes[k].ego_trajectory) << what;
  }
  size_t colliding = 0;
  for (std::int16_t s : a.first_collision_step) colliding += s > 0;
  return colliding;
}

// Crowded but collision-free: twelve cars around the ego on a three-lane motorway (25 m/s),
// those ahead faster (33-35 m/s), those behind slower (15-18 m/s), 12-45 m away. No hypothesis
// pair can collide within 2 s (the ego at full power gains at most 6 m on a car ahead braking
// at 9.7 m/s^2, a car behind at full power at most 8 m on the ego braking), yet every car is
// within reach of the bounding tests, so the fast path's pruning is exercised.
Scene CrowdedCollisionFree(unsigned variant) {
  Scene s;
  s.ego.state.speed_mps = 25.0;
  s.ego.lanes = bench::StraightThreeLanes();
  const double shift = 3.0 * variant;
  for (int lane = -1; lane <= 1; ++lane) {
    for (int k = 0; k < 2; ++k) {
      Vehicle ahead, behind;
      ahead.id = "ahead" + std::to_string(lane) + std::to_string(k);
      ahead.state.x_m = 4.5 + 14.0 + 28.0 * k + shift + 2.0 * lane;
      ahead.state.y_m = 3.5 * lane;
      ahead.state.speed_mps = 33.0 + k + 0.5 * variant;
      behind.id = "behind" + std::to_string(lane) + std::to_string(k);
      behind.state.x_m = -(4.5 + 13.0 + 30.0 * k + shift - 1.5 * lane);
      behind.state.y_m = 3.5 * lane;
      behind.state.speed_mps = 18.0 - 2.0 * k - 0.5 * variant;
      if (variant == 1) ahead.lanes = bench::StraightThreeLanes();  // own lanes, not associated
      s.vehicles.push_back(ahead);
      s.vehicles.push_back(behind);
    }
  }
  return s;
}

struct Variant {
  std::string name;
  Params params;
  /** S1 and S2 have colliding pairs (not within a 1.2 s horizon: their cars are too far). */
  bool paper_scenes_collide{true};
  /** Which crowded scenes are collision-free: both with drivable hypotheses; with the
   *  paper-literal ones (+1 g at any speed, no grip limit) the denser one collides. */
  std::vector<bool> crowded_collision_free{true, true};
};

std::vector<Variant> Variants() {
  std::vector<Variant> v{{"default", Params{}},
                         {"paper-literal", ParamsPreset("paper-literal"), true, {false, true}}};
  Params odd;
  odd.path_sample_times_s = {0.37, 1.13, 1.71};
  v.push_back({"odd sample instants 0.37/1.13/1.71 s", odd});
  Params four;
  four.path_sample_times_s = {0.5, 1.0, 1.5, 2.0};
  four.neighbour_lane_samples = 1;  // 5^4 = 625 ego paths
  v.push_back({"four sample instants", four});
  Params coarse;
  coarse.step_s = 0.05;
  v.push_back({"step 0.05 s", coarse});
  Params shorter;
  shorter.horizon_s = 1.2;
  shorter.path_sample_times_s = {0.4, 0.8, 1.2};
  v.push_back({"horizon 1.2 s", shorter, false});
  Params odd_step;
  odd_step.step_s = 0.03;
  odd_step.horizon_s = 1.5;
  odd_step.path_sample_times_s = {0.31, 0.77, 1.49};
  v.push_back({"step 0.03 s, horizon 1.5 s, odd instants", odd_step});
  // The paper's ablations: open-loop steering per section, and virtual lanes only.
  Params open_loop;
  open_loop.lateral_controller = false;
  v.push_back({"lateral controller off", open_loop});
  Params no_road;
  no_road.road_model = false;
  v.push_back({"road model off", no_road});
  return v;
}

// Every scene family under one parameter variant.
void ExpectFamiliesAgree(const Variant& v) {
  const std::string tag = " (" + v.name + ")";
  const size_t s1 = ExpectSameResult(bench::PaperSceneS1(), v.params, "S1" + tag);
  const size_t s2 = ExpectSameResult(bench::PaperSceneS2(), v.params, "S2" + tag);
  EXPECT_EQ(s1 > 0, v.paper_scenes_collide) << tag;
  EXPECT_EQ(s2 > 0, v.paper_scenes_collide) << tag;
  // Dense and sparse, with pedestrians, crossing and oncoming traffic; the ego alone.
  int with_collisions = 0;
  for (unsigned seed = 1; seed <= 10; ++seed) {
    const int max_objects = seed <= 8 ? 4 : 0;  // seeds 9 and 10: the ego alone
    const size_t colliding =
        ExpectSameResult(testing::RandomScene(seed, max_objects, max_objects / 2, seed % 2 == 0),
                         v.params, "seed " + std::to_string(seed) + tag);
    with_collisions += colliding > 0;
  }
  EXPECT_GE(with_collisions, 3) << tag;  // or agreement would prove little
  int picked = 0;
  for (const bench::DiscriminationScene& d : bench::DiscriminationScenes()) {
    if (d.name == "stopped-car-ttc-1.50" || d.name == "motorway-neighbours-alongside" ||
        d.name == "pedestrian-crosses-ttc-1.2" || d.name == "junction-car-crosses-ttc-1.3" ||
        d.name == "cut-in-ttc-1.0" || d.name == "pedestrians-on-sidewalks") {
      ExpectSameResult(d.scene, v.params, d.name + tag);
      ++picked;
    }
  }
  EXPECT_EQ(picked, 6) << "discrimination scenes renamed?";
  // Crowded without collisions: a fast path that invents collisions fails here.
  for (unsigned variant = 0; variant < 2; ++variant) {
    const size_t colliding = ExpectSameResult(CrowdedCollisionFree(variant), v.params,
                                              "crowded " + std::to_string(variant) + tag);
    EXPECT_EQ(colliding == 0, v.crowded_collision_free[variant]) << "crowded " << variant << tag;
  }
}

TEST(BackendsAgree, DefaultParams) { ExpectFamiliesAgree(Variants()[0]); }
TEST(BackendsAgree, PaperLiteral) { ExpectFamiliesAgree(Variants()[1]); }
TEST(BackendsAgree, OddSampleInstants) { ExpectFamiliesAgree(Variants()[2]); }
TEST(BackendsAgree, FourSampleInstants) { ExpectFamiliesAgree(Variants()[3]); }
TEST(BackendsAgree, AnotherStep) { ExpectFamiliesAgree(Variants()[4]); }
TEST(BackendsAgree, ShorterHorizon) { ExpectFamiliesAgree(Variants()[5]); }
TEST(BackendsAgree, OddStepHorizonAndInstants) { ExpectFamiliesAgree(Variants()[6]); }
TEST(BackendsAgree, LateralControllerOff) { ExpectFamiliesAgree(Variants()[7]); }
TEST(BackendsAgree, RoadModelOff) { ExpectFamiliesAgree(Variants()[8]); }

// Long bodies (Vehicle::carriages): every carriage is a hypothesis set checked like any box,
// folded into its vehicle's columns on the host, so the reference and the fast path must agree
// on the folded matrix as on any other. Scenes: the seeded random family with two boxes behind
// every other vehicle (a truck's trailer: the vehicle's paths; a rail vehicle's carriages: its
// track), a train crossing ahead of an approaching ego, trucks with trailers alongside it.
Scene WithCarriages(Scene s) {
  for (size_t i = 0; i < s.vehicles.size(); i += 2) {
    Vehicle& v = s.vehicles[i];
    if (i % 4 == 2) v.type.road_user = RoadUser::kRail;
    double rear = -0.5 * v.length_m;
    for (int k = 0; k < 2; ++k) {
      Carriage c;
      c.length_m = 8.0 + 2.0 * k;
      c.width_m = v.width_m;
      const double back = rear - 0.5 - 0.5 * c.length_m;  // along its heading, behind it
      c.x_m = v.state.x_m + back * std::cos(v.state.yaw_rad);
      c.y_m = v.state.y_m + back * std::sin(v.state.yaw_rad);
      c.yaw_rad = v.state.yaw_rad;
      if (v.lanes && k == 0) c.lanes = v.lanes;  // the same road, seen from nearly the same place
      v.carriages.push_back(c);
      rear = back - 0.5 * c.length_m;
    }
  }
  return s;
}

Scene TrainCrossingAhead() {
  Scene s;
  s.ego.lanes = bench::StraightThreeLanes();
  s.ego.state.speed_mps = 8.0;
  Vehicle t;
  t.id = "train";
  t.state.x_m = 18.0;
  t.state.y_m = 30.0;
  t.state.yaw_rad = 1.5707963267948966;
  t.state.speed_mps = 6.0;
  t.length_m = 20.0;
  t.width_m = 2.9;
  t.type.road_user = RoadUser::kRail;
  for (int k = 1; k <= 4; ++k) {
    Carriage c;
    c.x_m = 18.0;
    c.y_m = 30.0 - 19.0 * k;
    c.yaw_rad = t.state.yaw_rad;
    c.length_m = 18.0;
    c.width_m = 2.9;
    t.carriages.push_back(c);
  }
  s.vehicles.push_back(t);
  return s;
}

Scene TrailersAlongside() {
  Scene s = bench::PaperSceneS1();
  for (Vehicle& v : s.vehicles) {
    v.type.road_user = RoadUser::kHeavy;
    Carriage c;
    c.x_m = v.state.x_m - 0.5 * v.length_m - 0.5 - 6.8;
    c.y_m = v.state.y_m;
    c.length_m = 13.6;
    c.width_m = 2.55;
    c.lanes = v.lanes;
    v.carriages.push_back(c);
  }
  return s;
}

TEST(BackendsAgree, ScenesWithCarriages) {
  for (const Variant& v : {Variants()[0], Variants()[1], Variants()[7]}) {
    const std::string tag = " (" + v.name + ")";
    int with_collisions = 0;
    for (unsigned seed = 1; seed <= 8; ++seed) {
      const Scene scene = WithCarriages(testing::RandomScene(seed, 4, 2, seed % 2 == 0));
      with_collisions +=
          ExpectSameResult(scene, v.params, "seed " + std::to_string(seed) + tag) > 0;
    }
    EXPECT_GE(with_collisions, 3) << tag;
    EXPECT_GT(ExpectSameResult(TrainCrossingAhead(), v.params, "train crossing" + tag), 0u);
    EXPECT_GT(ExpectSameResult(TrailersAlongside(), v.params, "trailers" + tag), 0u);
  }
}

// Bodies on their path (Scene::bodies_on_path) in turning scenes: the same pair matrix.
TEST(BackendsAgree, BodiesOnTheirPath) {
  int with_collisions = 0, changed = 0;
  for (unsigned seed = 1; seed <= 8; ++seed) {
    Scene scene = testing::RandomScene(seed, 4, 2, seed % 2 == 0);
    scene.ego.state.yaw_rate_radps = 0.25;
    for (Vehicle& v : scene.vehicles) v.state.yaw_rate_radps = -0.3;
    const double tangent = testing::PCollision(scene);
    scene.bodies_on_path = true;
    with_collisions += ExpectSameResult(scene, Params{}, "seed " + std::to_string(seed)) > 0;
    changed += testing::PCollision(scene) != tangent;
  }
  EXPECT_GE(with_collisions, 3);
  EXPECT_GE(changed, 1);  // the switch reaches the backends
}

// Bodies on their way (Vehicle::way): every vehicle of the random family given a tight right
// turn ahead of it as its way; the same pair matrix.
TEST(BackendsAgree, BodiesOnTheirWay) {
  // With one path on the way (the default) and with their lanes' lateral paths beside it
  // (the experiment Params::way_lateral_paths).
  Params one_path, lateral;
  lateral.way_lateral_paths = true;
  int with_collisions = 0, changed = 0, lateral_changed = 0;
  for (unsigned seed = 1; seed <= 8; ++seed) {
    const Scene plain = testing::RandomScene(seed, 4, 2, seed % 2 == 0);
    const double free = testing::PCollision(plain);
    const Scene scene = testing::WithTurningWays(plain, 3.0 + seed % 3);
    with_collisions += ExpectSameResult(scene, Params{}, "seed " + std::to_string(seed)) > 0;
    ExpectSameResult(scene, lateral, "lateral paths, seed " + std::to_string(seed));
    changed += testing::PCollision(scene) != free;
    lateral_changed += testing::PCollision(scene, lateral) != testing::PCollision(scene, one_path);
  }
  EXPECT_GE(with_collisions, 3);
  EXPECT_GE(changed, 1);          // the ways reach the backends
  EXPECT_GE(lateral_changed, 1);  // and so do the paths beside them
}

// The experiment Params::ego_on_way: an ego in a tight turn moves along its way, on one path
// or (with way_lateral_paths) its path tree beside it, on the scalar path; the CPU's
// out-of-reach skips (from the ego's reach bound, widened for a body on its way) must leave
// the reference's pair matrix as it is.
TEST(BackendsAgree, AnEgoOnItsWay) {
  for (const bool lateral : {false, true}) {
    Params on;
    on.ego_on_way = true;
    on.way_lateral_paths = lateral;
    const std::string tag = lateral ? "ego on way, lateral paths, seed " : "ego on way, seed ";
    int with_collisions = 0, changed = 0;
    for (unsigned seed = 1; seed <= 8; ++seed) {
      Scene scene =
          testing::WithTurningWays(testing::RandomScene(seed, 4, 2, seed % 2 == 0), 3.0);
      scene.ego.way = testing::TurningWay(scene.ego.length_m, 2.0 + seed % 3);
      with_collisions += ExpectSameResult(scene, on, tag + std::to_string(seed)) > 0;
      Params others_only = on;  // the other vehicles' paths as `on`, the ego steered
      others_only.ego_on_way = false;
      changed += testing::PCollision(scene, on) != testing::PCollision(scene, others_only);
    }
    EXPECT_GE(with_collisions, 3) << tag;
    EXPECT_GE(changed, 1) << tag;  // the ego's way reaches the backends
  }
}

// Poses held between the world's steps (Params::collisions_at_world_steps): the fast path skips
// the box tests of blocks that only repeat poses tested before; the pair matrix must stay the
// reference's, scalar and SIMD, whether the world's step is a multiple of the blocks or not.
TEST(BackendsAgree, PosesHeldBetweenTheWorldsSteps) {
  for (const double world_step : {1.0, 0.5, 0.3, 0.06}) {  // 50, 25, 15 and 3 steps of 20 ms
    const std::string tag = " (world step " + std::to_string(world_step) + " s)";
    int with_collisions = 0, changed = 0;
    for (unsigned seed = 1; seed <= 8; ++seed) {
      Scene scene = testing::RandomScene(seed, 4, 2, seed % 2 == 0);
      const double every_step = testing::PCollision(scene);
      scene.euler_update_step_s = world_step;
      const std::string what = "seed " + std::to_string(seed) + tag;
      with_collisions += ExpectSameResult(scene, Params{}, what) > 0;
      // The SIMD lanes (trig within a few ulp of libm): the same p to 1e-6. PCollision runs
      // the default backend, the CPU's with SIMD lanes.
      EstimatorOptions ref_opt;
      ref_opt.backend = Backend::kReference;
      const double simd_p = testing::PCollision(scene);
      EXPECT_NEAR(Estimator(Params{}, ref_opt).Estimate(scene).p_collision, simd_p, 1e-6)
          << what << ", SIMD";
      changed += simd_p != every_step;
    }
    EXPECT_GE(with_collisions, 3) << tag;
    EXPECT_GE(changed, 1) << tag;  // the world's step reaches the backends
    for (const bench::DiscriminationScene& d : bench::DiscriminationScenes()) {
      Scene scene = d.scene;
      scene.euler_update_step_s = world_step;
      ExpectSameResult(scene, Params{}, d.name + tag);
    }
  }
}

// Params::euler_stops with held poses: a hypothesis whose speed is 0 at a world step keeps the
// pose of the world's previous step, on the scalar path, the SIMD lanes (StorePoses) and the
// reference alike; it must change p on some scene (so that the comparison could fail).
TEST(BackendsAgree, StoppedBodiesStayAtTheWorldsSteps) {
  Params stops;
  stops.euler_stops = true;
  int with_collisions = 0, changed = 0;
  for (const double world_step : {1.0, 0.5}) {
    for (unsigned seed = 1; seed <= 8; ++seed) {
      Scene scene = testing::RandomScene(seed, 4, 2, seed % 2 == 0);
      scene.euler_update_step_s = world_step;
      const std::string what = "seed " + std::to_string(seed) + ", world step " +
                                std::to_string(world_step) + ", stopped bodies stay";
      with_collisions += ExpectSameResult(scene, stops, what) > 0;
      EstimatorOptions ref_opt;
      ref_opt.backend = Backend::kReference;
      const double simd_p = testing::PCollision(scene, stops);
      EXPECT_NEAR(Estimator(stops, ref_opt).Estimate(scene).p_collision, simd_p, 1e-6) << what;
      changed += simd_p != testing::PCollision(scene);
    }
  }
  EXPECT_GE(with_collisions, 3);
  EXPECT_GE(changed, 1);
}

TEST(BackendsAgree, AllDiscriminationScenes) {
  for (const bench::DiscriminationScene& d : bench::DiscriminationScenes()) {
    ExpectSameResult(d.scene, Params{}, d.name);
  }
}

}  // namespace
}  // namespace criticality
