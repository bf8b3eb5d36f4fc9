#pragma once
// The lateral controller of the paper (Sec. IV-B-2b): two P-controllers on a predicted error,
// with dynamically weighted distance and yaw errors:
//   delta_f = (|(-0.018 v + 1.5) d| + 0.5) d + (-|(-0.018 v + 1.5) d| + 9.5) (3.8197 e_psi)
// d = signed distance from the predicted centre of gravity to the path section (positive when
// the section lies to the vehicle's left), e_psi = section direction - psi.
//
// Units: the paper gives none. We read delta_f in DEGREES at the front wheels (d in m, e_psi in
// rad): then a 3.5 m lane change reaches 90 % in about 1.1-1.2 s at 20-40 m/s with at most a
// few percent overshoot (tests/estimator/core/lateral_controller_test.cc). Read as radians at
// the wheels or at the steering wheel (ratio ~16) the gains are 57x or 3.6x larger and the
// loop oscillates against the steering-rate limit. The prediction time grows with speed
// (paper: "dynamically adjusting the prediction time ... according to v_V"):
// t_p = clamp(preview_s_per_mps * v, preview_min_s, preview_max_s); steering angle and rate
// are limited.
#include <cmath>

#include "core/geometry.h"
#include "core/hd.h"
#include "core/lane_fit.h"
#include "core/min_max.h"
#include "core/state.h"

namespace criticality::core {

struct ControllerLimits {
  double max_steer_rad{0.5};
  double max_steer_rate_radps{0.9};
  double preview_s_per_mps{0.008};
  double preview_min_s{0.05};
  double preview_max_s{0.4};
  /** false: the paper's "controller off" ablation (Params::lateral_controller): open-loop
   *  steering set once per path section, see OpenLoopSteer. */
  bool feedback{true};
};

/** The paper's steering law; returns degrees at the front wheels. */
CRIT_HD double PaperSteeringLawDeg(double v, double d_path, double e_psi) {
  const double g = std::fabs((-0.018 * v + 1.5) * d_path);
  return (g + 0.5) * d_path + (-g + 9.5) * (3.8197 * e_psi);
}

/** Prediction time for the controller's predicted position. */
CRIT_HD double PreviewTime(const ControllerLimits& c, double v) {
  return Clamp(c.preview_s_per_mps * v, c.preview_min_s, c.preview_max_s);
}

/** Steering angle at the front wheels for the next step: the paper's law on the predicted
 *  errors against `section` (in the same local frame as `s`; the errors are taken in the
 *  section's own frame when it is rotated), then the angle and rate limits.
 *  @param previous_steer the angle commanded at the previous step.
 *  @param cos_course, sin_course direction of travel, yaw + sideslip.
 *  @param wheelbase > 0: adds the section's curvature kappa at the predicted position as the
 *  steady-state angle atan(wheelbase * kappa) (feed-forward; 0: the paper's law alone). */
CRIT_HD double SteeringCommand(const ControllerLimits& c, const Parabola& section,
                               const MotionState& s, double previous_steer, double tau,
                               double cos_course, double sin_course, double wheelbase = 0.0) {
  const double tp = PreviewTime(c, s.v);
  double xp = s.x + cos_course * s.v * tp;
  double yp = s.y + sin_course * s.v * tp;
  if (section.rot != 0.0) section.ToFrame(xp, yp, &xp, &yp);  // a turn's lane frame
  const double slope = section.Slope(xp);
  const double d_path = (section.Eval(xp) - yp) / std::sqrt(1.0 + slope * slope);
  const double e_psi = WrapAngle(std::atan(slope) + section.rot - s.yaw);
  double cmd = PaperSteeringLawDeg(s.v, d_path, e_psi) * (kPi / 180.0);
  if (wheelbase > 0.0) {  // feed-forward of the section's curvature (HypothesisSet)
    const double kappa = 2.0 * (section.Curved(xp) ? section.a : 0.0) /
                         ((1.0 + slope * slope) * std::sqrt(1.0 + slope * slope));
    cmd += std::atan(wheelbase * kappa);
  }
  cmd = Clamp(cmd, -c.max_steer_rad, c.max_steer_rad);
  const double step = c.max_steer_rate_radps * tau;
  return Clamp(cmd, previous_steer - step, previous_steer + step);
}

/** The same, computing the course (yaw + sideslip) direction itself. */
CRIT_HD double SteeringCommand(const ControllerLimits& c, const Parabola& section,
                               const MotionState& s, double previous_steer, double tau) {
  const double course = s.yaw + s.beta;
  return SteeringCommand(c, section, s, previous_steer, tau, std::cos(course), std::sin(course));
}

/** Open-loop steering for the "controller off" ablation: the constant steering angle of a pure
 *  pursuit arc from the vehicle (state `s`, local frame) to the point of `section` that lies
 *  max(v * lookahead_s, 2 m) ahead along the current heading; clamped to the angle limit. It
 *  is set once when a section starts and then held (no feedback on the path errors). */
CRIT_HD double OpenLoopSteer(const ControllerLimits& c, const Parabola& section, const MotionState& s,
                             double wheelbase, double lookahead_s) {
  const double ahead = Max(s.v * lookahead_s, 2.0);
  double xr, yr, px, py;
  section.ToFrame(s.x, s.y, &xr, &yr);
  section.PointAt(xr + ahead * std::cos(s.yaw - section.rot), &px, &py);
  const double dx = px - s.x, dy = py - s.y;
  const double alpha = WrapAngle(std::atan2(dy, dx) - s.yaw);
  const double kappa = 2.0 * std::sin(alpha) / std::sqrt(dx * dx + dy * dy);
  return Clamp(std::atan(wheelbase * kappa), -c.max_steer_rad, c.max_steer_rad);
}

}  // namespace criticality::core
