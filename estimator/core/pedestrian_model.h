#pragma once
// Kinematic pedestrian model (paper Sec. IV-B-3), no controller:
//   [x, y]_{n+1} = [x, y]_n + [c(psi_P), s(psi_P)] (v_n tau + dv_n tau^2 / 2)
// with |v| limited to max_speed (paper: 2.7 m/s). When the limit (or zero) cuts the speed, the
// acceleration is reduced to what actually happened, so the displacement of one step never
// exceeds max_speed * tau.
#include <cmath>

#include "core/hd.h"
#include "core/min_max.h"

namespace criticality::core {

CRIT_HD void PedestrianStep(double heading, double accel, double max_speed, double tau, double* x,
                            double* y, double* v) {
  double v_next = *v + accel * tau;
  v_next = Clamp(v_next, 0.0, max_speed);
  const double accel_eff = (v_next - *v) / tau;
  const double dist = *v * tau + accel_eff * 0.5 * tau * tau;
  *x += std::cos(heading) * dist;
  *y += std::sin(heading) * dist;
  *v = v_next;
}

}  // namespace criticality::core
