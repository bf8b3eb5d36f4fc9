#pragma once
// Collision recognition's primitive (paper Sec. IV-C): objects are rectangles; two of them
// overlap unless one of the four edge normals separates them (separating axis theorem, exact
// for convex polygons). Unlike the paper's vertex-in-polygon test it also finds crossing
// rectangles with no corner inside the other. Touching counts as overlapping.
#include <cmath>

#include "core/hd.h"

namespace criticality::core {

template <typename T>
struct OrientedBox {
  T cx;  ///< centre
  T cy;
  T c;   ///< cos(yaw)
  T s;   ///< sin(yaw)
  T hl;  ///< half length (along yaw)
  T hw;  ///< half width
};

template <typename T>
CRIT_HD OrientedBox<T> MakeBox(T x, T y, T yaw, T half_length, T half_width) {
  return OrientedBox<T>{x, y, std::cos(yaw), std::sin(yaw), half_length, half_width};
}

template <typename T>
CRIT_HD bool BoxesOverlap(const OrientedBox<T>& a, const OrientedBox<T>& b) {
  const T dx = b.cx - a.cx, dy = b.cy - a.cy;
  const T cd = std::fabs(a.c * b.c + a.s * b.s);  // |cos(yaw_b - yaw_a)|
  const T sd = std::fabs(a.s * b.c - a.c * b.s);  // |sin(yaw_b - yaw_a)|
  if (std::fabs(dx * a.c + dy * a.s) > a.hl + b.hl * cd + b.hw * sd) return false;
  if (std::fabs(-dx * a.s + dy * a.c) > a.hw + b.hl * sd + b.hw * cd) return false;
  if (std::fabs(dx * b.c + dy * b.s) > b.hl + a.hl * cd + a.hw * sd) return false;
  if (std::fabs(-dx * b.s + dy * b.c) > b.hw + a.hl * sd + a.hw * cd) return false;
  return true;
}

/** Radius of the circle around a box's centre that contains it. */
template <typename T>
CRIT_HD T BoundingRadius(T half_length, T half_width) {
  return std::sqrt(half_length * half_length + half_width * half_width);
}

}  // namespace criticality::core
