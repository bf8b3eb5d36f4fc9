#pragma once
// Trajectory generation (paper Sec. IV-B): simulates one hypothesis (profile, path) of one
// object for n_steps steps of tau and writes its poses (scene frame) at steps 1..n_steps.
// The same function runs on the CPU and, compiled by nvcc, on the GPU.
#include <cmath>

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

/** Initial steering angle consistent with the current yaw rate (kinematic estimate). */
CRIT_HD double InitialSteer(const HypothesisSet& h, const ControllerLimits& c) {
  if (h.v0 < 0.1) return 0.0;
  const double wheelbase = h.vehicle.lf_m + h.vehicle.lr_m;
  return Clamp(std::atan(wheelbase * h.yaw_rate0 / h.v0), -c.max_steer_rad, c.max_steer_rad);
}

/** Simulates hypothesis (profile, path) of `h`; writes n_steps poses to x[], y[], yaw[]. */
CRIT_HD void SimulateHypothesis(const HypothesisSet& h, const SimulationConfig& cfg, int profile,
                                int path, double* x, double* y, double* yaw) {
  const double tau = cfg.tau;
  const double target = h.profile_target[profile];
  if (h.model == MotionModelKind::kPedestrian) {
    const double heading = h.heading[path];
    double px = h.X_WL.x, py = h.X_WL.y, v = Clamp(h.v0, 0.0, h.max_speed);
    for (int n = 0; n < cfg.n_steps; ++n) {
      PedestrianStep(heading, target, h.max_speed, tau, &px, &py, &v);
      x[n] = px;
      y[n] = py;
      yaw[n] = heading;
    }
    return;
  }
  MotionState s;
  s.v = h.v0;
  s.beta = h.beta0;
  s.yaw_rate = h.yaw_rate0;
  s.ax = h.accel0;
  s.ay = h.v0 * h.yaw_rate0;
  double steer = InitialSteer(h, cfg.controller);
  int instant = 0;
  for (int n = 0; n < cfg.n_steps; ++n) {
    const double t = n * tau;
    while (instant < h.n_instants - 1 && t >= h.instant_time[instant]) ++instant;
    const Parabola& section = h.section[instant][SectionOfPath(h, path, instant)];
    steer = SteeringCommand(cfg.controller, section, s, steer, tau);
    const double longitudinal = RampedValue(t, h.profile_start, target, h.latency, h.rate);
    const bool kinematic = s.v < h.seam_speed;
    StateDerivative d;
    if (h.model == MotionModelKind::kTwoTrack) {
      d = kinematic ? KinematicSingleTrack(h.vehicle, steer, AccelFromSlip(h.vehicle, longitudinal), &s)
                    : TwoTrackDerivative(h.vehicle, s, steer, longitudinal);
    } else {
      d = kinematic ? KinematicSingleTrack(h.vehicle, steer, longitudinal, &s)
                    : OneTrackDerivative(h.vehicle, s, steer, longitudinal);
    }
    d.v_dot = NonReversingAccel(s.v, d.v_dot, tau);
    EulerStep(d, tau, &s);
    if (s.v < 0.0) s.v = 0.0;  // rounding guard
    LocalToWorld(h.X_WL, s.x, s.y, &x[n], &y[n]);
    yaw[n] = h.X_WL.yaw + s.yaw;
  }
}

}  // namespace criticality::core
