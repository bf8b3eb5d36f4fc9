#pragma once
// Longitudinal hypotheses (paper Sec. IV-B-2a): acceleration profiles for the one-track model,
// longitudinal-slip profiles for the two-track model, accelerations for pedestrians.
#include <cmath>

#include "core/hd.h"

namespace criticality::core {

/** Target of vehicle profile k of n (n >= 3) over [lo, hi], lo < 0 < hi. Ascending order:
 *  the minimum, n-3 values equally spaced in the negative range (to favour reducing kinetic
 *  energy), zero (cruising), the maximum. n = 6 over +-9.7: -9.7 -7.275 -4.85 -2.425 0 9.7. */
CRIT_HD double VehicleProfileTarget(int k, int n, double lo, double hi) {
  if (k == n - 1) return hi;
  if (k == n - 2) return 0.0;
  return lo * (1.0 - static_cast<double>(k) / static_cast<double>(n - 2));
}

/** Sample k of n equally distributed over [lo, hi] (pedestrian accelerations); n = 1 gives the
 *  middle. */
CRIT_HD double EquallySpaced(int k, int n, double lo, double hi) {
  if (n <= 1) return 0.5 * (lo + hi);
  return lo + (hi - lo) * static_cast<double>(k) / static_cast<double>(n - 1);
}

/** A profile with latency and a rate limit (jerk for accelerations): holds `start` until
 *  `latency`, then moves towards `target` at `rate` per second and stays there. */
CRIT_HD double RampedValue(double t, double start, double target, double latency, double rate) {
  if (t <= latency) return start;
  const double reach = rate * (t - latency);
  const double gap = target - start;
  if (std::fabs(gap) <= reach) return target;
  return gap > 0.0 ? start + reach : start - reach;
}

}  // namespace criticality::core
