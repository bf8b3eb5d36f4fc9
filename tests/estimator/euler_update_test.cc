// A simulator's Euler position update (Scene::euler_update_step_s): SUMO moves each object over
// a step by its speed at the end of the step, so a braking vehicle stops v0 * dt / 2 short of
// where continuous braking stops it. The estimator must predict the positions that update
// gives, checked here against the update itself, written out step by step.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/trajectory_generation.h"
#include "criticality/estimator.h"
#include "criticality/vehicle_class.h"
#include "bench/discrimination_scenes.h"

namespace criticality {
namespace {

// SUMO's Euler update of a vehicle braking at `decel` from v0 with steps dt: the distance
// covered after each of `steps` steps (v_{k+1} = max(v_k - decel dt, 0); x += v_{k+1} dt).
std::vector<double> SumoEulerBraking(double v0, double decel, double dt, int steps) {
  std::vector<double> x;
  double v = v0, pos = 0.0;
  for (int k = 0; k < steps; ++k) {
    v = std::fmax(v - decel * dt, 0.0);
    pos += v * dt;
    x.push_back(pos);
  }
  return x;
}

// A one-track vehicle on a straight path braking at `decel` from v0 at once (no latency, an
// instant ramp), simulated for `seconds` with the estimator's step.
core::HypothesisSet BrakingVehicle(double v0, double decel) {
  core::HypothesisSet h;
  h.model = core::MotionModelKind::kOneTrack;
  h.vehicle = VehicleParamsFor(VehicleClass::kLargeFamily, 4.6, 1.8);
  h.v0 = v0;
  h.accel0 = -decel;
  h.n_profiles = 1;
  h.profile_target[0] = -decel;
  h.profile_start = -decel;
  h.rate = 1e6;
  h.n_instants = 1;
  h.instant_time[0] = 100.0;
  h.n_lateral = 1;
  h.section[0][0] = core::Parabola{0.0, 0.0, 0.0};
  h.n_paths = 1;
  return h;
}

TEST(EulerUpdate, BrakingVehicleStopsWhereSumosEulerUpdateStopsIt) {
  // 13.5 m/s at 4.5 m/s^2 with 1 s steps: SUMO's speeds 9, 4.5, 0 give 9, 13.5, 13.5 m;
  // continuous braking covers 11.25, 18, 20.25 m.
  const double v0 = 13.5, decel = 4.5, dt = 1.0;
  core::HypothesisSet h = BrakingVehicle(v0, decel);
  core::SimulationConfig cfg;
  cfg.tau = 0.02;
  cfg.n_steps = 200;  // 4 s
  std::vector<double> x(200), y(200), yaw(200);
  const std::vector<double> sumo = SumoEulerBraking(v0, decel, dt, 4);
  h.position_lead = 0.5 * dt;
  core::SimulateHypothesis(h, cfg, 0, 0, x.data(), y.data(), yaw.data());
  for (int k = 1; k <= 4; ++k) {
    const int n = k * 50 - 1;  // pose n is after n + 1 steps
    EXPECT_NEAR(x[n], sumo[k - 1], 0.05) << "after " << k << " s";
    EXPECT_NEAR(y[n], 0.0, 1e-9);
  }
  // Continuous motion (lead 0) is the physics the update departs from.
  h.position_lead = 0.0;
  core::SimulateHypothesis(h, cfg, 0, 0, x.data(), y.data(), yaw.data());
  EXPECT_NEAR(x[49], 11.25, 0.05);
  EXPECT_NEAR(x[199], v0 * v0 / (2.0 * decel), 0.05);
}

// Braking through a turn: SUMO moves the vehicle along its way by its speed at the end of each
// step, so its pose lies on the way it drives, only behind where continuous braking gets. Each
// step's part of the shift keeps that step's course (core::AccumulateLead). Shifted by the whole
// speed change along the heading it has now, as before, a car braking through a right turn at
// 1 s steps was put up to 1.4 m out to the left of its way (into the opposite lane, where a
// waiting car "collided" with it: bench/RESULTS.md, "the Euler update in a turn").
TEST(EulerUpdate, BrakingThroughATurnStaysOnTheWayItDrives) {
  const double v0 = 11.0, decel = 4.5, dt = 1.0;
  core::HypothesisSet h = BrakingVehicle(v0, decel);
  h.section[0][0] = core::Parabola{-0.05, 0.0, 0.0};  // a right turn, radius 10 m at x = 0
  h.reference_path = h.section[0][0];
  core::SimulationConfig cfg;
  cfg.tau = 0.02;
  cfg.n_steps = 100;  // 2 s
  std::vector<double> cx(100), cy(100), cyaw(100), x(100), y(100), yaw(100);
  core::SimulateHypothesis(h, cfg, 0, 0, cx.data(), cy.data(), cyaw.data());  // continuous
  h.position_lead = 0.5 * dt;
  core::SimulateHypothesis(h, cfg, 0, 0, x.data(), y.data(), yaw.data());
  // It turns: the heading changes by more than 35 degrees within the 2 s.
  ASSERT_LT(cyaw[99], -0.6);
  const std::vector<double> sumo = SumoEulerBraking(v0, decel, dt, 2);
  for (int k = 1; k <= 2; ++k) {
    const int n = k * 50 - 1;
    // The distance from the continuous way (its poses, 2 cm apart) ...
    double off = HUGE_VAL;
    int nearest = 0;
    for (int m = 0; m < 100; ++m) {
      const double dm = std::hypot(x[n] - cx[m], y[n] - cy[m]);
      if (dm < off) off = dm, nearest = m;
    }
    EXPECT_LT(off, 0.1) << "after " << k << " s";
    // ... and how far along it: SUMO's distance (9 m after 1 s, 6.5 m more after 2 s), within
    // what the way's 2 cm sampling and its arc against the straight steps leave.
    double along = std::hypot(cx[0], cy[0]) + 0.5 * v0 * cfg.tau;  // to the first pose
    for (int m = 1; m <= nearest; ++m) along += std::hypot(cx[m] - cx[m - 1], cy[m] - cy[m - 1]);
    EXPECT_NEAR(along, sumo[k - 1], 0.3) << "after " << k << " s";
  }
}

// A walker at (x, y) heading 90 degrees at v0, changing its speed at `accel` (one profile, one
// heading).
core::HypothesisSet Walker(double x, double y, double v0, double accel) {
  core::HypothesisSet h;
  h.model = core::MotionModelKind::kPedestrian;
  h.X_WL = core::Pose2{x, y, 0.0};
  h.v0 = v0;
  h.max_speed = 2.7;
  h.n_profiles = 1;
  h.profile_target[0] = accel;
  h.n_paths = 1;
  h.heading[0] = 0.5 * M_PI;
  return h;
}

TEST(EulerUpdate, PedestrianShiftIsAlongItsHeading) {
  // A walker at 1.2 m/s, heading 90 degrees, stopping at 1.2 m/s^2: SUMO's update with 1 s
  // steps leaves it where it stands (its speed after the step is 0); continuous motion 0.6 m on.
  core::HypothesisSet h = Walker(3.0, 4.0, 1.2, -1.2);
  core::SimulationConfig cfg;
  cfg.tau = 0.02;
  cfg.n_steps = 100;
  std::vector<double> x(100), y(100), yaw(100);
  h.position_lead = 0.5;
  core::SimulateHypothesis(h, cfg, 0, 0, x.data(), y.data(), yaw.data());
  EXPECT_NEAR(x[99], 3.0, 1e-9);
  EXPECT_NEAR(y[99], 4.0, 0.02);
  h.position_lead = 0.0;
  core::SimulateHypothesis(h, cfg, 0, 0, x.data(), y.data(), yaw.data());
  EXPECT_NEAR(y[99], 4.6, 0.02);
}

// The ego approaches a stopped car in its lane at 13.5 m/s, its driver expected to brake at
// 4.5 m/s^2 (SUMO's car following), 19 m between the bumpers. Continuous braking after the
// reaction latency needs about 23 m: a collision. SUMO's Euler update with 1 s steps stops it
// in 13.5 m: no collision, and no warning is due.
Scene StoppedCarAhead(double euler_step_s) {
  Scene s;
  s.ego.state.speed_mps = 13.5;
  s.ego.state.expected_accel_mps2 = -4.5;
  s.ego.length_m = 5.0;
  Vehicle v;
  v.id = "stopped";
  v.length_m = 5.0;
  v.state.x_m = 24.0;
  s.vehicles.push_back(v);
  s.euler_update_step_s = euler_step_s;
  return s;
}

TEST(EulerUpdate, SumosCoarseStepsStopTheEgoShortOfAStoppedCar) {
  Estimator est{Params{}};
  const Result continuous = est.Estimate(StoppedCarAhead(0.0));
  const Result fine = est.Estimate(StoppedCarAhead(0.1));
  const Result coarse = est.Estimate(StoppedCarAhead(1.0));
  EXPECT_GT(continuous.p_reference, 0.9);
  EXPECT_GT(fine.p_reference, 0.9);  // 0.1 s steps are nearly continuous: 0.7 m shorter
  EXPECT_LT(coarse.p_reference, 0.01);
  EXPECT_LT(coarse.p_collision, continuous.p_collision);
}

// Params::collisions_at_world_steps (HypothesisSet::pose_hold_steps): between the world's steps
// the poses repeat the last pose the world sees (before its first step, the pose now); at its
// steps they are the poses without the hold.
TEST(EulerUpdate, HeldPosesRepeatTheLastPoseTheWorldSees) {
  core::HypothesisSet h = BrakingVehicle(13.5, 4.5);
  h.X_WL = core::Pose2{3.0, -2.0, 0.25};
  h.position_lead = 0.5;
  core::SimulationConfig cfg;
  cfg.tau = 0.02;
  cfg.n_steps = 150;
  std::vector<double> x(150), y(150), yaw(150), hx(150), hy(150), hyaw(150);
  core::SimulateHypothesis(h, cfg, 0, 0, x.data(), y.data(), yaw.data());
  h.pose_hold_steps = 50;  // the world's 1 s steps
  core::SimulateHypothesis(h, cfg, 0, 0, hx.data(), hy.data(), hyaw.data());
  for (int n = 0; n < 150; ++n) {
    const int seen = (n + 1) / 50 * 50 - 1;  // the last pose the world saw (-1: the pose now)
    const double ex = seen < 0 ? 3.0 : x[seen], ey = seen < 0 ? -2.0 : y[seen];
    const double eyaw = seen < 0 ? 0.25 : yaw[seen];
    EXPECT_EQ(hx[n], ex) << n;
    EXPECT_EQ(hy[n], ey) << n;
    EXPECT_EQ(hyaw[n], eyaw) << n;
  }
  EXPECT_GT(x[49], x[0] + 5.0);  // it moves: the hold is seen
  // A walker holds too.
  core::HypothesisSet w = Walker(1.0, 1.0, 1.4, 0.0);
  w.pose_hold_steps = 50;
  core::SimulateHypothesis(w, cfg, 0, 0, hx.data(), hy.data(), hyaw.data());
  EXPECT_EQ(hy[48], 1.0);
  EXPECT_NEAR(hy[49], 1.0 + 1.4, 0.05);
  EXPECT_EQ(hy[98], hy[49]);
}

// Params::euler_stops (HypothesisSet::hold_stops): a vehicle that stops inside one of the
// world's steps stands, at that step and after, where the world's previous step left it, as
// SUMO's update (x += v_new dt) leaves it. Without it the shift (v - v0) dt / 2, exact only for a
// speed that changes linearly between the world's steps, puts it behind that place: behind
// where it stands now for a stop within the first step. Catches a hold that ignores the stop, a
// stop that keeps the wrong step's pose, or one that holds a body still moving.
TEST(EulerUpdate, ABodyThatStopsWithinAWorldStepStaysWhereTheWorldLeftIt) {
  core::SimulationConfig cfg;
  cfg.tau = 0.02;
  cfg.n_steps = 150;  // 3 s
  std::vector<double> x(150), y(150), yaw(150);
  // v0, decel: 5.2 m/s at 9 m/s^2 stops after 0.58 s (SUMO: 0 m); 13 m/s at 9 m/s^2 after
  // 1.44 s (SUMO: 4 m after the first step, then no more); 13.5 at 4.5 stops at 3 s exactly,
  // on a world step (the shift alone is SUMO's: 9, 13.5, 13.5 m).
  struct Case {
    double v0, decel;
    bool stops_on_a_step;  // its speed reaches 0 exactly at a world step: linear throughout
  };
  int linear = 0, inside = 0;
  for (const Case c : {Case{5.2, 9.0, false}, Case{13.0, 9.0, false}, Case{13.5, 4.5, true}}) {
    core::HypothesisSet h = BrakingVehicle(c.v0, c.decel);
    h.position_lead = 0.5;
    h.pose_hold_steps = 50;
    const std::vector<double> sumo = SumoEulerBraking(c.v0, c.decel, 1.0, 3);
    h.hold_stops = true;
    core::SimulateHypothesis(h, cfg, 0, 0, x.data(), y.data(), yaw.data());
    const std::string what = "v0 " + std::to_string(c.v0) + ", decel " + std::to_string(c.decel);
    for (int k = 1; k <= 3; ++k) EXPECT_NEAR(x[k * 50 - 1], sumo[k - 1], 0.05) << what << ", " << k;
    for (int n = 0; n < 150; ++n) EXPECT_GE(x[n], 0.0) << what << ", step " << n;
    // Without it: the same where the speed changes linearly up to the stop, else behind.
    h.hold_stops = false;
    std::vector<double> old(150);
    core::SimulateHypothesis(h, cfg, 0, 0, old.data(), y.data(), yaw.data());
    if (c.stops_on_a_step) {
      ++linear;
      for (int n = 0; n < 150; ++n) EXPECT_EQ(old[n], x[n]) << what << ", step " << n;
    } else {
      ++inside;
      EXPECT_LT(old[149], sumo[2] - 0.5) << what;
    }
  }
  EXPECT_EQ(linear, 1);  // both kinds were checked
  EXPECT_EQ(inside, 2);
  // The first case goes back behind where it stands without the hold: 1.1 m.
  core::HypothesisSet h = BrakingVehicle(5.2, 9.0);
  h.position_lead = 0.5;
  h.pose_hold_steps = 50;
  core::SimulateHypothesis(h, cfg, 0, 0, x.data(), y.data(), yaw.data());
  EXPECT_LT(x[49], -1.0);
  // A walker stopping within a step stays too (1.4 m/s at 2 m/s^2 stops after 0.7 s).
  core::HypothesisSet w = Walker(1.0, 1.0, 1.4, -2.0);
  w.position_lead = 0.5;
  w.pose_hold_steps = 50;
  w.hold_stops = true;
  core::SimulateHypothesis(w, cfg, 0, 0, x.data(), y.data(), yaw.data());
  for (int n = 0; n < 150; ++n) EXPECT_EQ(y[n], 1.0) << "walker, step " << n;
  w.hold_stops = false;
  core::SimulateHypothesis(w, cfg, 0, 0, x.data(), y.data(), yaw.data());
  EXPECT_LT(y[49], 1.0 - 0.1);  // behind where it stands
}

// The estimator with Params::euler_stops: at 1 s steps the ego (5 m/s) brakes hard (8 m/s^2,
// its driver's expectation). Without the hold, every ego hypothesis that stops within the
// first step is put back behind where the ego stands (up to 0.9 m), and the car standing
// behind it, 0.5 m from its back, is "hit".
TEST(EulerUpdate, AnEgoThatStopsWithinAStepDoesNotBackIntoTheCarBehind) {
  Scene s;
  s.ego.state.speed_mps = 5.0;
  s.ego.state.accel_mps2 = -8.0;
  s.ego.state.expected_accel_mps2 = -8.0;
  s.ego.length_m = 5.0;
  Vehicle behind;
  behind.id = "behind";
  behind.length_m = 5.0;
  behind.state.x_m = -5.5;  // 0.5 m between the bumpers, standing
  s.vehicles.push_back(behind);
  s.euler_update_step_s = 1.0;
  Params off, on;
  on.euler_stops = true;
  const Result without = Estimator{off}.Estimate(s);
  const Result with = Estimator{on}.Estimate(s);
  EXPECT_GT(without.p_collision, 0.1);
  EXPECT_LT(with.p_collision, 0.01);
  EXPECT_LT(with.p_collision, without.p_collision);
}

// A car crosses the ego's way at 15 m/s, 8 m ahead of the ego (at 9 m/s) and 10 m to its side:
// it passes through the ego's front between two of SUMO's 1 s steps. Checked every 20 ms, the
// ego's hypotheses meet it; at SUMO's steps it is short of their way (the pose now) and then
// past it, which is all SUMO would see.
Scene CrossingBetweenSteps() {
  Scene s;
  s.ego.state.speed_mps = 9.0;
  s.ego.length_m = 4.6;
  Vehicle v;
  v.id = "crossing";
  v.length_m = 4.6;
  v.state.x_m = 8.0;
  v.state.y_m = -10.0;
  v.state.yaw_rad = 0.5 * M_PI;
  v.state.speed_mps = 15.0;
  s.vehicles.push_back(v);
  s.euler_update_step_s = 1.0;
  return s;
}

TEST(EulerUpdate, APairCollidesAtTheWorldsStepsUnlessTurnedOff) {
  Params at_steps, every_step;
  every_step.collisions_at_world_steps = false;
  EXPECT_TRUE(at_steps.collisions_at_world_steps);  // the default
  const Result every = Estimator{every_step}.Estimate(CrossingBetweenSteps());
  const Result seen = Estimator{at_steps}.Estimate(CrossingBetweenSteps());
  EXPECT_GT(every.p_collision, 0.5);
  EXPECT_LT(seen.p_collision, 0.5 * every.p_collision);
  // Continuous motion (no world step) and a world step that is no multiple of the estimator's
  // step leave every step checked.
  Scene continuous = CrossingBetweenSteps();
  continuous.euler_update_step_s = 0.0;
  Scene odd = CrossingBetweenSteps();
  odd.euler_update_step_s = 0.25;  // 12.5 estimator steps
  EXPECT_EQ(Estimator{at_steps}.Estimate(continuous).p_collision,
            Estimator{every_step}.Estimate(continuous).p_collision);
  EXPECT_EQ(Estimator{at_steps}.Estimate(odd).p_collision,
            Estimator{every_step}.Estimate(odd).p_collision);
}

// The CPU fast path against the reference with held poses (the quick check; every scene
// family: BackendsAgree.PosesHeldBetweenTheWorldsSteps, labelled slow). A stopped car 40 m ahead
// of the ego at 20 m/s: at SUMO's 1 s steps the ego's held pose jumps 20 m at 1 s and 2 s.
// The fast path used to bound a tree node's reach from its last stored pose, a held one up to
// a second old, left out the subtrees that reach the car at 2 s, and gave p 0.0005 for the
// reference's 0.15.
TEST(EulerUpdate, TheFastPathFindsTheReferencesCollisionsWithHeldPoses) {
  Scene scene;
  for (const bench::DiscriminationScene& d : bench::DiscriminationScenes())
    if (d.name == "stopped-car-ttc-2.00") scene = d.scene;
  ASSERT_EQ(scene.vehicles.size(), 1u);
  for (const double world_step : {1.0, 0.5}) {
    scene.euler_update_step_s = world_step;
    EstimatorOptions ref_opt, scalar_opt, simd_opt;
    ref_opt.backend = Backend::kReference;
    scalar_opt.backend = simd_opt.backend = Backend::kCpu;
    ref_opt.keep_pair_matrix = scalar_opt.keep_pair_matrix = true;
    scalar_opt.simd = false;
    simd_opt.simd = true;
    const Result reference = Estimator{Params{}, ref_opt}.Estimate(scene);
    const Result scalar = Estimator{Params{}, scalar_opt}.Estimate(scene);
    EXPECT_GT(reference.p_collision, 0.01) << world_step;  // it collides at SUMO's steps
    // The scalar fast path: bit for bit.
    EXPECT_EQ(reference.first_collision_step, scalar.first_collision_step) << world_step;
    EXPECT_EQ(reference.p_collision, scalar.p_collision) << world_step;
    // The SIMD lanes (trig within a few ulp of libm's): the same p to 1e-6.
    EXPECT_NEAR(reference.p_collision, Estimator(Params{}, simd_opt).Estimate(scene).p_collision,
                1e-6)
        << world_step;
  }
}

}  // namespace
}  // namespace criticality
