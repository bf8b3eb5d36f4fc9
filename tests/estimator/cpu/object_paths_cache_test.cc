// Other road users simulated once per batch (cpu/object_paths_cache.h, EstimatorOptions::
// shared_object_paths_mib): a set another scene simulated is copied, and the copy must give
// each scene exactly what simulating it there gives (poses, cos/sin, block bounds, so the pair
// matrix); a set that differs in any value must be simulated; nothing is stored beyond the
// capacity.
#include "cpu/object_paths_cache.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "../test_scenes.h"
#include "cpu/cpu_backend.h"
#include "criticality/errors.h"
#include "src/problem.h"
#include "src/reach_filter.h"

namespace criticality {
namespace {

// The fleet, and one more scene: the first one with its first object 1 mm/s faster (a set
// that differs from a stored one in one value).
std::vector<Scene> FleetAndANearTwin() {
  std::vector<Scene> scenes = testing::FleetScenes();
  Scene twin = scenes[0];
  twin.vehicles.at(0).state.speed_mps += 1e-3;
  scenes.push_back(twin);
  return scenes;
}

// Runs every scene through `shared` (with a cache) and `own` (without): the objects'
// trajectories and the pair matrix must be the same bit for bit. Returns the lookups that
// should have found a stored set (sets whose key an earlier scene had).
long long ExpectSharedMatchesOwn(const std::vector<Scene>& scenes, bool simd,
                                 internal::ObjectPathsCache* cache) {
  CpuBackend shared(1, simd), own(1, simd);
  shared.ShareObjectPaths(cache);
  const Params params;
  std::set<std::string> seen;
  long long repeats = 0;
  size_t colliding = 0;
  for (size_t k = 0; k < scenes.size(); ++k) {
    const internal::Problem pb = internal::BuildProblem(scenes[k], params);
    for (const core::HypothesisSet& h : pb.cos)
      repeats += !seen.insert(internal::ObjectPathsCache::KeyOf(h, pb.sim, simd ? 1 : 0)).second;
    shared.GenerateTrajectories(pb);
    own.GenerateTrajectories(pb);
    const std::string what = "scene " + std::to_string(k) + (simd ? " simd" : " scalar");
    EXPECT_EQ(shared.CoTrajectories().x, own.CoTrajectories().x) << what;
    EXPECT_EQ(shared.CoTrajectories().y, own.CoTrajectories().y) << what;
    EXPECT_EQ(shared.CoTrajectories().yaw, own.CoTrajectories().yaw) << what;
    std::vector<std::int16_t> a, b;
    shared.RecognizeCollisions(pb, &a);
    own.RecognizeCollisions(pb, &b);
    EXPECT_EQ(a, b) << what;
    for (std::int16_t s : b) colliding += s > 0;
  }
  EXPECT_GT(colliding, 0u) << "the fleet should have colliding pairs to compare";
  return repeats;
}

TEST(ObjectPathsCache, AnObjectAnotherSceneSimulatedIsCopiedAndGivesTheSamePairMatrix) {
  const std::vector<Scene> scenes = FleetAndANearTwin();
  for (bool simd : {true, false}) {
    internal::ObjectPathsCache cache(64u << 20);
    const long long repeats = ExpectSharedMatchesOwn(scenes, simd, &cache);
    // Seven vehicles, each an object in six fleet scenes: 42 sets, 7 distinct; the twin brings
    // one new set (the faster object) and five repeats.
    EXPECT_EQ(repeats, 35 + 5);
    EXPECT_EQ(cache.Hits(), repeats) << (simd ? "simd" : "scalar");
    EXPECT_EQ(cache.Misses(), 7 * 6 + 6 - repeats) << (simd ? "simd" : "scalar");
  }
}

TEST(ObjectPathsCache, NothingIsStoredBeyondTheCapacityAndClearForgetsEverything) {
  const std::vector<Scene> scenes = testing::FleetScenes();
  internal::ObjectPathsCache tiny(1);
  ExpectSharedMatchesOwn(scenes, true, &tiny);
  EXPECT_EQ(tiny.Hits(), 0);

  internal::ObjectPathsCache cache(64u << 20);
  ExpectSharedMatchesOwn({scenes[0], scenes[1]}, true, &cache);
  const long long hits = cache.Hits();
  EXPECT_EQ(hits, 5);  // scene 1's objects but "a" were scene 0's
  cache.Clear();
  ExpectSharedMatchesOwn({scenes[0]}, true, &cache);
  EXPECT_EQ(cache.Hits(), hits) << "a cleared cache still found a set";
}

TEST(ObjectPathsCache, TheReachShortcutDropsTheSameObjectsWithRoomAndWithout) {
  // With room, the shortcut simulates a set whole and stores it; without, it simulates profile
  // by profile, stopping at the first that comes near, as without a cache. Either way the same
  // objects are dropped. Two objects start beyond the ego's final reach: one oncoming in its
  // lane (kept), one driving away behind it (dropped); one starts near (kept unsimulated).
  Scene scene;
  scene.ego.id = "ego";
  scene.ego.state.speed_mps = 12.0;
  scene.ego.lanes = bench::StraightThreeLanes();
  auto add = [&](const char* id, double x, double yaw, double v) {
    Vehicle o;
    o.id = id;
    o.state.x_m = x;
    o.state.yaw_rad = yaw;
    o.state.speed_mps = v;
    o.lanes = bench::StraightThreeLanes();
    scene.vehicles.push_back(o);
  };
  add("oncoming", 80.0, 3.14159, 15.0);
  add("away", -90.0, 3.14159, 10.0);
  add("near", 12.0, 0.0, 8.0);
  const internal::Problem pb = internal::BuildProblem(scene, Params{});
  const std::vector<char> expected = internal::OutOfReach(pb, true);
  ASSERT_EQ(expected, (std::vector<char>{0, 1, 0})) << "the scene should keep, drop, keep";
  internal::ObjectPathsCache roomy(64u << 20), tiny(1);
  EXPECT_TRUE(roomy.HasRoom(42, 100));
  EXPECT_FALSE(tiny.HasRoom(1, 1));
  for (int round = 0; round < 2; ++round) {  // the second round finds what the first stored
    EXPECT_EQ(internal::OutOfReach(pb, true, &roomy), expected) << "round " << round;
    EXPECT_EQ(internal::OutOfReach(pb, true, &tiny), expected) << "round " << round;
  }
  EXPECT_EQ(roomy.Hits(), 2) << "the two objects beyond reach, stored in the first round";
  EXPECT_EQ(tiny.Hits(), 0);
}

TEST(ObjectPathsCache, ANegativeCapacityIsRefused) {
  EstimatorOptions o;
  o.shared_object_paths_mib = -1;
  EXPECT_THROW(Estimator(Params{}, o), InputError);
}

}  // namespace
}  // namespace criticality
