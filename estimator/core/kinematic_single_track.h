#pragma once
// Kinematic single-track model for low speeds, where the dynamic models' 1/v terms blow up:
// no tyre slip, so beta = atan(lr tan(delta) / (lf + lr)) and dpsi = v cos(beta) tan(delta) / L.
// It sets beta and the yaw rate directly (algebraic), and returns zero derivatives for them.
// With VehicleParams::friction_limited the longitudinal acceleration is limited to mu g and the
// steering angle so that the lateral acceleration v dpsi <= v^2 tan(delta) / L stays within
// what the friction circle leaves, sqrt((mu g)^2 - a_x^2).
#include <cmath>

#include "core/hd.h"
#include "core/min_max.h"
#include "core/state.h"
#include "core/vehicle_params.h"

namespace criticality::core {

CRIT_HD StateDerivative KinematicSingleTrack(const VehicleParams& p, double steer, double v_dot,
                                             MotionState* s) {
  const double wheelbase = p.lf_m + p.lr_m;
  double t = std::tan(steer);
  if (p.friction_limited) {
    const double mu_g = p.friction * kGravity;
    v_dot = Clamp(v_dot, -mu_g, mu_g);
    const double lateral = std::sqrt(Max(0.0, mu_g * mu_g - v_dot * v_dot));
    const double v2 = s->v * s->v;
    if (v2 * std::fabs(t) > lateral * wheelbase) t = std::copysign(lateral * wheelbase / v2, t);
  }
  s->beta = std::atan(p.lr_m * t / wheelbase);
  s->yaw_rate = s->v * std::cos(s->beta) * t / wheelbase;
  StateDerivative d;
  d.v_dot = v_dot;
  return d;
}

}  // namespace criticality::core
