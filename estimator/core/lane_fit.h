#pragma once
// Street data processing (paper Sec. IV-A): a lane divider given by three points in an object's
// local frame becomes the parabola y = a x^2 + b x + c, solved by Gauss-Jordan elimination
// (paper ref. [Ansorge & Oberle]) on the 3x3 system [x_i^2 x_i 1] [a b c]^T = y_i.
#include <cmath>

#include "core/hd.h"

namespace criticality::core {

/** y(x) = a x^2 + b x + c in an object's local frame, or, for a lane that turns far across
 *  the object's heading (Params::turn_lane_frame), in that frame rotated by `rot` (x along the
 *  lane's chord), continued along its tangent beyond x_end and, for a straight road before a
 *  turn (Lane::straight_to_middle), along its tangent before x_start. With the defaults
 *  (rot = 0, x_start = -inf, x_end = +inf) it is the paper's parabola in the local frame. */
struct Parabola {
  double a{0.0};
  double b{0.0};
  double c{0.0};
  double rot{0.0};      ///< angle of the parabola's frame in the local frame (rad)
  double cos_rot{1.0};  ///< cos(rot)
  double sin_rot{0.0};  ///< sin(rot)
  /** Beyond this x (in the parabola's frame) the curve continues straight along its tangent
   *  there: a lane sampled to the end of a turn leaves it straight instead of turning on. */
  double x_end{HUGE_VAL};
  /** Before this x (in the parabola's frame) the curve is the straight line tangent to it
   *  there: the straight road before a turn. */
  double x_start{-HUGE_VAL};
  /** True where the curve follows the parabola (x_start <= x <= x_end), not a straight end. */
  CRIT_HD bool Curved(double x) const { return x >= x_start && x <= x_end; }
  /** y and dy/dx at x, both in the parabola's frame. */
  CRIT_HD double Eval(double x) const {
    const double xc = x < x_start ? x_start : (x > x_end ? x_end : x);
    return (a * xc + b) * xc + c + (2.0 * a * xc + b) * (x - xc);
  }
  CRIT_HD double Slope(double x) const {
    return 2.0 * a * (x < x_start ? x_start : (x < x_end ? x : x_end)) + b;
  }
  /** Unsigned curvature at x (parabola's frame): 2|a| / (1 + slope^2)^1.5; 0 on the straight
   *  ends. */
  CRIT_HD double Curvature(double x) const {
    if (!Curved(x)) return 0.0;
    const double m = Slope(x);
    const double q = 1.0 + m * m;
    return 2.0 * std::fabs(a) / (q * std::sqrt(q));
  }
  /** A point of the local frame in the parabola's frame. */
  CRIT_HD void ToFrame(double x, double y, double* xr, double* yr) const {
    *xr = cos_rot * x + sin_rot * y;
    *yr = -sin_rot * x + cos_rot * y;
  }
  /** The curve's point at xr (parabola's frame), in the local frame. */
  CRIT_HD void PointAt(double xr, double* x, double* y) const {
    const double yr = Eval(xr);
    *x = cos_rot * xr - sin_rot * yr;
    *y = sin_rot * xr + cos_rot * yr;
  }
  /** Curve minus point along the parabola frame's y axis, for a point of the local frame
   *  (positive: the curve lies to the left of the point as the frame sees it). */
  CRIT_HD double OffsetFrom(double x, double y) const {
    double xr, yr;
    ToFrame(x, y, &xr, &yr);
    return Eval(xr) - yr;
  }
  /** Direction of the curve at xr (parabola's frame), as an angle in the local frame. */
  CRIT_HD double Direction(double xr) const { return std::atan(Slope(xr)) + rot; }
  /** The same curve written in a frame rotated by r (its coefficients unchanged). */
  CRIT_HD void SetFrame(double r) {
    rot = r;
    cos_rot = std::cos(r);
    sin_rot = std::sin(r);
  }
};

/** Pointwise blend (1 - f) * p + f * q: the curve "parallel" to two dividers that passes at
 *  fraction f across the lane they delimit (used for path sections, paper Sec. IV-B-2b). Both
 *  must be written in the same frame; the blend keeps p's frame, x_start and x_end. */
CRIT_HD Parabola Blend(const Parabola& p, const Parabola& q, double f) {
  Parabola out = p;
  out.a = (1.0 - f) * p.a + f * q.a;
  out.b = (1.0 - f) * p.b + f * q.b;
  out.c = (1.0 - f) * p.c + f * q.c;
  return out;
}

/** The x (parabola's frame) reached after arc length s along the curve from x0. In the
 *  paper's frame (rot = 0) a distance along the road is taken as a distance along x, as the
 *  paper does; in a rotated frame the arc is integrated (16 midpoint steps). */
CRIT_HD double XAfterArc(const Parabola& p, double x0, double s) {
  if (p.rot == 0.0) return x0 + s;
  const int n = 16;
  const double ds = s / n;
  double x = x0;
  for (int i = 0; i < n; ++i) {
    const double m1 = p.Slope(x);
    const double xm = x + 0.5 * ds / std::sqrt(1.0 + m1 * m1);
    const double m2 = p.Slope(xm);
    x += ds / std::sqrt(1.0 + m2 * m2);
  }
  return x;
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

/** The straight road before a turn (Lane::straight_to_middle): y = c + b x up to x_start,
 *  continued beyond it by the parabola tangent to that line there,
 *  y = c + b x + k (x - x_start)^2, through the three points. The dividers of one lane share
 *  x_start (the mean of their middle points' x), so that blends between them stay straight
 *  before it too. @returns false (leaving *out untouched) unless x[0] < x_start < x[2] and
 *  x[0] < x[1] < x[2]. */
CRIT_HD bool FitStraightThenParabola(const double x[3], const double y[3], double x_start,
                                     Parabola* out) {
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(x[i]) || !std::isfinite(y[i])) return false;
  }
  if (!std::isfinite(x_start) || !(x[0] < x[1] && x[1] < x[2]) ||
      !(x[0] < x_start && x_start < x[2]))
    return false;
  // With d_i = max(0, x_i - x_start): b (x_i - x_0) + k d_i^2 = y_i - y_0 for i = 1, 2.
  const double d1 = x[1] > x_start ? x[1] - x_start : 0.0, d2 = x[2] - x_start;
  const double det = (x[1] - x[0]) * d2 * d2 - (x[2] - x[0]) * d1 * d1;
  const double span = x[2] - x[0];
  if (!(std::fabs(det) > kLaneFitPivotTolerance * span * span * span)) return false;
  const double k = ((x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0])) / det;
  const double b = (y[1] - y[0] - k * d1 * d1) / (x[1] - x[0]);
  const double c = y[0] - b * x[0];
  out->a = k;
  out->b = b - 2.0 * k * x_start;
  out->c = c + k * x_start * x_start;
  out->x_start = x_start;
  return true;
}

/** A lane turning at a corner (Lane::corner_tangent_m): the straight through (x[0], y[0]) and
 *  the corner (x[1], y[1]) up to x_start, the parabola tangent to it there and, at x_end, to
 *  the straight from the corner through (x[2], y[2]), that straight beyond x_end. The two
 *  tangents of a parabola meet halfway between their points of contact, so with x_start and
 *  x_end centred on x[1] the second straight is exact; shared by both dividers of a lane
 *  (centred on their mean corner) it is parallel to it. @returns false (leaving *out untouched)
 *  unless x[0] < x[1] < x[2] and x_start < x_end. */
CRIT_HD bool FitCorner(const double x[3], const double y[3], double x_start, double x_end,
                       Parabola* out) {
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(x[i]) || !std::isfinite(y[i])) return false;
  }
  if (!(x[0] < x[1] && x[1] < x[2]) || !std::isfinite(x_start) || !std::isfinite(x_end) ||
      !(x_end - x_start > kLaneFitPivotTolerance * (x[2] - x[0])))
    return false;
  const double m1 = (y[1] - y[0]) / (x[1] - x[0]);
  const double m2 = (y[2] - y[1]) / (x[2] - x[1]);
  const double a = (m2 - m1) / (2.0 * (x_end - x_start));
  const double b = m1 - 2.0 * a * x_start;
  out->a = a;
  out->b = b;
  out->c = y[0] + m1 * (x_start - x[0]) - (a * x_start + b) * x_start;
  out->x_start = x_start;
  out->x_end = x_end;
  return true;
}

}  // namespace criticality::core
