// Long and articulated bodies (Vehicle::carriages; estimator/ALGORITHM.md "Long and articulated
// bodies"): a vehicle and its carriages are one object whose hypotheses are the vehicle's; each
// carriage box is simulated and checked like any box, and its first colliding steps are folded
// into the vehicle's columns before the risk.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "bench/paper_scenes.h"
#include "core/hypothesis_set.h"
#include "cpu/reference_backend.h"
#include "criticality/estimator.h"
#include "src/problem.h"

namespace criticality {
namespace {

constexpr double kHalfPi = 1.5707963267948966;

// A straight track of one lane (3 m wide) along the observer's heading.
LaneSet Track() {
  LaneSet lanes;
  Lane own;
  for (int i = 0; i < 3; ++i) {
    own.right.points[i] = Point2{40.0 * i, -1.5};
    own.left.points[i] = Point2{40.0 * i, 1.5};
  }
  lanes.own = own;
  return lanes;
}

// A train ("train7": a 20 m locomotive and `carriages` carriages of 18 m with 1 m gaps, 2.9 m
// wide) crossing the ego's road at x = track_x along +y at 8 m/s. Its locomotive is at y =
// 57, past the road; carriage k (1-based) at y = 57 - 19 k: the third at y = 0, on the
// crossing.
Vehicle Train(double track_x, int carriages) {
  Vehicle t;
  t.id = "train7";
  t.state.x_m = track_x;
  t.state.y_m = 57.0;
  t.state.yaw_rad = kHalfPi;
  t.state.speed_mps = 8.0;
  t.length_m = 20.0;
  t.width_m = 2.9;
  t.lanes = Track();
  t.type.road_user = RoadUser::kRail;
  for (int k = 1; k <= carriages; ++k) {
    Carriage c;
    c.x_m = track_x;
    c.y_m = 57.0 - 19.0 * k;
    c.yaw_rad = kHalfPi;
    c.length_m = 18.0;
    c.width_m = 2.9;
    c.lanes = Track();
    t.carriages.push_back(c);
  }
  return t;
}

// The ego standing on its road with its front 0.5 m over the edge of the train's clearance
// (a car waiting too close to a level crossing).
Scene StandingAtTheCrossing(int carriages) {
  Scene s;
  s.ego.id = "ego";
  s.ego.lanes = bench::StraightThreeLanes();
  s.vehicles.push_back(Train(2.25 + 1.45 - 0.5, carriages));
  return s;
}

TEST(LongBodies, ATrainWhoseThirdCarriageIsOnTheCrossingCollidesWithAStandingEgo) {
  EstimatorOptions opt;
  opt.keep_pair_matrix = true;
  Estimator estimator(Params{}, opt);
  const Result with = estimator.Estimate(StandingAtTheCrossing(5));
  EXPECT_GT(with.p_collision, 0.99);
  // One object, the train, with the train's hypotheses; its share is the whole risk.
  ASSERT_EQ(with.objects.size(), 1u);
  EXPECT_EQ(with.objects[0].id, "train7");
  EXPECT_EQ(with.objects[0].trajectories, Params{}.profiles);  // rail: one path per profile
  EXPECT_NEAR(with.objects[0].contribution, with.p_collision, 1e-12);
  // The pair matrix has the train's columns only; the carriages' work is counted apart.
  EXPECT_EQ(with.counts.co_trajectories, with.objects[0].trajectories);
  EXPECT_EQ(with.counts.carriage_trajectories, 5 * with.objects[0].trajectories);
  EXPECT_EQ(with.first_collision_step.size(),
            static_cast<size_t>(with.counts.ego_trajectories) * with.counts.co_trajectories);
  EXPECT_EQ(
      with.counts.pose_combinations,
      static_cast<std::uint64_t>(with.counts.ego_trajectories) * 6 * 6 * with.counts.time_steps);

  // The locomotive alone has passed the crossing: nothing collides.
  const Result alone = estimator.Estimate(StandingAtTheCrossing(0));
  EXPECT_EQ(alone.p_collision, 0.0);
  ASSERT_EQ(alone.objects.size(), 1u);
  EXPECT_EQ(alone.counts.carriage_trajectories, 0);
}

// Two trucks with trailers beside the ego on a straight three-lane road, all at 15 m/s: on the
// left a tractor ahead of the ego with its trailer alongside it (the trailer's lanes are the
// road's: the trailer follows the tractor's paths); on the right the same, the trailer's lanes
// its own lane only (the trailer keeps its lane's centre in every hypothesis).
Scene TrucksWithTrailers() {
  Scene s;
  s.ego.lanes = bench::StraightThreeLanes();
  s.ego.state.speed_mps = 15.0;
  for (int side : {1, -1}) {
    Vehicle truck;
    truck.id = side > 0 ? "left-truck" : "right-truck";
    truck.state.x_m = 7.0;
    truck.state.y_m = side * bench::kLaneWidth;
    truck.state.speed_mps = 15.0;
    truck.length_m = 6.0;
    truck.width_m = 2.5;
    truck.lanes = bench::StraightThreeLanes();
    truck.type.road_user = RoadUser::kHeavy;
    Carriage trailer;
    trailer.x_m = 7.0 - 3.0 - 0.5 - 6.8;
    trailer.y_m = truck.state.y_m;
    trailer.length_m = 13.6;
    trailer.width_m = 2.55;
    trailer.lanes = bench::StraightThreeLanes();
    if (side < 0) {
      trailer.lanes->left.reset();
      trailer.lanes->right.reset();
    }
    truck.carriages.push_back(trailer);
    s.vehicles.push_back(truck);
  }
  return s;
}

TEST(LongBodies, TheFoldedPairMatrixIsTheEarliestOfTheVehiclesAndItsCarriagesSteps) {
  const Scene scene = TrucksWithTrailers();
  const Params params;
  const internal::Problem pb = internal::BuildProblem(scene, params);
  ASSERT_EQ(pb.objects.size(), 2u);
  ASSERT_EQ(pb.cos.size(), 4u);                     // two tractors, then two trailers
  EXPECT_EQ(pb.cos[2].n_paths, pb.cos[0].n_paths);  // the left trailer follows its paths
  EXPECT_EQ(pb.cos[3].n_paths, 1);                  // the right one keeps its lane
  ReferenceBackend backend;
  backend.GenerateTrajectories(pb);
  std::vector<std::int16_t> all;
  backend.RecognizeCollisions(pb, &all);
  const int n_ego = pb.EgoTrajectories(), n_all = pb.CoTrajectories();
  const int n_obj = pb.ObjectTrajectories();

  EstimatorOptions opt;
  opt.backend = Backend::kReference;
  opt.keep_pair_matrix = true;
  const Result r = Estimator(params, opt).Estimate(scene);
  ASSERT_EQ(r.first_collision_step.size(), static_cast<size_t>(n_ego) * n_obj);
  int carriage_first = 0, vehicle_first = 0;
  for (int i = 0; i < n_ego; ++i) {
    for (int o = 0; o < 2; ++o) {
      const core::HypothesisSet& v = pb.cos[o];
      const core::HypothesisSet& c = pb.cos[2 + o];
      for (int t = 0; t < v.Trajectories(); ++t) {
        const int profile = t / v.n_paths, path = t % v.n_paths;
        const int tc = profile * c.n_paths + (c.n_paths == 1 ? 0 : path);
        const int own = all[static_cast<size_t>(i) * n_all + pb.co_offset[o] + t];
        const int trailer = all[static_cast<size_t>(i) * n_all + pb.co_offset[2 + o] + tc];
        int expected = own;
        if (trailer > 0 && (own == 0 || trailer < own)) expected = trailer;
        carriage_first += trailer > 0 && (own == 0 || trailer < own);
        vehicle_first += own > 0 && (trailer == 0 || own < trailer);
        ASSERT_EQ(r.first_collision_step[static_cast<size_t>(i) * n_obj + pb.co_offset[o] + t],
                  expected)
            << i << " " << o << " " << t;
      }
    }
  }
  // Both kinds occur, so the fold is exercised both ways.
  EXPECT_GT(carriage_first, 0);
  EXPECT_GT(vehicle_first, 0);
  ASSERT_EQ(r.objects.size(), 2u);
  EXPECT_NEAR(r.objects[0].contribution + r.objects[1].contribution, r.p_collision, 1e-12);
}

// The ego at 10 m/s towards a level crossing 30 m ahead; the train crosses along +y, its
// locomotive 150 m past the road (out of the ego's reach), its carriages in a chain back to
// the crossing (the last one on it).
Scene LongTrainAhead(bool carriages) {
  Scene s;
  s.ego.lanes = bench::StraightThreeLanes();
  s.ego.state.speed_mps = 10.0;
  Vehicle t = Train(30.0, 0);
  t.state.y_m = 150.0;
  if (carriages) {
    for (int k = 1; k <= 7; ++k) {
      Carriage c;
      c.x_m = 30.0;
      c.y_m = 150.0 - 21.0 * k;
      c.yaw_rad = kHalfPi;
      c.length_m = 20.0;
      c.width_m = 2.9;
      c.lanes = Track();
      t.carriages.push_back(c);
    }
  }
  s.vehicles.push_back(t);
  return s;
}

TEST(LongBodies, TheReachShortcutKeepsABodyWhoseRearCarriageCanReach) {
  EstimatorOptions full, shortcut;
  shortcut.reach_shortcut = true;
  full.keep_pair_matrix = shortcut.keep_pair_matrix = true;
  const Params params;
  // The locomotive alone is out of reach...
  const Result alone = Estimator(params, shortcut).Estimate(LongTrainAhead(false));
  ASSERT_EQ(alone.objects.size(), 1u);
  EXPECT_TRUE(alone.objects[0].out_of_reach);
  // ...the train with its carriages is not: its last carriage is on the crossing ahead.
  const Scene scene = LongTrainAhead(true);
  const Result a = Estimator(params, full).Estimate(scene);
  const Result b = Estimator(params, shortcut).Estimate(scene);
  ASSERT_EQ(b.objects.size(), 1u);
  EXPECT_FALSE(b.objects[0].out_of_reach);
  EXPECT_GT(a.p_collision, 0.0);
  EXPECT_EQ(a.p_collision, b.p_collision);
  EXPECT_EQ(a.first_collision_step, b.first_collision_step);
  EXPECT_EQ(a.objects[0].contribution, b.objects[0].contribution);
}

TEST(LongBodies, ABatchMixingScenesWithAndWithoutCarriagesGivesEachSceneItsEstimate) {
  const std::vector<Scene> scenes{StandingAtTheCrossing(5), bench::PaperSceneS1(),
                                  TrucksWithTrailers(), LongTrainAhead(true)};
  for (Backend backend : {Backend::kReference, Backend::kCpu}) {
    EstimatorOptions opt;
    opt.backend = backend;
    opt.threads = 2;
    opt.keep_pair_matrix = true;
    Estimator batch(Params{}, opt), single(Params{}, opt);
    const std::vector<Result> together = batch.EstimateBatch(scenes);
    ASSERT_EQ(together.size(), scenes.size());
    for (size_t k = 0; k < scenes.size(); ++k) {
      const Result alone = single.Estimate(scenes[k]);
      EXPECT_EQ(together[k].p_collision, alone.p_collision) << k;
      EXPECT_EQ(together[k].first_collision_step, alone.first_collision_step) << k;
      ASSERT_EQ(together[k].objects.size(), alone.objects.size()) << k;
      for (size_t o = 0; o < alone.objects.size(); ++o)
        EXPECT_EQ(together[k].objects[o].contribution, alone.objects[o].contribution) << k;
    }
  }
}

TEST(LongBodies, ASevenHundredMetreFreightTrainIsEstimatedAsItsBoxes) {
  // About 700 m: a 20 m locomotive and 64 wagons of 10.6 m (the input limit's kMaxCarriages),
  // on a track along the ego's road to its left, at 20 m/s.
  Scene s;
  s.ego.lanes = bench::StraightThreeLanes();
  s.ego.state.speed_mps = 20.0;
  Vehicle t;
  t.id = "freight";
  t.state.x_m = 30.0;
  t.state.y_m = 8.0;
  t.state.speed_mps = 20.0;
  t.length_m = 20.0;
  t.width_m = 3.0;
  t.lanes = Track();
  t.type.road_user = RoadUser::kRail;
  double rear = t.state.x_m - 10.0;
  for (int k = 0; k < kMaxCarriages; ++k) {
    Carriage c;
    c.length_m = 10.6;
    c.width_m = 3.0;
    c.x_m = rear - 0.1 - 5.3;
    c.y_m = 8.0;
    rear = c.x_m - 5.3;
    t.carriages.push_back(c);
  }
  s.vehicles.push_back(t);
  ASSERT_NEAR(30.0 + 10.0 - rear, 700.0, 7.0);
  const Result r = Estimator(Params{}).Estimate(s);
  ASSERT_EQ(r.objects.size(), 1u);
  EXPECT_EQ(r.counts.carriage_trajectories, kMaxCarriages * Params{}.profiles);
  EXPECT_EQ(r.p_collision, 0.0);  // on its own track beside the road
}

}  // namespace
}  // namespace criticality
