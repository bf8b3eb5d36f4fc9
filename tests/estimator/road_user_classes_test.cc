// Road users by class (Params::road_user_classes; estimator/ALGORITHM.md "Road users by class"):
// every hypothesis of a vehicle stays within its type's limits (the VehicleType's values, else
// its class's), rail vehicles keep to their track, the paper-literal preset and a car without
// type values keep the paper's hypotheses.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "bench/paper_scenes.h"
#include "core/hypothesis_set.h"
#include "core/trajectory_generation.h"
#include "criticality/estimator.h"
#include "src/problem.h"
#include "test_scenes.h"

namespace criticality {
namespace {

using internal::BuildProblem;
using internal::Problem;

// The ego standing on a straight three-lane road (bench::StraightThreeLanes), one vehicle
// 20 m ahead in the ego's lane with lanes of its own, driving along the road.
Scene OneVehicle(const VehicleType& type, double speed, double accel) {
  Scene s;
  s.ego.lanes = bench::StraightThreeLanes();
  Vehicle v;
  v.id = "other";
  v.state.x_m = 20.0;
  v.state.speed_mps = speed;
  v.state.accel_mps2 = accel;
  v.lanes = bench::StraightThreeLanes();
  v.type = type;
  s.vehicles.push_back(v);
  return s;
}

// Speed changes of every hypothesis of a vehicle's set, per step: the largest gain and loss
// rates (m/s^2) and the highest speed reached.
struct SpeedEnvelope {
  double max_accel{-HUGE_VAL};
  double min_accel{HUGE_VAL};
  double max_speed{0.0};
};

SpeedEnvelope EnvelopeOf(const core::HypothesisSet& h, const core::SimulationConfig& sim) {
  SpeedEnvelope e;
  const int steps = sim.n_steps;
  std::vector<double> x(steps), y(steps), yaw(steps), steer(steps);
  std::vector<core::MotionState> state(steps);
  for (int t = 0; t < h.Trajectories(); ++t) {
    core::StepTrace trace{state.data(), steer.data()};
    core::SimulateHypothesis(h, sim, t / h.n_paths, t % h.n_paths, x.data(), y.data(), yaw.data(),
                             1, &trace);
    double v = h.v0;
    for (int n = 0; n < steps; ++n) {
      const double rate = (state[n].v - v) / sim.tau;
      e.max_accel = std::max(e.max_accel, rate);
      e.min_accel = std::min(e.min_accel, rate);
      e.max_speed = std::max(e.max_speed, state[n].v);
      v = state[n].v;
    }
  }
  return e;
}

TEST(RoadUsers, ABicycleStaysWithinItsTypesAccelerationTopSpeedAndEmergencyDeceleration) {
  VehicleType bicycle;
  bicycle.road_user = RoadUser::kBicycle;
  bicycle.accel_mps2 = 1.0;
  bicycle.max_speed_mps = 6.0;
  bicycle.emergency_decel_mps2 = 5.0;
  // Measured at 2 m/s^2, above what the type can do: not even the latency keeps it.
  const Problem pb = BuildProblem(OneVehicle(bicycle, 5.0, 2.0), Params{});
  const core::HypothesisSet& h = pb.cos[0];
  const SpeedEnvelope e = EnvelopeOf(h, pb.sim);
  EXPECT_LE(e.max_accel, 1.0 + 1e-9);
  EXPECT_LE(e.max_speed, 6.0 + 1e-9);
  EXPECT_GE(e.min_accel, -5.0 - 1e-9);
  // And the limits are reached, not undercut: the strongest profiles drive at them.
  EXPECT_NEAR(e.max_accel, 1.0, 1e-6);
  EXPECT_NEAR(e.max_speed, 6.0, 1e-6);
  EXPECT_NEAR(e.min_accel, -5.0, 1e-6);
  // A bicycle is kinematic at every speed.
  EXPECT_TRUE(std::isinf(h.seam_speed));
}

TEST(RoadUsers, ABicycleWithoutTypeValuesTakesItsClasssLimits) {
  VehicleType bicycle;
  bicycle.road_user = RoadUser::kBicycle;
  const Params params;
  const Problem pb = BuildProblem(OneVehicle(bicycle, 5.0, 0.0), params);
  const SpeedEnvelope e = EnvelopeOf(pb.cos[0], pb.sim);
  EXPECT_NEAR(e.max_accel, params.bicycle.accel_mps2, 1e-6);
  EXPECT_NEAR(e.max_speed, params.bicycle.max_speed_mps, 1e-6);
  EXPECT_NEAR(e.min_accel, -params.bicycle.emergency_decel_mps2, 1e-6);
}

TEST(RoadUsers, ATruckBrakesAtMostItsEmergencyDeceleration) {
  VehicleType truck;
  truck.road_user = RoadUser::kHeavy;
  const Params params;
  const Problem pb = BuildProblem(OneVehicle(truck, 20.0, 0.0), params);
  const core::HypothesisSet& h = pb.cos[0];
  const SpeedEnvelope e = EnvelopeOf(h, pb.sim);
  EXPECT_GE(e.min_accel, -params.heavy.emergency_decel_mps2 - 1e-9);
  EXPECT_NEAR(e.min_accel, -params.heavy.emergency_decel_mps2, 1e-6);  // a car's -9.7 fails
  EXPECT_LE(e.max_accel, params.heavy.accel_mps2 + 1e-9);
  // Its model is a heavy vehicle's: its class mass and the long wheelbase of a 4.5 m box
  // clamped to the class minimum.
  EXPECT_EQ(h.vehicle.mass_kg, params.heavy.mass_kg);
  EXPECT_NEAR(h.vehicle.lf_m + h.vehicle.lr_m, params.heavy.wheelbase_min_m, 1e-12);
  EXPECT_EQ(h.vehicle.power_per_mass_wpkg, params.heavy.power_per_mass_wpkg);
}

// Offset of a pose (scene frame) from the parabola y = k x^2 in the frame of `h`.
double OffsetFromParabola(const core::HypothesisSet& h, double k, double x, double y) {
  double lx, ly;
  core::WorldToLocal(h.X_WL, x, y, &lx, &ly);
  return ly - k * lx * lx;
}

// Three lanes of width 3.5 along y = k x^2 (exactly a parabola, so the fit is exact).
LaneSet CurvedThreeLanes(double k) {
  auto lane = [&](double right, double left) {
    Lane l;
    for (int i = 0; i < 3; ++i) {
      const double x = 40.0 * i;
      l.right.points[i] = Point2{x, k * x * x + right};
      l.left.points[i] = Point2{x, k * x * x + left};
    }
    return l;
  };
  LaneSet s;
  s.own = lane(-1.75, 1.75);
  s.left = lane(1.75, 5.25);
  s.right = lane(-5.25, -1.75);
  return s;
}

TEST(RoadUsers, ARailVehicleHasOnePathPerProfileAndStaysOnItsLanesCentre) {
  const double k = 0.002;  // radius 250 m at the vehicle
  Scene scene = OneVehicle(VehicleType{}, 12.0, 0.0);
  scene.vehicles[0].lanes = CurvedThreeLanes(k);
  scene.vehicles[0].length_m = 30.0;
  scene.vehicles[0].width_m = 2.65;
  scene.vehicles[0].state.yaw_rate_radps = 2.0 * k * 12.0;  // following the curve
  Scene tram = scene;
  tram.vehicles[0].type.road_user = RoadUser::kRail;
  const Params params;
  const Problem as_car = BuildProblem(scene, params);
  const Problem as_tram = BuildProblem(tram, params);
  ASSERT_EQ(as_car.cos[0].n_paths, 7);  // the lanes give a car seven paths
  const core::HypothesisSet& h = as_tram.cos[0];
  EXPECT_EQ(h.n_paths, 1);
  EXPECT_EQ(h.n_lateral, 1);
  EXPECT_EQ(h.Trajectories(), params.profiles);
  const int steps = as_tram.sim.n_steps;
  std::vector<double> x(steps), y(steps), yaw(steps);
  double worst_tram = 0.0, worst_car = 0.0;
  for (int t = 0; t < h.Trajectories(); ++t) {
    core::SimulateHypothesis(h, as_tram.sim, t / h.n_paths, t % h.n_paths, x.data(), y.data(),
                             yaw.data());
    for (int n = 0; n < steps; ++n)
      worst_tram = std::max(worst_tram, std::fabs(OffsetFromParabola(h, k, x[n], y[n])));
  }
  const core::HypothesisSet& c = as_car.cos[0];
  for (int t = 0; t < c.Trajectories(); ++t) {
    core::SimulateHypothesis(c, as_car.sim, t / c.n_paths, t % c.n_paths, x.data(), y.data(),
                             yaw.data());
    for (int n = 0; n < steps; ++n)
      worst_car = std::max(worst_car, std::fabs(OffsetFromParabola(c, k, x[n], y[n])));
  }
  EXPECT_LT(worst_tram, 0.1);  // on the centre line of its track
  EXPECT_GT(worst_car, 1.0);   // the car's lane changes leave it: the bound is not trivial
}

TEST(RoadUsers, ARailVehicleWithoutLanesOfItsOwnFollowsTheEgoLaneItIsOn) {
  // A tram in the ego's left lane on a curved road, 0.3 m left of the lane's centre, its
  // heading along the lane and no yaw rate measured (a virtual lane along its heading would be
  // straight and leave the curve by about 0.8 m within 20 m).
  const double k = 0.002;
  Scene scene;
  scene.ego.lanes = CurvedThreeLanes(k);
  scene.ego.state.speed_mps = 10.0;
  Vehicle tram;
  tram.id = "tram";
  const double x0 = 25.0, slope = 2.0 * k * x0;
  const double q = std::sqrt(1.0 + slope * slope);
  tram.state.x_m = x0 - 0.3 * slope / q;
  tram.state.y_m = k * x0 * x0 + bench::kLaneWidth + 0.3 / q;
  tram.state.yaw_rad = std::atan(slope);
  tram.state.speed_mps = 10.0;
  tram.length_m = 30.0;
  tram.width_m = 2.65;
  tram.type.road_user = RoadUser::kRail;
  scene.vehicles.push_back(tram);
  const Problem pb = BuildProblem(scene, Params{});
  ASSERT_EQ(pb.objects[0].lane, 1);  // associated with the ego's left lane
  const core::HypothesisSet& h = pb.cos[0];
  ASSERT_EQ(h.n_paths, 1);
  const int steps = pb.sim.n_steps;
  std::vector<double> x(steps), y(steps), yaw(steps);
  double farthest = 0.0;
  for (int profile = 0; profile < h.n_profiles; ++profile) {
    core::SimulateHypothesis(h, pb.sim, profile, 0, x.data(), y.data(), yaw.data());
    for (int n = 0; n < steps; ++n) {
      // Its offset from the left lane's centre (ego frame = scene frame), along that lane.
      const double m = 2.0 * k * x[n];
      const double offset = (y[n] - k * x[n] * x[n] - bench::kLaneWidth) / std::sqrt(1.0 + m * m);
      EXPECT_NEAR(offset, 0.3, 0.05) << profile << " " << n;  // the lane refitted in its frame
      EXPECT_NEAR(yaw[n], std::atan(m), 0.01) << profile << " " << n;
    }
    farthest = std::max(farthest, x[steps - 1] - tram.state.x_m);
  }
  EXPECT_GT(farthest, 19.0);  // it went along the curve, not only stood on it
}

TEST(RoadUsers, VehicleTypeValuesOverrideTheClasss) {
  const Params params;
  VehicleType truck;
  truck.road_user = RoadUser::kHeavy;
  truck.accel_mps2 = 0.8;
  truck.emergency_decel_mps2 = 4.0;
  truck.max_speed_mps = 12.0;
  truck.mass_kg = 20000.0;
  const Problem pb = BuildProblem(OneVehicle(truck, 10.0, 0.0), params);
  const core::HypothesisSet& h = pb.cos[0];
  EXPECT_EQ(h.profile_target[0], -4.0);
  EXPECT_EQ(h.profile_target[h.n_profiles - 1], 0.8);
  EXPECT_EQ(h.top_speed, 12.0);
  EXPECT_EQ(h.vehicle.mass_kg, 20000.0);
  // Cornering stiffness scales with the type's mass.
  EXPECT_DOUBLE_EQ(h.vehicle.cf_npr, params.heavy.cornering_stiffness_per_kg * 20000.0);

  // Only decel given: SUMO's rule, the larger of it and the class's emergency deceleration.
  VehicleType soft = VehicleType{};
  soft.road_user = RoadUser::kHeavy;
  soft.decel_mps2 = 3.0;
  EXPECT_EQ(BuildProblem(OneVehicle(soft, 10.0, 0.0), params).cos[0].profile_target[0],
            -params.heavy.emergency_decel_mps2);
  soft.decel_mps2 = 8.0;
  EXPECT_EQ(BuildProblem(OneVehicle(soft, 10.0, 0.0), params).cos[0].profile_target[0], -8.0);

  // A car keeps the paper's profile grid: its type's emergency deceleration floors the hardest
  // braking samples only (the others stay where they were), its positive profiles stay the
  // paper's (the power limit bounds them), its top speed bounds it, and its mass replaces its
  // class's.
  VehicleType car;
  car.accel_mps2 = 2.6;
  car.emergency_decel_mps2 = 9.0;
  car.max_speed_mps = 15.0;
  car.mass_kg = 2000.0;
  const Problem typed_car = BuildProblem(OneVehicle(car, 10.0, 0.0), params);
  const Problem plain_car = BuildProblem(OneVehicle(VehicleType{}, 10.0, 0.0), params);
  EXPECT_EQ(typed_car.cos[0].profile_target[0], -9.0);
  EXPECT_EQ(plain_car.cos[0].profile_target[0], params.vehicle_accel_min_mps2);
  for (int k = 1; k < params.profiles; ++k)
    EXPECT_EQ(typed_car.cos[0].profile_target[k], plain_car.cos[0].profile_target[k]) << k;
  EXPECT_EQ(typed_car.cos[0].profile_target[params.profiles - 1], params.vehicle_accel_max_mps2);
  EXPECT_EQ(typed_car.cos[0].top_speed, 15.0);
  EXPECT_EQ(typed_car.cos[0].vehicle.mass_kg, 2000.0);
  EXPECT_DOUBLE_EQ(
      typed_car.cos[0].vehicle.yaw_inertia_kgm2,
      plain_car.cos[0].vehicle.yaw_inertia_kgm2 * 2000.0 / plain_car.cos[0].vehicle.mass_kg);
}

TEST(RoadUsers, ACarWithoutTypeValuesKeepsThePapersRange) {
  const Params params;
  const Problem pb = BuildProblem(OneVehicle(VehicleType{}, 10.0, 0.0), params);
  EXPECT_EQ(pb.cos[0].profile_target[0], params.vehicle_accel_min_mps2);
  EXPECT_EQ(pb.cos[0].profile_target[params.profiles - 1], params.vehicle_accel_max_mps2);
  EXPECT_TRUE(std::isinf(pb.cos[0].top_speed));
  EXPECT_TRUE(std::isinf(pb.ego.top_speed));
  // Bit for bit the estimate without classes: untyped scenes are unchanged by them.
  Params off = params;
  off.road_user_classes = false;
  EstimatorOptions opt;
  opt.keep_pair_matrix = true;
  Estimator with(params, opt), without(off, opt);
  for (const Scene& scene : {bench::PaperSceneS1(), bench::PaperSceneS2()}) {
    const Result a = with.Estimate(scene), b = without.Estimate(scene);
    EXPECT_EQ(a.p_collision, b.p_collision);
    EXPECT_EQ(a.p_reference, b.p_reference);
    EXPECT_EQ(a.first_collision_step, b.first_collision_step);
    EXPECT_EQ(a.ego_probability, b.ego_probability);
  }
}

// A scene with one vehicle of every class, each with type values.
Scene MixedFleet() {
  Scene s = bench::PaperSceneS1();
  const RoadUser users[] = {RoadUser::kBicycle, RoadUser::kHeavy, RoadUser::kRail};
  for (size_t i = 0; i < s.vehicles.size(); ++i) {
    s.vehicles[i].type.road_user = users[i];
    s.vehicles[i].type.accel_mps2 = 1.0 + i;
    s.vehicles[i].type.emergency_decel_mps2 = 3.0 + i;
    s.vehicles[i].type.max_speed_mps = 22.0;
  }
  s.ego.type.road_user = RoadUser::kHeavy;
  s.ego.type.mass_kg = 15000.0;
  return s;
}

TEST(RoadUsers, ThePaperLiteralPresetIgnoresTheClasses) {
  const Scene typed = MixedFleet();
  Scene untyped = typed;
  untyped.ego.type = VehicleType{};
  for (Vehicle& v : untyped.vehicles) v.type = VehicleType{};
  EstimatorOptions opt;
  opt.keep_pair_matrix = true;
  Estimator literal(ParamsPreset("paper-literal"), opt), standard(Params{}, opt);
  const Result a = literal.Estimate(typed), b = literal.Estimate(untyped);
  EXPECT_EQ(a.p_collision, b.p_collision);
  EXPECT_EQ(a.first_collision_step, b.first_collision_step);
  EXPECT_EQ(a.ego_probability, b.ego_probability);
  EXPECT_EQ(a.counts.co_trajectories, b.counts.co_trajectories);
  // With the default parameters the types count (the rail vehicle has one path per profile).
  EXPECT_NE(standard.Estimate(typed).counts.co_trajectories,
            standard.Estimate(untyped).counts.co_trajectories);
  const Problem pb = BuildProblem(typed, ParamsPreset("paper-literal"));
  EXPECT_EQ(pb.cos[0].profile_target[0], -9.7);
  EXPECT_EQ(pb.cos[2].n_paths, 7);
}

TEST(RoadUsers, AHeavyEgoBrakesAndDrivesWithinItsClasssLimits) {
  Scene scene = bench::PaperSceneS1();
  scene.ego.type.road_user = RoadUser::kHeavy;
  scene.ego.type.max_speed_mps = 25.5;  // 0.5 m/s above its speed
  const Params params;
  const Problem pb = BuildProblem(scene, params);
  ASSERT_FALSE(pb.ego_profile_accel.empty());
  EXPECT_EQ(*std::min_element(pb.ego_profile_accel.begin(), pb.ego_profile_accel.end()),
            -params.heavy.emergency_decel_mps2);
  EXPECT_EQ(*std::max_element(pb.ego_profile_accel.begin(), pb.ego_profile_accel.end()),
            params.heavy.accel_mps2);
  EXPECT_EQ(pb.ego.vehicle.mass_kg, params.heavy.mass_kg);
  // Its two-track hypotheses never pass its top speed. Straight along its lane (the reference
  // path) its braking follows the force demand within a few percent; swerving, the tyres' side
  // forces brake it further (cornering drag), as a real truck's do.
  const SpeedEnvelope all = EnvelopeOf(pb.ego, pb.sim);
  EXPECT_LE(all.max_speed, 25.5 + 1e-9);
  core::HypothesisSet straight = pb.ego;
  straight.n_paths = 1;  // path 0 of a copy whose only sections are the own lane's centre
  for (int k = 0; k < straight.n_instants; ++k) {
    for (int l = 0; l < straight.n_lateral; ++l) straight.section[k][l] = straight.reference_path;
  }
  const SpeedEnvelope e = EnvelopeOf(straight, pb.sim);
  EXPECT_GE(e.min_accel, -1.05 * params.heavy.emergency_decel_mps2);
  EXPECT_LT(e.min_accel, -0.9 * params.heavy.emergency_decel_mps2);
  EXPECT_LE(e.max_speed, 25.5 + 1e-9);
}

TEST(RoadUsers, EgosOfEveryClassGiveTheSameEstimateWithTheReachShortcut) {
  // The shortcut bounds the ego's reach from its model: a kinematic (bicycle) or track-bound
  // (rail) ego must not be bounded too tightly, or reachable objects would be left out.
  EstimatorOptions full, shortcut;
  shortcut.reach_shortcut = true;
  full.keep_pair_matrix = shortcut.keep_pair_matrix = true;
  const Params params;
  Estimator a(params, full), b(params, shortcut);
  int dropped = 0, colliding = 0;
  for (RoadUser user : {RoadUser::kCar, RoadUser::kMotorcycle, RoadUser::kBicycle,
                        RoadUser::kHeavy, RoadUser::kRail}) {
    for (unsigned seed = 1; seed <= 8; ++seed) {
      Scene scene = testing::RandomScene(seed, 4, 2, seed % 2 == 0);
      scene.ego.type.road_user = user;
      const Result x = a.Estimate(scene), y = b.Estimate(scene);
      EXPECT_EQ(x.p_collision, y.p_collision) << static_cast<int>(user) << " " << seed;
      EXPECT_EQ(x.p_reference, y.p_reference) << static_cast<int>(user) << " " << seed;
      for (const ObjectResult& o : y.objects) dropped += o.out_of_reach;
      colliding += x.p_collision > 0.0;
      // A rail ego has one path per profile, every other class its lanes' combinations.
      EXPECT_EQ(user == RoadUser::kRail, x.counts.ego_trajectories == params.profiles) << seed;
    }
  }
  EXPECT_GT(dropped, 0);    // the shortcut acted
  EXPECT_GT(colliding, 5);  // and there was risk to keep
}

}  // namespace
}  // namespace criticality
