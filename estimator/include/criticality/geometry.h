#pragma once
/** @file Planar geometry for callers that build scenes or judge their outcome (the SUMO
 *  driver): poses, angle wrapping, frame changes and the estimator's rectangle overlap test.
 *  These are the very functions the estimator uses inside (core/geometry.h,
 *  core/oriented_box.h), so a caller gets its results bit for bit without including the
 *  estimator's internals. Notation (Drake): X_WL is frame L's pose in frame W. */

namespace criticality {

constexpr double kPi = 3.14159265358979323846;

/** A planar pose: position and heading (math yaw: counter-clockwise from +x, radians). */
struct Pose2 {
  double x{0.0};
  double y{0.0};
  double yaw{0.0};
};

/** `a` wrapped into [-pi, pi) (pi itself becomes -pi). */
double WrapAngle(double a);

/** The world point (xw, yw) in frame L, whose pose in the world is X_WL: p_L = X_WL^-1 p_W. */
void WorldToLocal(const Pose2& X_WL, double xw, double yw, double* xl, double* yl);

/** The point (xl, yl) of frame L in the world: p_W = X_WL p_L. */
void LocalToWorld(const Pose2& X_WL, double xl, double yl, double* xw, double* yw);

/** Whether two rectangles, each centred on its pose with half extents along (length) and across
 *  (width) its yaw, overlap: the separating axis test of collision recognition (paper
 *  Sec. IV-C), exact, also for crossing rectangles with no corner inside the other. Touching
 *  counts as overlapping. */
bool RectanglesOverlap(const Pose2& a, double half_length_a, double half_width_a, const Pose2& b,
                       double half_length_b, double half_width_b);

}  // namespace criticality
