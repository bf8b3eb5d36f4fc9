#pragma once
// One-track (single-track, "bicycle") model of the other vehicles, paper Sec. IV-B-1b
// (Schramm et al. 2014), in the paper's matrix form:
//   dbeta = -(cf+cr)/(m v) beta + ((cr lr - cf lf)/(m v^2) - 1) dpsi + cf/(m v) delta
//   ddpsi = (cr lr - cf lf)/Iz beta - (cf lf^2 + cr lr^2)/(Iz v) dpsi + cf lf/Iz delta
// It is singular at v = 0; callers switch to the kinematic model below SeamSpeed().
//
// With VehicleParams::friction_limited the same equations are written with the axle side
// forces, m v (dbeta + dpsi) = F_yf + F_yr and Iz ddpsi = lf F_yf - lr F_yr, F_yf = cf alpha_f,
// alpha_f = delta - beta - lf dpsi / v, F_yr = cr alpha_r, alpha_r = -beta + lr dpsi / v (the
// matrix form above, expanded), and each axle's side force saturates at the share of its
// friction limit mu F_z (static load) that the longitudinal acceleration leaves:
// sqrt(1 - (a_x / (mu g))^2). Then |(a_x, F_y / m)| <= mu g: the friction circle of the whole
// vehicle (Params::friction_limited_lateral). Saturation alone lets a hard step steer spin the
// car (both axles saturate together at the limit); as a driver or a stability control would,
// the steering angle is also limited to the steady-state angle at the limit,
// delta_max(v) = (L + EG v^2) a_lat,max / v^2 (EG the understeer gradient, Schramm et al. 2014),
// "a steering limit that depends on speed".
#include <cmath>

#include "core/hd.h"
#include "core/min_max.h"
#include "core/state.h"
#include "core/vehicle_params.h"

namespace criticality::core {

CRIT_HD StateDerivative OneTrackDerivative(const VehicleParams& p, const MotionState& s,
                                           double steer, double v_dot) {
  const double m = p.mass_kg, iz = p.yaw_inertia_kgm2, v = s.v;
  const double cf = p.cf_npr, cr = p.cr_npr, lf = p.lf_m, lr = p.lr_m;
  StateDerivative d;
  if (p.friction_limited) {
    const double mu_g = p.friction * kGravity;
    const double ax = Clamp(v_dot, -mu_g, mu_g);
    const double r = ax / mu_g;
    // Friction left for side force, per unit of axle load (N per N of weight).
    const double side = p.friction * std::sqrt(Max(0.0, 1.0 - r * r));
    const double wheelbase = lf + lr;
    const double weight_per_l = m * kGravity / wheelbase;
    const double f_max = side * weight_per_l * lr, r_max = side * weight_per_l * lf;
    const double gradient = Max(0.0, m * (cr * lr - cf * lf) / (cf * cr * wheelbase));
    const double steer_max = (wheelbase + gradient * v * v) * side * kGravity / (v * v);
    steer = Clamp(steer, -steer_max, steer_max);
    const double fyf = Clamp(cf * (steer - s.beta - lf * s.yaw_rate / v), -f_max, f_max);
    const double fyr = Clamp(cr * (-s.beta + lr * s.yaw_rate / v), -r_max, r_max);
    d.v_dot = ax;
    d.beta_dot = (fyf + fyr) / (m * v) - s.yaw_rate;
    d.yaw_acc = (lf * fyf - lr * fyr) / iz;
    return d;
  }
  d.v_dot = v_dot;
  d.beta_dot = -(cf + cr) / (m * v) * s.beta +
               ((cr * lr - cf * lf) / (m * v * v) - 1.0) * s.yaw_rate + cf / (m * v) * steer;
  d.yaw_acc = (cr * lr - cf * lf) / iz * s.beta -
              (cf * lf * lf + cr * lr * lr) / (iz * v) * s.yaw_rate + cf * lf / iz * steer;
  return d;
}

/** Speed below which the dynamic models are replaced by the kinematic one: the configured
 *  kinematic_below_mps, raised when needed so that explicit Euler with step tau stays stable
 *  (the fastest eigenvalues of the one-track model are about -(cf+cr)/(m v) and
 *  -(cf lf^2 + cr lr^2)/(Iz v); Euler needs |lambda| tau <= 2, we keep
 *  |lambda| tau <= 1 / stability_factor). */
CRIT_HD double SeamSpeed(const VehicleParams& p, double tau, double stability_factor) {
  const double k1 = (p.cf_npr + p.cr_npr) / p.mass_kg;
  const double k2 = (p.cf_npr * p.lf_m * p.lf_m + p.cr_npr * p.lr_m * p.lr_m) / p.yaw_inertia_kgm2;
  return Max(p.kinematic_below_mps, stability_factor * tau * Max(k1, k2));
}

}  // namespace criticality::core
