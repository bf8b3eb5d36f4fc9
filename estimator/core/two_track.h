#pragma once
// Two-track model of the ego (paper Sec. IV-B-1a, Mitschke & Wallentowitz): the state
// derivative [dv, dbeta, ddpsi] from the forces of the four tyres.
//
// Where the paper is silent we chose (DESIGN.md): static wheel loads (no load transfer); the
// same longitudinal slip on all four wheels (the slip profile drives/brakes every wheel);
// longitudinal force from Pacejka's magic formula F_x = mu F_z sin(C atan(B slip)) with the
// dry-asphalt shape factor C = 1.65 and the peak at slip 0.1 (the paper's slip range);
// lateral force linear in the slip angle with half the axle's cornering stiffness per wheel;
// combined force limited to the friction circle mu F_z. No air or rolling resistance, so zero
// slip coasts, like the one-track model's zero acceleration profile.
#include <cmath>

#include "core/geometry.h"
#include "core/hd.h"
#include "core/min_max.h"
#include "core/state.h"
#include "core/vehicle_params.h"

namespace criticality::core {

constexpr double kMagicFormulaShapeC = 1.65;
constexpr double kMagicFormulaPeakSlip = 0.1;
/** Stiffness factor B = tan(pi / (2 C)) / peak slip, so that the force peaks at the peak slip
 *  (tests/estimator/core/motion_models_test.cc checks it against the formula). */
constexpr double kMagicFormulaB = 14.043035064481925;

/** Normalised longitudinal force F_x / (mu F_z) at longitudinal slip `slip`. */
CRIT_HD double LongitudinalForceFactor(double slip) {
  const double b = kMagicFormulaB;
  const double arg = Clamp(kMagicFormulaShapeC * std::atan(b * slip), -kPi / 2.0, kPi / 2.0);
  return std::sin(arg);
}

/** Steady longitudinal acceleration (straight line) that a slip gives on every wheel. */
CRIT_HD double AccelFromSlip(const VehicleParams& p, double slip) {
  return p.friction * kGravity * LongitudinalForceFactor(slip);
}

/** Inverse of AccelFromSlip on the stable branch |slip| <= peak; saturates beyond mu g. */
CRIT_HD double SlipFromAccel(const VehicleParams& p, double accel) {
  const double b = kMagicFormulaB;
  double f = accel / (p.friction * kGravity);
  f = std::fmax(-1.0, std::fmin(1.0, f));
  return std::tan(std::asin(f) / kMagicFormulaShapeC) / b;
}

/** Sum of the four tyre forces in the vehicle frame and their yaw moment about the CoG. */
struct ChassisForces {
  double fx{0.0};
  double fy{0.0};
  double mz{0.0};
};

/** @param cb, sb cos and sin of s.beta; fx_factor LongitudinalForceFactor(slip) (the caller
 *  has them). */
CRIT_HD ChassisForces TwoTrackForces(const VehicleParams& p, const MotionState& s, double steer,
                                     double fx_factor, double cb, double sb) {
  const double wheelbase = p.lf_m + p.lr_m;
  const double weight = p.mass_kg * kGravity;
  const double fz_front = 0.5 * weight * p.lr_m / wheelbase;  // per wheel
  const double fz_rear = 0.5 * weight * p.lf_m / wheelbase;
  const double vx_cog = s.v * cb, vy_cog = s.v * sb;
  const double cos_steer = std::cos(steer), sin_steer = std::sin(steer);
  ChassisForces out;
  for (int wheel = 0; wheel < 4; ++wheel) {
    const bool front = wheel < 2;
    const double xw = front ? p.lf_m : -p.lr_m;
    const double yw = (wheel % 2 == 0) ? 0.5 * p.track_m : -0.5 * p.track_m;
    const double delta = front ? steer : 0.0;
    const double fz = front ? fz_front : fz_rear;
    const double c_wheel = 0.5 * (front ? p.cf_npr : p.cr_npr);
    // Velocity of the wheel centre in the vehicle frame, then its slip angle.
    const double vx = vx_cog - s.yaw_rate * yw;
    const double vy = vy_cog + s.yaw_rate * xw;
    // vx > 0 above the seam speed (the model is not used below it), so atan(vy / vx) is
    // atan2(vy, vx), at about half the cost.
    const double alpha = delta - std::atan(vy / vx);
    double fl = p.friction * fz * fx_factor;  // in the wheel frame
    double fs = c_wheel * alpha;
    const double limit = p.friction * fz;
    const double norm = std::sqrt(fl * fl + fs * fs);
    if (norm > limit) {
      fl *= limit / norm;
      fs *= limit / norm;
    }
    const double cd = front ? cos_steer : 1.0, sd = front ? sin_steer : 0.0;
    const double fxv = cd * fl - sd * fs;
    const double fyv = sd * fl + cd * fs;
    out.fx += fxv;
    out.fy += fyv;
    out.mz += xw * fyv - yw * fxv;
  }
  return out;
}

/** [dv, dbeta, ddpsi] of the two-track model. Singular at v = 0 (see SeamSpeed). */
CRIT_HD ChassisForces TwoTrackForces(const VehicleParams& p, const MotionState& s, double steer,
                                     double slip) {
  return TwoTrackForces(p, s, steer, LongitudinalForceFactor(slip), std::cos(s.beta),
                        std::sin(s.beta));
}

/** [dv, dbeta, ddpsi]; cb, sb = cos/sin(s.beta), fx_factor = LongitudinalForceFactor(slip). */
CRIT_HD StateDerivative TwoTrackDerivative(const VehicleParams& p, const MotionState& s,
                                           double steer, double fx_factor, double cb, double sb) {
  const ChassisForces f = TwoTrackForces(p, s, steer, fx_factor, cb, sb);
  StateDerivative d;
  d.v_dot = (f.fx * cb + f.fy * sb) / p.mass_kg;
  d.beta_dot = (-f.fx * sb + f.fy * cb) / (p.mass_kg * s.v) - s.yaw_rate;
  d.yaw_acc = f.mz / p.yaw_inertia_kgm2;
  return d;
}

CRIT_HD StateDerivative TwoTrackDerivative(const VehicleParams& p, const MotionState& s,
                                           double steer, double slip) {
  return TwoTrackDerivative(p, s, steer, LongitudinalForceFactor(slip), std::cos(s.beta),
                            std::sin(s.beta));
}

}  // namespace criticality::core
