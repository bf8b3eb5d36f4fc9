#pragma once
// Everything needed to simulate any hypothesis of one object, as plain data with fixed-size
// arrays (so that it copies to a GPU as is). A hypothesis = (profile, path); its index among
// the object's trajectories is profile * n_paths + path (paper Sec. IV-B-4).
#include "core/geometry.h"
#include "core/hd.h"
#include "core/lane_fit.h"
#include "core/vehicle_params.h"

namespace criticality::core {

constexpr int kMaxSampleInstants = 4;
constexpr int kMaxLateralSamples = 16;
constexpr int kMaxProfiles = 32;
/** criticality::kMaxWayPoints (scene.h), the points of a body's way. */
constexpr int kMaxWayPointsCore = 48;

enum class MotionModelKind : int {
  kTwoTrack = 0,    ///< the ego
  kOneTrack = 1,    ///< other vehicles
  kPedestrian = 2,  ///< kinematic, no lanes
};

struct HypothesisSet {
  MotionModelKind model{MotionModelKind::kOneTrack};
  /** The object's local frame (its current pose) in the scene frame; simulation runs in the
   *  local frame, where its lanes are given, and poses are stored in the scene frame. */
  Pose2 X_WL;
  double v0{0.0};
  double beta0{0.0};
  double yaw_rate0{0.0};
  double accel0{0.0};
  VehicleParams vehicle;
  double seam_speed{2.0};  ///< below: kinematic single-track model
  double half_length{2.25};
  double half_width{0.9};

  // Longitudinal: profile k targets profile_target[k] (acceleration; for the two-track model a
  // longitudinal slip, or with force_profiles a tyre force demand a / (mu g)), starting from
  // profile_start, after `latency`, at `rate` per second.
  int n_profiles{0};
  double profile_target[kMaxProfiles]{};
  double profile_start{0.0};
  double latency{0.0};
  double rate{0.0};
  /** Two-track model: profiles are force demands a / (mu g) on the four wheels (ramped in
   *  acceleration) instead of slips (Params::ego_profiles_in_accel). */
  bool force_profiles{false};
  /** Positive acceleration limited to min(drive_traction, P / (m v)) (Params::
   *  power_limited_drive; P / m = vehicle.power_per_mass_wpkg). */
  bool power_limited{false};
  double drive_traction{0.0};  ///< m/s^2
  /** Vehicles: positive accelerations stop at this speed (its type's top speed, Params::
   *  road_user_classes; a vehicle already faster keeps its speed unless it brakes). +inf: none
   *  (the paper's). */
  double top_speed{HUGE_VAL};

  /** Until this time the vehicle keeps following its reference path (the centre of its own
   *  lane, as a driver does without reacting to anything); its hypothesis' path takes over
   *  after it (Params::steer_latency_s). */
  double steer_latency{0.0};
  Parabola reference_path;
  /** The lateral controller adds the curvature of the path it tracks (feed-forward,
   *  Params::steer_curvature_feedforward): set for a vehicle already turning along its lane. */
  bool steer_feedforward{false};
  /** Bound to its track (a rail vehicle, Params::road_user_classes): no steering and no
   *  motion model across its way; its centre moves along reference_path, at track_offset from
   *  it (the signed normal offset it starts at, positive to the path's left), by the distance
   *  its speed covers, heading along the path. track_x0: where it starts, in the path's frame. */
  bool on_track{false};
  double track_x0{0.0};
  double track_offset{0.0};
  /** Bound to its way (Vehicle::way, Params::bodies_on_way): the middle of its front moves
   *  along the polyline way_x/way_y (local frame, way_s its arc lengths) from track_x0 by the
   *  distance its speed covers, the middle of its back way_body behind it on the way; its box
   *  points from back to front with its centre half its length behind the front, then moved
   *  by (way_dx, way_dy, way_dyaw) in that pose's frame (what puts it on its measured pose at
   *  the start). Beyond either end the way goes straight on. No steering, no sideslip. */
  bool on_way{false};
  int n_way{0};
  double way_x[kMaxWayPointsCore]{};
  double way_y[kMaxWayPointsCore]{};
  double way_s[kMaxWayPointsCore]{};
  double way_body{0.0};
  double way_dx{0.0}, way_dy{0.0}, way_dyaw{0.0};
  /** Lateral paths along the way (Params::way_lateral_paths; all zero: one path on the way):
   *  the sideways offset (positive to the left) from where it started beside its way that
   *  path section l asks at sample instant k, the section's offset from the reference path
   *  there. Reached from the lateral latency on (WayLateralTarget), sideways at most
   *  kWayCrabSlope per metre driven. */
  double way_lateral[kMaxSampleInstants][kMaxLateralSamples]{};
  /** The vehicle leaves the scene once its centre has travelled this far along its way
   *  (Params::route_end_leaves): its poses from then on lie far from everything (kGoneX), so
   *  they collide with nothing. +inf: it stays. */
  double leave_distance{HUGE_VAL};
  /** Half the step of a simulator's Euler position update (Scene::euler_update_step_s / 2), 0
   *  for continuous motion: each pose is moved by (v - v0) * position_lead along the way the
   *  object drives, which puts it where that update puts the object (ShiftAlongCourse and
   *  ShiftAlongPath in trajectory_generation.h). Per set, so that a batch may mix scenes. */
  double position_lead{0.0};
  /** The world looks for collisions only every this many steps (its own step; 0 or 1: every
   *  step): the poses in between repeat the pose of the last step it looks at, the pose now
   *  until its first (Params::collisions_at_world_steps). */
  int pose_hold_steps{0};
  /** With held poses: a body whose speed is 0 at a step the world looks at keeps the pose of
   *  the world's previous step (Params::euler_stops; HoldPose). */
  bool hold_stops{false};
  /** Its box is centred on the chord of its path (Scene::bodies_on_path): each stored pose's
   *  centre lies PathSagitta(h, course curvature) toward the turn's centre from the model's,
   *  its heading the model's, and the model's centre starts that far outside the measured one
   *  (InitialSimulationState). */
  bool body_on_path{false};

  // Lateral: section[k][l] is the path section through lateral sample l (right to left) that
  // is tracked until instant_time[k].
  int n_instants{0};
  double instant_time[kMaxSampleInstants]{};
  int n_lateral{0};
  Parabola section[kMaxSampleInstants][kMaxLateralSamples]{};
  /** Ego: every combination of sections (n_lateral^n_instants paths, instant 0 the most
   *  significant digit, so paths that share their first sections are adjacent). Others: path l
   *  keeps sample l at every instant (n_lateral paths). */
  bool combine_sections{false};
  int n_paths{0};

  // Pedestrians: the path index selects heading[path] (scene frame); speed limit.
  double heading[kMaxLateralSamples]{};
  double max_speed{0.0};

  CRIT_HD int Trajectories() const { return n_profiles * n_paths; }
};

/** The course curvature a body on its path is bent by (HypothesisSet::body_on_path): the yaw
 *  rate over the speed above 1 m/s; below, the yaw rate times the speed, down to 0 at a stand
 *  (there a yaw rate tells no path: a standing vehicle's measured yaw rate would otherwise put
 *  its model's centre a sagitta off, and its prediction, whose yaw rate the models take to 0,
 *  would not come back). */
CRIT_HD double BodyCurvature(double yaw_rate, double v) {
  return v > 1.0 ? yaw_rate / v : yaw_rate * v;
}

/** How far the centre of the chord of a body's path lies toward the turn's centre from the
 *  path (signed: positive to the left, as the curvature): kappa c^2 / 8 for a box of length c,
 *  the curvature limited to 2 / c (a turn of radius c / 2, the sagitta then c / 4). */
CRIT_HD double PathSagitta(const HypothesisSet& h, double kappa) {
  const double c = 2.0 * h.half_length, limit = 2.0 / c;
  const double k = kappa < -limit ? -limit : (kappa > limit ? limit : kappa);
  return k * (0.125 * c * c);
}

/** The largest positive acceleration the drive gives at speed v (power_limited). */
CRIT_HD double DriveAccelLimit(const HypothesisSet& h, double v) {
  const double power = h.vehicle.power_per_mass_wpkg / (v > 0.1 ? v : 0.1);
  return power < h.drive_traction ? power : h.drive_traction;
}

/** Lateral sample index that `path` uses at sample instant `instant`. */
CRIT_HD int SectionOfPath(const HypothesisSet& h, int path, int instant) {
  if (!h.combine_sections) return path;
  int divisor = 1;
  for (int k = instant + 1; k < h.n_instants; ++k) divisor *= h.n_lateral;
  return (path / divisor) % h.n_lateral;
}

}  // namespace criticality::core
