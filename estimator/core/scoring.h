#pragma once
// Hypothesis scores (paper Sec. IV-D-1):
//   n_h = (w_acc n_acc + w_str d_str) / (c_com c_cou)
// n_acc scores the longitudinal profile, d_str the path, both against the reference trajectory
// (keep the current acceleration, follow the own lane's centre); c_com >= 1 penalises complex
// manoeuvres, c_cou >= 1 paths into counter traffic. The paper gives the form, not the
// functions: ours are 1 / (1 + deviation / scale), 1 for the reference and decreasing slowly,
// so that unlikely hypotheses keep some probability (paper Sec. II: unlikely is not impossible).
#include <cmath>

#include "core/hd.h"

namespace criticality::core {

/** Score of a deviation from the reference: 1 / (1 + |deviation| / scale). */
CRIT_HD double DeviationScore(double deviation, double scale) {
  return 1.0 / (1.0 + std::fabs(deviation) / scale);
}

CRIT_HD double HypothesisScore(double w_acc, double n_acc, double w_str, double d_str, double c_com,
                               double c_cou) {
  return (w_acc * n_acc + w_str * d_str) / (c_com * c_cou);
}

}  // namespace criticality::core
