// Vehicle motion models (paper Sec. IV-B-1): one-track against the linear single-track
// steady state, the low-speed seam, two-track against one-track at small slip.
#include <gtest/gtest.h>

#include <cmath>

#include "core/euler_integration.h"
#include "core/kinematic_single_track.h"
#include "core/one_track.h"
#include "core/two_track.h"
#include "criticality/vehicle_class.h"

namespace criticality::core {
namespace {

constexpr double kTau = 0.02;

VehicleParams Car() { return VehicleParamsFor(VehicleClass::kLargeFamily, 4.6, 1.8); }

// One step of the model the trajectory generator uses at this speed.
void OneTrackStep(const VehicleParams& p, double steer, double v_dot, MotionState* s) {
  StateDerivative d = s->v < SeamSpeed(p, kTau, 1.5) ? KinematicSingleTrack(p, steer, v_dot, s)
                                                     : OneTrackDerivative(p, *s, steer, v_dot);
  d.v_dot = NonReversingAccel(s->v, d.v_dot, kTau);
  EulerStep(d, kTau, s);
}

TEST(OneTrack, SteadyStateYawRateMatchesLinearSingleTrackFormula) {
  const VehicleParams p = Car();
  const double wheelbase = p.lf_m + p.lr_m;
  // Self-steering gradient of the linear single-track model (Schramm et al. 2014).
  const double eg =
      p.mass_kg * (p.cr_npr * p.lr_m - p.cf_npr * p.lf_m) / (p.cf_npr * p.cr_npr * wheelbase);
  ASSERT_GT(eg, 0.0) << "understeering car expected";
  for (double v : {5.0, 15.0, 30.0}) {
    for (double steer : {0.01, 0.03}) {
      MotionState s;
      s.v = v;
      for (int n = 0; n < 500; ++n) OneTrackStep(p, steer, 0.0, &s);
      const double expected = v * steer / (wheelbase + eg * v * v);
      EXPECT_NEAR(s.yaw_rate, expected, 0.005 * expected) << "v=" << v << " steer=" << steer;
      EXPECT_NEAR(s.v, v, 1e-12);
    }
  }
}

TEST(OneTrack, LowSpeedSeamIsContinuousAndStopsCleanly) {
  const VehicleParams p = Car();
  const double seam = SeamSpeed(p, kTau, 1.5);
  ASSERT_GE(seam, p.kinematic_below_mps);
  MotionState s;
  s.v = seam + 2.0;
  const double steer = 0.1;
  // Settle at constant speed, then brake gently through the seam to a stop.
  for (int n = 0; n < 200; ++n) OneTrackStep(p, steer, 0.0, &s);
  double prev_rate = s.yaw_rate;
  double max_jump = 0.0, jump_at_seam = 0.0;
  bool crossed = false;
  for (int n = 0; n < 400; ++n) {
    const bool above = s.v >= seam;
    OneTrackStep(p, steer, -1.0, &s);
    ASSERT_TRUE(std::isfinite(s.x) && std::isfinite(s.yaw_rate) && std::isfinite(s.beta));
    ASSERT_GE(s.v, 0.0);
    const double jump = std::fabs(s.yaw_rate - prev_rate);
    if (above && s.v < seam) {
      crossed = true;
      jump_at_seam = jump;
    } else {
      max_jump = std::fmax(max_jump, jump);
    }
    prev_rate = s.yaw_rate;
  }
  ASSERT_TRUE(crossed);
  // The yaw rate at the seam changes no more than 2% of its value there (kinematic and
  // dynamic steady states nearly agree at low speed), and it ends at rest.
  EXPECT_LT(jump_at_seam,
            0.02 * std::fabs(prev_rate) + 0.02 * seam * std::tan(steer) / (p.lf_m + p.lr_m));
  EXPECT_EQ(s.v, 0.0);
  EXPECT_EQ(s.yaw_rate, 0.0);
}

TEST(OneTrack, SeamSpeedKeepsEulerStableForEveryClass) {
  for (VehicleClass c : {VehicleClass::kQuadricycle, VehicleClass::kSupermini,
                         VehicleClass::kExecutive, VehicleClass::kCargo}) {
    VehicleParams p = VehicleParamsFor(c, 4.5, 1.8);
    p.kinematic_below_mps = 0.0;  // the stability bound alone
    const double seam = SeamSpeed(p, kTau, 1.5);
    MotionState s;
    s.v = seam * 1.001;
    s.beta = 0.05;  // disturbed
    for (int n = 0; n < 500; ++n) OneTrackStep(p, 0.0, 0.0, &s);
    EXPECT_LT(std::fabs(s.beta), 1e-3) << VehicleClassName(c);
    EXPECT_LT(std::fabs(s.yaw_rate), 1e-3) << VehicleClassName(c);
  }
}

TEST(TwoTrack, AgreesWithOneTrackAtSmallSlip) {
  const VehicleParams p = Car();
  for (double steer : {0.005, 0.02}) {
    MotionState one, two;
    one.v = two.v = 20.0;
    for (int n = 0; n < 100; ++n) {
      OneTrackStep(p, steer, 0.0, &one);
      StateDerivative d = TwoTrackDerivative(p, two, steer, 0.0);
      EulerStep(d, kTau, &two);
    }
    // Same path within a few percent. The two-track car also slows slightly: the steered
    // front tyres' side force has a component against the motion (cornering drag), which the
    // one-track model with a zero acceleration profile does not have.
    EXPECT_NEAR(two.yaw_rate, one.yaw_rate, 0.03 * std::fabs(one.yaw_rate)) << steer;
    EXPECT_NEAR(two.y, one.y, 0.02 + 0.03 * std::fabs(one.y)) << steer;
    EXPECT_NEAR(two.x, one.x, 0.005 * one.x) << steer;
    EXPECT_NEAR(two.v, one.v, 0.005 * one.v) << steer;
    EXPECT_LE(two.v, one.v) << steer;
  }
}

TEST(TwoTrack, SlipGivesTheTyreCurveDeceleration) {
  const VehicleParams p = Car();
  MotionState s;
  s.v = 20.0;
  for (double slip : {-0.1, -0.05, -0.025, 0.0, 0.1}) {
    const StateDerivative d = TwoTrackDerivative(p, s, 0.0, slip);
    EXPECT_NEAR(d.v_dot, AccelFromSlip(p, slip), 1e-9) << slip;
    EXPECT_NEAR(d.yaw_acc, 0.0, 1e-9);
  }
  EXPECT_NEAR(AccelFromSlip(p, -0.1), -p.friction * kGravity, 1e-9);  // the peak
  for (double a : {-9.0, -3.0, 0.0, 4.0})
    EXPECT_NEAR(AccelFromSlip(p, SlipFromAccel(p, a)), a, 1e-9);
}

TEST(TwoTrack, FrictionCircleLimitsCombinedForce) {
  const VehicleParams p = Car();
  MotionState s;
  s.v = 20.0;
  const ChassisForces f = TwoTrackForces(p, s, 0.5, -0.1);  // full brake and full steer
  EXPECT_LE(std::hypot(f.fx, f.fy), p.friction * p.mass_kg * kGravity * (1.0 + 1e-9));
}

}  // namespace
}  // namespace criticality::core

namespace criticality::core {
namespace {
TEST(TwoTrack, MagicFormulaStiffnessPeaksAtThePeakSlip) {
  EXPECT_NEAR(kMagicFormulaB, std::tan(kPi / (2.0 * kMagicFormulaShapeC)) / kMagicFormulaPeakSlip,
              1e-12);
  EXPECT_NEAR(LongitudinalForceFactor(kMagicFormulaPeakSlip), 1.0, 1e-12);
  EXPECT_LT(LongitudinalForceFactor(0.9 * kMagicFormulaPeakSlip), 1.0);
}
}  // namespace
}  // namespace criticality::core

namespace criticality::core {
namespace {

TEST(Euler, OneStepByHand) {
  // The paper's equations with tau = 0.1 s from x = 1, y = 2, psi = 0.3, v = 10, beta = 0.05,
  // dpsi = 0.2, a_x = 0.5, a_y = 2 and [dv, dbeta, ddpsi] = [-1, 0.01, 0.1]:
  //   x' = 1 + cos(0.35) 10 0.1 + cos(0.3) 0.5 0.005 - sin(0.3) 2 0.005
  //      = 1 + 0.939372713 + 0.002388351 - 0.002955202 = 1.938805852
  //   y' = 2 + sin(0.35) 1 + sin(0.3) 0.0025 + cos(0.3) 0.01 = 2.353189973
  //   psi' = 0.3 + 0.02 + 0.0005 = 0.3205, dpsi' = 0.21, v' = 9.9, beta' = 0.051
  //   a_x' = cos(0.05) (-1) - sin(0.05) 10 (0.21) = -0.998750260 - 0.104956301 = -1.103706516
  //   a_y' = sin(0.05) (-1) + cos(0.05) 10 (0.21) = -0.049979169 + 2.097375546 = 2.047396378
  MotionState s;
  s.x = 1.0;
  s.y = 2.0;
  s.yaw = 0.3;
  s.v = 10.0;
  s.beta = 0.05;
  s.yaw_rate = 0.2;
  s.ax = 0.5;
  s.ay = 2.0;
  StateDerivative d;
  d.v_dot = -1.0;
  d.beta_dot = 0.01;
  d.yaw_acc = 0.1;
  EulerStep(d, 0.1, &s);
  EXPECT_NEAR(s.x, 1.938805852, 1e-9);
  EXPECT_NEAR(s.y, 2.353189973, 1e-9);
  EXPECT_NEAR(s.yaw, 0.3205, 1e-12);
  EXPECT_NEAR(s.yaw_rate, 0.21, 1e-12);
  EXPECT_NEAR(s.v, 9.9, 1e-12);
  EXPECT_NEAR(s.beta, 0.051, 1e-12);
  EXPECT_NEAR(s.ax, -1.103706516, 1e-9);
  EXPECT_NEAR(s.ay, 2.047396378, 1e-9);
}

TEST(TwoTrack, SteadyCorneringFollowsTheLinearModelAndSaturatesAtTheFrictionLimit) {
  const VehicleParams p = Car();
  const double wheelbase = p.lf_m + p.lr_m;
  const double eg =
      p.mass_kg * (p.cr_npr * p.lr_m - p.cf_npr * p.lf_m) / (p.cf_npr * p.cr_npr * wheelbase);
  {  // Small steer, 15 m/s, constant speed held by a small drive slip: steady circle.
    MotionState s;
    s.v = 15.0;
    const double steer = 0.02;
    for (int n = 0; n < 1000; ++n) {
      StateDerivative d = TwoTrackDerivative(p, s, steer, 0.0);
      d.v_dot = 0.0;  // hold the speed (the test is about the lateral steady state)
      EulerStep(d, kTau, &s);
    }
    const double expected = s.v * steer / (wheelbase + eg * s.v * s.v);
    EXPECT_NEAR(s.yaw_rate, expected, 0.03 * expected);
    EXPECT_NEAR(s.ay, s.v * s.yaw_rate, 0.01 * s.v * s.yaw_rate);  // steady: a_y = v dpsi
  }
  {  // Large steer at 20 m/s: the tyres saturate; |a| <= mu g, and near it.
    MotionState s;
    s.v = 20.0;
    double peak = 0.0;
    for (int n = 0; n < 150; ++n) {
      const StateDerivative d = TwoTrackDerivative(p, s, 0.3, 0.0);
      EulerStep(d, kTau, &s);
      const double a = std::hypot(s.ax, s.ay);
      EXPECT_LE(a, p.friction * kGravity * (1.0 + 1e-9)) << n;
      peak = std::fmax(peak, a);
    }
    EXPECT_GT(peak, 0.9 * p.friction * kGravity);
    EXPECT_GT(s.yaw_rate, 0.0);  // still turning left, not spun round
    EXPECT_LT(std::fabs(s.beta), 0.3);
  }
}

TEST(OneTrack, FrictionLimitedModelSaturatesWithoutSpinning) {
  VehicleParams p = Car();
  p.friction_limited = true;
  MotionState s;
  s.v = 30.0;
  // 0.1 rad at 30 m/s asks the linear model for about 2 g; the saturated one gives mu g.
  double peak = 0.0;
  for (int n = 0; n < 150; ++n) {
    const StateDerivative d = OneTrackDerivative(p, s, 0.1, 0.0);
    EulerStep(d, kTau, &s);
    const double a = std::hypot(s.ax, s.ay);
    EXPECT_LE(a, p.friction * kGravity * (1.0 + 1e-9)) << n;
    peak = std::fmax(peak, a);
  }
  EXPECT_GT(peak, 0.99 * p.friction * kGravity);
  EXPECT_LT(std::fabs(s.beta), 0.2);
  // Unsaturated (small steer), the force form gives the paper's matrix form.
  MotionState q;
  q.v = 20.0;
  q.beta = 0.01;
  q.yaw_rate = 0.05;
  VehicleParams linear = Car();
  const StateDerivative a = OneTrackDerivative(p, q, 0.02, -1.0);
  const StateDerivative b = OneTrackDerivative(linear, q, 0.02, -1.0);
  EXPECT_NEAR(a.beta_dot, b.beta_dot, 1e-12);
  EXPECT_NEAR(a.yaw_acc, b.yaw_acc, 1e-12);
  EXPECT_EQ(a.v_dot, b.v_dot);
  // Braking at mu g leaves no side force.
  const StateDerivative c = OneTrackDerivative(p, q, 0.02, -p.friction * kGravity);
  EXPECT_NEAR(c.beta_dot + q.yaw_rate, 0.0, 1e-12);
}

}  // namespace
}  // namespace criticality::core

#include "core/trajectory_generation.h"

namespace criticality::core {
namespace {

TEST(TwoTrack, EgoLowSpeedSeamIsContinuousAndStopsCleanly) {
  // The ego's hypothesis machinery (two-track model, controller, kinematic model below the
  // seam): braking gently at 1 m/s^2 through the seam while steering towards a path 2 m to
  // the left, down to a stop.
  HypothesisSet h;
  h.model = MotionModelKind::kTwoTrack;
  h.vehicle = Car();
  h.vehicle.friction_limited = true;
  h.seam_speed = SeamSpeed(h.vehicle, kTau, 1.5);
  h.v0 = h.seam_speed + 1.5;
  h.force_profiles = true;
  h.n_profiles = 1;
  h.profile_target[0] = -1.0 / (h.vehicle.friction * kGravity);
  h.rate = 10.0;
  h.n_instants = 1;
  h.instant_time[0] = 10.0;
  h.n_lateral = 1;
  h.section[0][0] = Parabola{0.0, 0.0, 2.0};
  h.n_paths = 1;
  SimulationConfig cfg;
  cfg.n_steps = 400;
  std::vector<double> x(400), y(400), yaw(400), steer(400);
  std::vector<MotionState> state(400);
  StepTrace trace{state.data(), steer.data()};
  SimulateHypothesis(h, cfg, 0, 0, x.data(), y.data(), yaw.data(), 1, &trace);
  double prev_v = h.v0, prev_rate = 0.0, jump_at_seam = -1.0, max_jump = 0.0;
  for (int n = 0; n < 400; ++n) {
    const MotionState& s = state[n];
    ASSERT_TRUE(std::isfinite(s.x) && std::isfinite(s.yaw_rate) && std::isfinite(s.beta)) << n;
    ASSERT_GE(s.v, 0.0);
    const double jump = std::fabs(s.yaw_rate - prev_rate);
    if (prev_v >= h.seam_speed && s.v < h.seam_speed) {
      jump_at_seam = jump;
    } else if (n > 0) {
      max_jump = std::fmax(max_jump, jump);
    }
    prev_v = s.v;
    prev_rate = s.yaw_rate;
  }
  ASSERT_GE(jump_at_seam, 0.0) << "never crossed the seam";
  // Crossing the seam changes the yaw rate by less than a tenth of the largest change of any
  // other step (the controller steering at its rate limit; measured: 0.001 against 0.032
  // rad/s), and the car ends at rest.
  EXPECT_LT(jump_at_seam, 0.1 * max_jump);
  EXPECT_GT(state[399].y, 1.0);  // it did steer towards the path
  EXPECT_EQ(state[399].v, 0.0);
  EXPECT_EQ(state[399].yaw_rate, 0.0);
}

}  // namespace
}  // namespace criticality::core
