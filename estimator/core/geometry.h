#pragma once
// Planar poses and frame changes. Notation (Drake): X_WL is frame L's pose in frame W;
// p_W is a point expressed in W.
#include <cmath>

#include "core/hd.h"

namespace criticality::core {

constexpr double kPi = 3.14159265358979323846;

/** A planar pose: position and heading (counter-clockwise from +x). */
struct Pose2 {
  double x{0.0};
  double y{0.0};
  double yaw{0.0};
};

/** Wraps an angle into [-pi, pi). */
CRIT_HD double WrapAngle(double a) {
  if (a >= -kPi && a < kPi) return a;  // the common case, exact
  a = std::fmod(a + kPi, 2.0 * kPi);
  if (a < 0.0) a += 2.0 * kPi;
  return a - kPi;
}

/** p_W = X_WL * p_L. */
CRIT_HD void LocalToWorld(const Pose2& X_WL, double xl, double yl, double* xw, double* yw) {
  const double c = std::cos(X_WL.yaw), s = std::sin(X_WL.yaw);
  *xw = X_WL.x + c * xl - s * yl;
  *yw = X_WL.y + s * xl + c * yl;
}

/** p_L = X_WL^-1 * p_W. */
CRIT_HD void WorldToLocal(const Pose2& X_WL, double xw, double yw, double* xl, double* yl) {
  const double c = std::cos(X_WL.yaw), s = std::sin(X_WL.yaw);
  const double dx = xw - X_WL.x, dy = yw - X_WL.y;
  *xl = c * dx + s * dy;
  *yl = -s * dx + c * dy;
}

}  // namespace criticality::core
