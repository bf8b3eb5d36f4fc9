#pragma once
// Kinematic single-track model for low speeds, where the dynamic models' 1/v terms blow up:
// no tyre slip, so beta = atan(lr tan(delta) / (lf + lr)) and dpsi = v cos(beta) tan(delta) / L.
// It sets beta and the yaw rate directly (algebraic), and returns zero derivatives for them.
#include <cmath>

#include "core/hd.h"
#include "core/state.h"
#include "core/vehicle_params.h"

namespace criticality::core {

CRIT_HD StateDerivative KinematicSingleTrack(const VehicleParams& p, double steer, double v_dot,
                                             MotionState* s) {
  const double wheelbase = p.lf_m + p.lr_m;
  const double t = std::tan(steer);
  s->beta = std::atan(p.lr_m * t / wheelbase);
  s->yaw_rate = s->v * std::cos(s->beta) * t / wheelbase;
  StateDerivative d;
  d.v_dot = v_dot;
  return d;
}

}  // namespace criticality::core
