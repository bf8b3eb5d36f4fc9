#pragma once
// Hypothesis scores (paper Sec. IV-D-1):
//   n_h = (w_acc n_acc + w_str d_str) / (c_com c_cou)
// n_acc scores the longitudinal profile, d_str the path, both against the reference trajectory
// (keep the current acceleration, follow the own lane's centre); c_com >= 1 penalises complex
// manoeuvres, c_cou >= 1 paths into counter traffic. The paper gives the form, not the
// functions. Two sets (Params::Scoring): the paper-literal one, 1 / (1 + deviation / scale)
// (decreasing slowly, so that an extreme hypothesis keeps a sizeable share), and the
// naturalistic one, Gaussian in the deviation with widths from naturalistic driving data
// (src/problem.cc says which deviations).
#include <cmath>

#include "core/hd.h"

namespace criticality::core {

/** Score of a deviation from the reference: 1 / (1 + |deviation| / scale). */
CRIT_HD double DeviationScore(double deviation, double scale) {
  return 1.0 / (1.0 + std::fabs(deviation) / scale);
}

/** Gaussian score of normalised squared deviations: exp(-z2 / 2), z2 = sum of (dev / sigma)^2.
 *  z2 is capped at 1200 (a score of about 1e-261) so that no hypothesis gets probability 0:
 *  unlikely is not impossible (paper Sec. II). */
CRIT_HD double GaussianScore(double z2) { return std::exp(-0.5 * (z2 < 1200.0 ? z2 : 1200.0)); }

CRIT_HD double HypothesisScore(double w_acc, double n_acc, double w_str, double d_str, double c_com,
                               double c_cou) {
  return (w_acc * n_acc + w_str * d_str) / (c_com * c_cou);
}

}  // namespace criticality::core
