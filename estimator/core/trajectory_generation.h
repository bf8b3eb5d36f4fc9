#pragma once
// Trajectory generation (paper Sec. IV-B): simulates one hypothesis (profile, path) of one
// object for n_steps steps of tau and writes its poses (scene frame) at steps 1..n_steps.
// The same function runs on the CPU and, compiled by nvcc, on the GPU.
#include <cmath>
#include <cstddef>

#include "core/euler_integration.h"
#include "core/geometry.h"
#include "core/hd.h"
#include "core/hypothesis_set.h"
#include "core/kinematic_single_track.h"
#include "core/lateral_controller.h"
#include "core/one_track.h"
#include "core/pedestrian_model.h"
#include "core/profiles.h"
#include "core/two_track.h"

namespace criticality::core {

struct SimulationConfig {
  double tau{0.02};
  int n_steps{100};
  ControllerLimits controller;
};

/** Where a simulator that moves each object over a step dt by its speed at the end of the step
 *  (x += v_new dt) puts it, given where continuous motion puts it: over steps 1..k the two
 *  differ by sum (v_n - v_{n-1}) dt / 2 = (v_k - v_0) dt / 2, along the course. A braking
 *  object is behind its continuous pose, an accelerating one ahead. (cx, cy): unit course. */
CRIT_HD void ShiftAlongCourse(double lead_s, double v, double v0, double cx, double cy, double* x,
                              double* y) {
  const double d = (v - v0) * lead_s;
  *x += cx * d;
  *y += cy * d;
}

/** The largest turn of the course over the shift of ShiftAlongPath (rad). */
constexpr double kMaxShiftTurnRad = 1.5707963267948966;

/** ShiftAlongCourse for a vehicle whose way curves (curvature kappa, signed: positive to the
 *  left, BodyCurvature of its yaw rate and speed): the simulator's pose lies on the way it
 *  drives, (v - v0) lead along it from the continuous pose, which on an arc of curvature kappa
 *  is sin(phi) / kappa along the course and (1 - cos(phi)) / kappa = 2 sin^2(phi / 2) / kappa
 *  to the side of it, phi = kappa (v - v0) lead (at most kMaxShiftTurnRad). Shifted along the
 *  course alone, a car braking through a right turn at 1 s steps was put out to the left of
 *  its way, into the opposite lane (bench/RESULTS.md, 2026-12-04, "the Euler update in a
 *  turn"). kappa = 0: ShiftAlongCourse exactly. */
CRIT_HD void ShiftAlongPath(double lead_s, double v, double v0, double kappa, double cx, double cy,
                            double* x, double* y) {
  const double d = (v - v0) * lead_s;
  const double phi = Clamp(kappa * d, -kMaxShiftTurnRad, kMaxShiftTurnRad);
  if (phi == 0.0) {
    *x += cx * d;
    *y += cy * d;
    return;
  }
  // sin(phi) = 2 sin(phi / 2) cos(phi / 2): one angle's sine and cosine for both.
  const double half = 0.5 * phi, r = d / phi;
  const double sh = std::sin(half), ch = std::cos(half);
  const double along = 2.0 * sh * ch * r, across = 2.0 * sh * sh * r;
  *x += cx * along - cy * across;
  *y += cy * along + cx * across;
}

/** Initial steering angle consistent with the current yaw rate (kinematic estimate). */
CRIT_HD double InitialSteer(const HypothesisSet& h, const ControllerLimits& c) {
  if (h.v0 < 0.1) return 0.0;
  const double wheelbase = h.vehicle.lf_m + h.vehicle.lr_m;
  return Clamp(std::atan(wheelbase * h.yaw_rate0 / h.v0), -c.max_steer_rad, c.max_steer_rad);
}

/** What a vehicle simulation did at each step, for reports and tests (escape routes record the
 *  manoeuvre, tests check the friction circle): after step n (time (n+1) tau), the state in
 *  the object's local frame and the steering angle commanded for that step. Arrays of n_steps;
 *  null = not recorded. */
struct StepTrace {
  MotionState* state{nullptr};
  double* steer{nullptr};
};

/** Where a vehicle simulation stands between steps; lets ego paths that share their first
 *  path sections share the simulation of that prefix (the state after it is the same). */
struct SimulationState {
  MotionState s;      ///< in the object's local frame
  double steer{0.0};  ///< last commanded steering angle
  int instant{0};     ///< current sample instant (path section)
  /** Controller off (ControllerLimits::feedback false): the held open-loop steering angle and
   *  the section it was set for (-1: before the lateral latency; -2: none yet). */
  double held_steer{0.0};
  int held_section{-2};
  double travelled{0.0};  ///< distance its centre has covered (for HypothesisSet::leave_distance)
  double track_x{0.0};    ///< on a track: where it is along reference_path (the path's frame)
  /** On a way (HypothesisSet::on_way): how far it has moved sideways from its start beside
   *  the way (positive to the left), and the angle its last step's sideways move turned it
   *  from the way's heading. */
  double way_lat{0.0}, way_crab{0.0};
  /** HypothesisSet::pose_hold_steps: the pose (scene frame) the poses in between repeat, and
   *  (for the CPU's SIMD path, which stores them) its heading's cos and sin. */
  double held_x{0.0}, held_y{0.0}, held_yaw{0.0}, held_c{1.0}, held_s{0.0};
  /** The centre (scene frame) where the last step left it, whether or not the pose stored for
   *  that step is a held one: where a reach bound from this state must start (the CPU's
   *  out-of-reach test of a tree node). */
  double pose_x{0.0}, pose_y{0.0};
};

/** Where the poses of a vehicle that has left the scene go (HypothesisSet::leave_distance):
 *  the ego's and the others' on opposite sides, a million kilometres from any scene, so that a
 *  pose that has left overlaps nothing, not even another that has left. */
constexpr double kGoneX = 1e9;
CRIT_HD double GoneX(const HypothesisSet& h) {
  return h.model == MotionModelKind::kTwoTrack ? kGoneX : -kGoneX;
}

CRIT_HD SimulationState InitialSimulationState(const HypothesisSet& h,
                                               const SimulationConfig& cfg) {
  SimulationState st;
  st.s.v = h.v0;
  st.s.beta = h.beta0;
  st.s.yaw_rate = h.yaw_rate0;
  st.s.ax = h.accel0;
  st.s.ay = h.v0 * h.yaw_rate0;
  st.steer = InitialSteer(h, cfg.controller);
  st.track_x = h.track_x0;
  st.held_x = st.pose_x = h.X_WL.x;
  st.held_y = st.pose_y = h.X_WL.y;
  st.held_yaw = h.X_WL.yaw;
  if (h.pose_hold_steps > 1) {
    st.held_c = std::cos(h.X_WL.yaw);
    st.held_s = std::sin(h.X_WL.yaw);
  }
  if (h.body_on_path && !h.on_track && !h.on_way) {  // the measured box is the chord
    const double e = PathSagitta(h, BodyCurvature(h.yaw_rate0, h.v0));
    st.s.x = e * std::sin(h.beta0);
    st.s.y = -e * std::cos(h.beta0);
  }
  return st;
}

/** The rest of a step along a track or a way, its position set: it heads `yaw` (its yaw rate
 *  the change over the step), without sideslip, and its speed changes by v_dot. */
CRIT_HD void TurnAlongPath(double yaw, double v_dot, double tau, MotionState* s) {
  s->yaw_rate = (yaw - s->yaw) / tau;
  s->yaw = yaw;
  s->beta = 0.0;
  s->v = s->v + v_dot * tau;
  s->ax = v_dot;
  s->ay = s->v * s->yaw_rate;
}

/** One step of a vehicle bound to its track (HypothesisSet::on_track): its speed changes by
 *  v_dot, its centre moves along the track by the distance that Euler step covers (v tau +
 *  a_x tau^2 / 2, as EulerStep moves every other model), at the track's direction, keeping its
 *  normal offset from the track; no sideslip. */
CRIT_HD void TrackStep(const HypothesisSet& h, double v_dot, double tau, SimulationState* st) {
  MotionState& s = st->s;
  const Parabola& track = h.reference_path;
  const double ds = s.v * tau + 0.5 * s.ax * tau * tau;
  double m = track.Slope(st->track_x);
  m = track.Slope(st->track_x + 0.5 * ds / std::sqrt(1.0 + m * m));  // midpoint slope
  st->track_x += ds / std::sqrt(1.0 + m * m);
  m = track.Slope(st->track_x);
  const double q = std::sqrt(1.0 + m * m);
  const double xr = st->track_x - h.track_offset * m / q;
  const double yr = track.Eval(st->track_x) + h.track_offset / q;
  const double yaw = std::atan(m) + track.rot;
  s.x = track.cos_rot * xr - track.sin_rot * yr;
  s.y = track.sin_rot * xr + track.cos_rot * yr;
  TurnAlongPath(yaw, v_dot, tau, &s);
}

/** The point at arc length `at` along a body's way (HypothesisSet::on_way), straight on
 *  along its first or last piece beyond either end; (*dx, *dy) that piece's unit direction. */
CRIT_HD void PointOnWay(const HypothesisSet& h, double at, double* x, double* y, double* dx,
                        double* dy) {
  const int last = (h.n_way < kMaxWayPointsCore ? h.n_way : kMaxWayPointsCore) - 1;
  int lo = 0, hi = last;  // the piece [k, k + 1] holding `at`: way_s[lo] <= at < way_s[hi]
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    if (h.way_s[mid] <= at) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  const double len = h.way_s[hi] - h.way_s[lo];
  *dx = (h.way_x[hi] - h.way_x[lo]) / len;
  *dy = (h.way_y[hi] - h.way_y[lo]) / len;
  const double u = at - h.way_s[lo];
  *x = h.way_x[lo] + *dx * u;
  *y = h.way_y[lo] + *dy * u;
}

/** The pose (local frame) of a body whose front is at arc length `front` on its way, as the
 *  simulation places it: front and back on the way, heading from back to front, centre half
 *  its length behind the front; `moved`: then moved by (way_dx, way_dy + lat, way_dyaw). */
CRIT_HD void WayPose(const HypothesisSet& h, double front, bool moved, double lat, double* x,
                     double* y, double* yaw) {
  double fx, fy, bx, by, dx, dy;
  PointOnWay(h, front, &fx, &fy, &dx, &dy);
  PointOnWay(h, front - h.way_body, &bx, &by, &dx, &dy);
  double ux = fx - bx, uy = fy - by;
  const double chord = std::sqrt(ux * ux + uy * uy);
  if (chord > 1e-9) {
    ux /= chord;
    uy /= chord;
  } else {  // a way that folds back on itself: the back's piece
    ux = dx;
    uy = dy;
  }
  const double cx = fx - h.half_length * ux, cy = fy - h.half_length * uy;
  *yaw = std::atan2(uy, ux);
  if (!moved) {
    *x = cx;
    *y = cy;
    return;
  }
  const double across = h.way_dy + lat;
  *x = cx + ux * h.way_dx - uy * across;
  *y = cy + uy * h.way_dx + ux * across;
  *yaw += h.way_dyaw;
}

/** The most a body on its way moves sideways per metre it drives (lateral paths along the
 *  way): tan 0.35 rad, the heading off its way beyond which a body is not on it (problem.cc,
 *  kWayMaxTurnRad), so that it never crabs farther off its way's heading than that. */
constexpr double kWayCrabSlope = 0.365;

/** The sideways offset path `path` asks of a body on its way at time t, `instant` the sample
 *  instant in force (InstantAt): none until the lateral latency; then, linearly in time, each
 *  sample instant's offset (way_lateral) by that instant, never one past the instant in force
 *  (so that a path tree's shared prefix asks the same of every path in its group); the last
 *  one's after it. */
CRIT_HD double WayLateralTarget(const HypothesisSet& h, int path, int instant, double t) {
  if (t < h.steer_latency) return 0.0;
  double t0 = h.steer_latency, o0 = 0.0;
  const int last = instant < kMaxSampleInstants - 1 ? instant : kMaxSampleInstants - 1;
  for (int k = 0; k <= last; ++k) {
    const double t1 = h.instant_time[k];
    const double o1 = h.way_lateral[k][SectionOfPath(h, path, k)];
    if (t < t1 || k == last) {
      return t1 > t0 ? o0 + (o1 - o0) * Min((t - t0) / (t1 - t0), 1.0) : o1;
    }
    if (t1 > t0) t0 = t1;
    o0 = o1;
  }
  return o0;
}

/** One step of a body bound to its way (HypothesisSet::on_way): its speed changes by v_dot,
 *  its front moves along the way by the distance that Euler step covers (as TrackStep), it
 *  moves sideways towards its path's offset (WayLateralTarget, at most kWayCrabSlope of that
 *  distance), and its pose follows (WayPose, turned by the sideways move's angle; the yaw
 *  unwrapped from the last step's). */
CRIT_HD void WayStep(const HypothesisSet& h, int path, double t, double v_dot, double tau,
                     SimulationState* st) {
  MotionState& s = st->s;
  const double ds = s.v * tau + 0.5 * s.ax * tau * tau;
  st->track_x += ds;
  const double reach = kWayCrabSlope * (ds > 0.0 ? ds : 0.0);
  const double side =
      Clamp(WayLateralTarget(h, path, st->instant, t + tau) - st->way_lat, -reach, reach);
  st->way_lat += side;
  st->way_crab = side != 0.0 ? std::atan2(side, ds) : 0.0;
  double yaw;
  WayPose(h, st->track_x, true, st->way_lat, &s.x, &s.y, &yaw);
  TurnAlongPath(s.yaw + WrapAngle(yaw + st->way_crab - s.yaw), v_dot, tau, &s);
}

/** What one vehicle simulation keeps from step to step besides its state: the frame change
 *  and, as the slip profile is constant once its ramp ends, its last tyre-curve value. */
struct StepContext {
  double c0{1.0}, s0{0.0};  ///< cos/sin of the local frame's yaw in the scene frame
  double mu_g{0.0};
  double cached_slip{0.0};
  double cached_factor{0.0};
};

CRIT_HD StepContext MakeStepContext(const HypothesisSet& h) {
  StepContext c;
  c.c0 = std::cos(h.X_WL.yaw);
  c.s0 = std::sin(h.X_WL.yaw);
  c.mu_g = h.vehicle.friction * kGravity;
  c.cached_slip = 0.0;
  c.cached_factor = LongitudinalForceFactor(0.0);
  return c;
}

/** The instant in force at time t, advanced from the current one (instants only move on). */
CRIT_HD int InstantAt(const HypothesisSet& h, int instant, double t) {
  int k = instant;  // explicit bounds keep the compiler's array-bounds check quiet
  while (k >= 0 && k < h.n_instants - 1 && k < kMaxSampleInstants - 1 && t >= h.instant_time[k])
    ++k;
  return k;
}

/** The tyre-curve value of a slip (two-track profiles), through the context's one-value memo. */
CRIT_HD double SlipFactor(StepContext* c, double slip) {
  if (slip != c->cached_slip) {
    c->cached_slip = slip;
    c->cached_factor = LongitudinalForceFactor(slip);
  }
  return c->cached_factor;
}

/** Where the pose after a step goes in the scene frame: far away once the vehicle has left,
 *  else its local pose (shifted along the step's course (cx, cy) for an Euler-updating
 *  simulator; for a body on its path, across it to the chord's centre) turned into the scene
 *  frame. */
CRIT_HD void StorePose(const HypothesisSet& h, const StepContext& c, const SimulationState& st,
                       double cx, double cy, double* x, double* y, double* yaw) {
  const MotionState& s = st.s;
  if (st.travelled > h.leave_distance) {  // it has left the scene
    *x = GoneX(h);
    *y = 0.0;
  } else {
    double px = s.x, py = s.y;
    if (h.on_way) {
      // Along the way itself: where the simulator's update puts the front.
      double yaw_lead = 0.0;
      if (h.position_lead > 0.0) {
        WayPose(h, st.track_x + (s.v - h.v0) * h.position_lead, true, st.way_lat, &px, &py,
                &yaw_lead);
        yaw_lead += st.way_crab;
      }
      *x = h.X_WL.x + c.c0 * px - c.s0 * py;
      *y = h.X_WL.y + c.s0 * px + c.c0 * py;
      *yaw = h.X_WL.yaw + (h.position_lead > 0.0 ? s.yaw + WrapAngle(yaw_lead - s.yaw) : s.yaw);
      return;
    }
    if (h.position_lead > 0.0) {
      ShiftAlongPath(h.position_lead, s.v, h.v0, BodyCurvature(s.yaw_rate, s.v), cx, cy, &px, &py);
    }
    if (h.body_on_path && !h.on_track && !h.on_way) {
      const double e = PathSagitta(h, BodyCurvature(s.yaw_rate, s.v));
      px -= cy * e;
      py += cx * e;
    }
    *x = h.X_WL.x + c.c0 * px - c.s0 * py;
    *y = h.X_WL.y + c.s0 * px + c.c0 * py;
  }
  *yaw = h.X_WL.yaw + s.yaw;
}

/** HypothesisSet::pose_hold_steps: after step n, the pose the world would see. At the steps
 *  it looks at, the pose just stored, kept in `held`, unless `stays` (HypothesisSet::
 *  hold_stops and a speed of 0 there: the world's update moves it by 0); in between, the last
 *  one kept. */
CRIT_HD void HoldPose(int hold_steps, int n, bool stays, double* held_x, double* held_y,
                      double* held_yaw, double* x, double* y, double* yaw) {
  if (hold_steps <= 1) return;
  if ((n + 1) % hold_steps == 0 && !stays) {
    *held_x = *x;
    *held_y = *y;
    *held_yaw = *yaw;
  } else {
    *x = *held_x;
    *y = *held_y;
    *yaw = *held_yaw;
  }
}

/** Advances a VEHICLE hypothesis (profile, path) by step n (time n tau to (n+1) tau) from
 *  `st` and writes the pose after it (scene frame) to *x, *y, *yaw. */
CRIT_HD void VehicleStep(const HypothesisSet& h, const SimulationConfig& cfg, int profile, int path,
                         int n, StepContext* ctx, SimulationState* st, double* x, double* y,
                         double* yaw) {
  const double tau = cfg.tau;
  const double target = h.profile_target[profile];
  const double mu_g = ctx->mu_g;
  MotionState& s = st->s;
  const double t = n * tau;
  st->instant = InstantAt(h, st->instant, t);
  // Trig of yaw and sideslip once per step; the course by the angle-sum identities.
  double cb = std::cos(s.beta), sb = std::sin(s.beta);
  const double cy = std::cos(s.yaw), sy = std::sin(s.yaw);
  if (h.on_track || h.on_way) {
    double a = RampedValue(t, h.profile_start, target, h.latency, h.rate);
    if (h.model == MotionModelKind::kTwoTrack)  // a force demand or a slip: in m/s^2
      a = mu_g * (h.force_profiles ? a : LongitudinalForceFactor(a));
    if (h.power_limited && a > 0.0) a = Min(a, DriveAccelLimit(h, s.v));
    if (h.vehicle.friction_limited) a = Clamp(a, -mu_g, mu_g);
    a = NonReversingAccel(s.v, TopSpeedAccel(s.v, a, tau, h.top_speed), tau);
    st->steer = 0.0;
    if (h.on_way) {
      WayStep(h, path, t, a, tau, st);
    } else {
      TrackStep(h, a, tau, st);
    }
  } else {
    // Lateral reaction latency: until then the vehicle follows its reference path; its
    // hypothesis' path section after it.
    const bool latent = t < h.steer_latency;
    const int lateral = SectionOfPath(h, path, st->instant);
    const Parabola& section = latent ? h.reference_path : h.section[st->instant][lateral];
    if (cfg.controller.feedback) {
      st->steer = SteeringCommand(cfg.controller, section, s, st->steer, tau, cy * cb - sy * sb,
                                  sy * cb + cy * sb,
                                  h.steer_feedforward ? h.vehicle.lf_m + h.vehicle.lr_m : 0.0);
    } else {  // the "controller off" ablation: one open-loop angle per section, held
      const int key = latent ? -1 : st->instant * kMaxLateralSamples + lateral;
      if (key != st->held_section) {
        st->held_section = key;
        st->held_steer =
            latent ? InitialSteer(h, cfg.controller)
                   : OpenLoopSteer(cfg.controller, section, s, h.vehicle.lf_m + h.vehicle.lr_m,
                                   Max(h.instant_time[st->instant] - t, 0.5));
      }
      const double rate = cfg.controller.max_steer_rate_radps * tau;
      st->steer = Clamp(st->held_steer, st->steer - rate, st->steer + rate);
    }
    double longitudinal = RampedValue(t, h.profile_start, target, h.latency, h.rate);
    const bool kinematic = s.v < h.seam_speed;
    StateDerivative d;
    if (h.model == MotionModelKind::kTwoTrack) {
      double factor = h.force_profiles ? longitudinal : SlipFactor(ctx, longitudinal);
      if (h.power_limited && factor > 0.0) factor = Min(factor, DriveAccelLimit(h, s.v) / mu_g);
      if (kinematic) {
        d = KinematicSingleTrack(h.vehicle, st->steer, mu_g * factor, &s);
      } else {
        d = TwoTrackDerivative(h.vehicle, s, st->steer, factor, cb, sb);
      }
    } else {
      if (h.power_limited && longitudinal > 0.0)
        longitudinal = Min(longitudinal, DriveAccelLimit(h, s.v));
      d = kinematic ? KinematicSingleTrack(h.vehicle, st->steer, longitudinal, &s)
                    : OneTrackDerivative(h.vehicle, s, st->steer, longitudinal);
    }
    if (kinematic) cb = std::cos(s.beta), sb = std::sin(s.beta);  // the kinematic model set beta
    d.v_dot = NonReversingAccel(s.v, TopSpeedAccel(s.v, d.v_dot, tau, h.top_speed), tau);
    EulerStep(d, tau, &s, cb, sb, cy, sy);
  }
  if (s.v < 0.0) s.v = 0.0;  // rounding guard
  st->travelled += s.v * tau;
  // The course of this step (cy, sy, cb, sb from its start).
  StorePose(h, *ctx, *st, cy * cb - sy * sb, sy * cb + cy * sb, x, y, yaw);
  st->pose_x = *x;
  st->pose_y = *y;
  HoldPose(h.pose_hold_steps, n, h.hold_stops && s.v == 0.0, &st->held_x, &st->held_y,
           &st->held_yaw, x, y, yaw);
}

/** Advances a VEHICLE hypothesis (profile, path) over steps [n_begin, n_end) from `st`,
 *  writing the poses (scene frame) of those steps to x[n * stride], y[..], yaw[..]. For a
 *  shared prefix, any path of the group gives the same sections (SectionOfPath) up to the
 *  group's instant. The stride lets the GPU store poses step-major. */
CRIT_HD void SimulateVehicleSteps(const HypothesisSet& h, const SimulationConfig& cfg, int profile,
                                  int path, int n_begin, int n_end, SimulationState* st, double* x,
                                  double* y, double* yaw, int stride = 1,
                                  StepTrace* trace = nullptr) {
  StepContext ctx = MakeStepContext(h);
  for (int n = n_begin; n < n_end; ++n) {
    const size_t at = static_cast<size_t>(n) * stride;
    VehicleStep(h, cfg, profile, path, n, &ctx, st, &x[at], &y[at], &yaw[at]);
    if (trace) {
      trace->state[n] = st->s;
      trace->steer[n] = st->steer;
    }
  }
}

/** First step of each sample instant's span: the instant in force at step n is the k with
 *  boundary[k] <= n < boundary[k+1] (boundary[0] = 0, boundary[n_instants] = n_steps). */
CRIT_HD void InstantBoundaries(const HypothesisSet& h, const SimulationConfig& cfg, int* boundary) {
  int instant = 0;
  boundary[0] = 0;
  for (int n = 0; n < cfg.n_steps; ++n) {
    const double t = n * cfg.tau;
    while (instant < h.n_instants - 1 && t >= h.instant_time[instant]) boundary[++instant] = n;
  }
  for (int k = instant + 1; k <= h.n_instants; ++k) boundary[k] = cfg.n_steps;
}

/** Simulates hypothesis (profile, path) of `h`; writes n_steps poses to x[n * stride], ... */
CRIT_HD void SimulateHypothesis(const HypothesisSet& h, const SimulationConfig& cfg, int profile,
                                int path, double* x, double* y, double* yaw, int stride = 1,
                                StepTrace* trace = nullptr) {
  if (h.model == MotionModelKind::kPedestrian) {
    // (path < n_lateral <= kMaxLateralSamples; the bound keeps the array-bounds check quiet)
    const double heading = h.heading[path < kMaxLateralSamples ? path : kMaxLateralSamples - 1];
    const double target = h.profile_target[profile];
    const double v0 = Clamp(h.v0, 0.0, h.max_speed);
    const double ch = std::cos(heading), sh = std::sin(heading);
    double px = h.X_WL.x, py = h.X_WL.y, v = v0;
    double held_x = h.X_WL.x, held_y = h.X_WL.y, held_yaw = h.X_WL.yaw;
    for (int n = 0; n < cfg.n_steps; ++n) {
      PedestrianStep(heading, target, h.max_speed, cfg.tau, &px, &py, &v);
      const size_t at = static_cast<size_t>(n) * stride;
      double sx = px, sy = py, syaw = heading;
      if (h.position_lead > 0.0) ShiftAlongCourse(h.position_lead, v, v0, ch, sh, &sx, &sy);
      HoldPose(h.pose_hold_steps, n, h.hold_stops && v == 0.0, &held_x, &held_y, &held_yaw, &sx,
               &sy, &syaw);
      x[at] = sx;
      y[at] = sy;
      yaw[at] = syaw;
    }
    return;
  }
  SimulationState st = InitialSimulationState(h, cfg);
  SimulateVehicleSteps(h, cfg, profile, path, 0, cfg.n_steps, &st, x, y, yaw, stride, trace);
}

}  // namespace criticality::core
