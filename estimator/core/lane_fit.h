#pragma once
// Street data processing (paper Sec. IV-A): a lane divider given by three points in an object's
// local frame becomes the parabola y = a x^2 + b x + c, solved by Gauss-Jordan elimination
// (paper ref. [Ansorge & Oberle]) on the 3x3 system [x_i^2 x_i 1] [a b c]^T = y_i.
#include <cmath>

#include "core/hd.h"

namespace criticality::core {

/** y(x) = a x^2 + b x + c in an object's local frame. */
struct Parabola {
  double a{0.0};
  double b{0.0};
  double c{0.0};
  CRIT_HD double Eval(double x) const { return (a * x + b) * x + c; }
  CRIT_HD double Slope(double x) const { return 2.0 * a * x + b; }
};

/** Pointwise blend (1 - f) * p + f * q: the curve "parallel" to two dividers that passes at
 *  fraction f across the lane they delimit (used for path sections, paper Sec. IV-B-2b). */
CRIT_HD Parabola Blend(const Parabola& p, const Parabola& q, double f) {
  return Parabola{(1.0 - f) * p.a + f * q.a, (1.0 - f) * p.b + f * q.b, (1.0 - f) * p.c + f * q.c};
}

/** Relative pivot size below which the system counts as singular. */
constexpr double kLaneFitPivotTolerance = 1e-10;

/** Gauss-Jordan elimination with partial pivoting on the Vandermonde system through
 *  (x[i], y[i]). @returns false (leaving *out untouched) when the points do not define a
 *  function of x: repeated or (near-)equal x values, e.g. a divider that is vertical in the
 *  local frame. */
CRIT_HD bool FitParabola(const double x[3], const double y[3], Parabola* out) {
  double m[3][4];
  double scale = 0.0;
  for (int i = 0; i < 3; ++i) {
    m[i][0] = x[i] * x[i];
    m[i][1] = x[i];
    m[i][2] = 1.0;
    m[i][3] = y[i];
    for (int j = 0; j < 3; ++j) scale = std::fmax(scale, std::fabs(m[i][j]));
    if (!std::isfinite(m[i][0]) || !std::isfinite(m[i][3])) return false;
  }
  for (int col = 0; col < 3; ++col) {
    int pivot = col;
    for (int r = col + 1; r < 3; ++r) {
      if (std::fabs(m[r][col]) > std::fabs(m[pivot][col])) pivot = r;
    }
    if (!(std::fabs(m[pivot][col]) > kLaneFitPivotTolerance * scale)) return false;
    if (pivot != col) {
      for (int j = 0; j < 4; ++j) {
        const double t = m[col][j];
        m[col][j] = m[pivot][j];
        m[pivot][j] = t;
      }
    }
    const double inv = 1.0 / m[col][col];
    for (int j = col; j < 4; ++j) m[col][j] *= inv;
    for (int r = 0; r < 3; ++r) {
      if (r == col) continue;
      const double f = m[r][col];
      for (int j = col; j < 4; ++j) m[r][j] -= f * m[col][j];
    }
  }
  out->a = m[0][3];
  out->b = m[1][3];
  out->c = m[2][3];
  return true;
}

}  // namespace criticality::core
