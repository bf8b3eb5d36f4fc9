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
