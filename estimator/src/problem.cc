#include "src/problem.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>

#include "core/geometry.h"
#include "core/one_track.h"
#include "core/pedestrian_model.h"
#include "core/profiles.h"
#include "core/scoring.h"
#include "core/trajectory_generation.h"
#include "core/two_track.h"
#include "criticality/errors.h"
#include "criticality/vehicle_class.h"
#include "src/street_data.h"
#include "src/validation.h"

namespace criticality::internal {
namespace {

struct LateralSample {
  core::Parabola curve;
  bool counter_traffic{false};
  int lane{0};  ///< -1 right, 0 own, +1 left
};

// Params::hold_line_max_width_share: the fraction across its own lane (0 at the right divider,
// 1 at the left) at which a narrow vehicle rides and holds its line, kept its half width inside
// the dividers; -1 where it is not that narrow (or the rule is off): it heads for the centre.
double HeldLineFraction(const FittedLanes& lanes, double half_width, const Params& p) {
  if (p.hold_line_max_width_share <= 0.0 || !lanes.own) return -1.0;
  const double right = lanes.own->right.OffsetFrom(0.0, 0.0);
  const double width = lanes.own->left.OffsetFrom(0.0, 0.0) - right;
  if (!(width > 0.0) || 2.0 * half_width > p.hold_line_max_width_share * width) return -1.0;
  const double margin = half_width / width;
  return core::Clamp(-right / width, margin, 1.0 - margin);
}

// Lateral samples right to left: neighbour_lane_samples across the right lane, own_lane_samples
// across the own lane, neighbour_lane_samples across the left lane, each equally distributed
// over its lane's width (fractions i / (n + 1)); the own lane's sample nearest to `held`
// (HeldLineFraction, when >= 0) moves there.
std::vector<LateralSample> LateralSamples(const FittedLanes& lanes, const Params& p,
                                          bool centre_only, double held) {
  std::vector<LateralSample> out;
  if (centre_only) {  // bound to its track: its own lane's centre
    out.push_back({lanes.own->Centre(), lanes.own->counter_traffic, 0});
    return out;
  }
  auto add = [&](const std::optional<FittedLane>& lane, int n, int index) {
    if (!lane) return;
    // The own-lane sample nearest to the held line (the lower one on a tie), 0 for none.
    const int moved = index == 0 && held >= 0.0
                          ? std::clamp(static_cast<int>(std::ceil(held * (n + 1) - 0.5)), 1, n)
                          : 0;
    for (int i = 1; i <= n; ++i) {
      const double f = i == moved ? held : static_cast<double>(i) / (n + 1);
      out.push_back({lane->At(f), lane->counter_traffic, index});
    }
  };
  add(lanes.right, p.neighbour_lane_samples, -1);
  add(lanes.own, p.own_lane_samples, 0);
  add(lanes.left, p.neighbour_lane_samples, 1);
  return out;
}

// Distance the reference trajectory (current acceleration, never reversing) covers by time t.
double ReferenceDistance(double v0, double a0, double t) {
  if (a0 < 0.0 && v0 + a0 * t < 0.0) return v0 * v0 / (2.0 * -a0);
  return v0 * t + 0.5 * a0 * t * t;
}

bool Naturalistic(const Params& p) { return p.scoring == Params::Scoring::kNaturalistic; }

// Naturalistic n_acc of an acceleration deviation: Gaussian, wider for braking.
double AccelScore(const Params& p, double deviation) {
  const double z =
      deviation / (deviation < 0.0 ? p.decel_score_sigma_mps2 : p.accel_score_sigma_mps2);
  return core::GaussianScore(z * z);
}

// The class limits of a vehicle's type (Params::road_user_classes); nullptr for a car (the
// paper's range, vehicle_class.h) and with the classes off.
const RoadUserLimits* ClassOf(const VehicleType& t, const Params& p) {
  return p.road_user_classes ? p.LimitsOf(t.road_user) : nullptr;
}

// Whether its class is simulated with the kinematic single-track model at every speed.
bool KinematicClass(const VehicleType& t, const Params& p) {
  const RoadUserLimits* c = ClassOf(t, p);
  return c && c->kinematic;
}

// Rail vehicles are bound to their track: one path, their own lane's centre, from t = 0.
bool TrackBound(const VehicleType& t, const Params& p) {
  return p.road_user_classes && t.road_user == RoadUser::kRail;
}

// The range of a vehicle's longitudinal hypotheses (Params::road_user_classes): braking down
// to its emergency deceleration (the VehicleType's; else the larger of its decel and its
// class's, SUMO's rule), positive profiles up to its acceleration (the VehicleType's, else its
// class's) and never above its top speed. A car (the paper's classes) keeps the paper's profile
// grid (vehicle_accel_min..max_mps2, positive profiles bounded by the power limit); its type's
// emergency deceleration only floors the hardest braking samples (`floor`) and its top speed
// bounds it: moving every sample with SUMO's default 9 m/s^2 instead of 9.7 shifted the whole
// grid and split a designed scenario's warning (cut_in). `typed`: the range comes from a class
// or a VehicleType value (a kCar without values keeps every step of the paper's range as
// before, bit for bit).
struct ProfileRange {
  double lo{-9.7};
  double hi{9.7};
  double floor{-9.7};  ///< no profile brakes harder (lo, or a car's type's emergency decel)
  double top_speed{HUGE_VAL};
  bool typed{false};
  double Clamp(double a) const { return core::Clamp(a, floor, hi); }
};

ProfileRange RangeOf(const VehicleType& t, const Params& p) {
  ProfileRange r;
  r.lo = p.vehicle_accel_min_mps2;
  r.hi = p.vehicle_accel_max_mps2;
  if (!p.road_user_classes) return r;
  const RoadUserLimits* c = p.LimitsOf(t.road_user);
  const double class_emergency = c ? c->emergency_decel_mps2 : -p.vehicle_accel_min_mps2;
  double emergency = class_emergency;
  if (t.emergency_decel_mps2) {
    emergency = *t.emergency_decel_mps2;
  } else if (t.decel_mps2) {
    emergency = std::fmax(*t.decel_mps2, class_emergency);
  }
  if (c) {
    r.lo = -emergency;
    r.hi = t.accel_mps2 ? *t.accel_mps2 : c->accel_mps2;
  }
  r.floor = c ? r.lo : std::fmax(r.lo, -emergency);
  if (t.max_speed_mps) {
    r.top_speed = *t.max_speed_mps;
  } else if (c) {
    r.top_speed = c->max_speed_mps;
  }
  r.typed = c || t.decel_mps2 || t.emergency_decel_mps2 || t.max_speed_mps;
  return r;
}

// The model parameters of a box of `type`: a car's from its dimensions (vehicle_class.h), its
// VehicleType's mass replacing the class's (yaw inertia and cornering stiffness scaled with
// it); another class's from its RoadUserLimits: mass (the VehicleType's when given), yaw
// inertia yaw_inertia_box_share of a uniform box's, wheelbase and cornering stiffness.
core::VehicleParams VehicleModelParams(double length, double width, std::optional<double> height,
                                       const VehicleType& type, const Params& p) {
  core::VehicleParams vp;
  if (const RoadUserLimits* c = ClassOf(type, p)) {
    const double m = type.mass_kg ? *type.mass_kg : c->mass_kg;
    vp.mass_kg = m;
    vp.yaw_inertia_kgm2 = p.yaw_inertia_box_share * m * (length * length + width * width) / 12.0;
    vp.power_per_mass_wpkg = c->power_per_mass_wpkg;
    const double wheelbase =
        std::clamp(c->wheelbase_share * length, c->wheelbase_min_m, c->wheelbase_max_m);
    vp.lf_m = 0.45 * wheelbase;
    vp.lr_m = 0.55 * wheelbase;
    vp.cf_npr = c->cornering_stiffness_per_kg * m;
    vp.cr_npr = c->cornering_stiffness_per_kg * m;
    vp.track_m = std::clamp(width - 0.25, 0.5, 2.5);
  } else {
    vp = VehicleParamsFor(ClassifyVehicle(length, width, height), length, width);
    if (p.road_user_classes && type.mass_kg) {
      const double k = *type.mass_kg / vp.mass_kg;
      vp.mass_kg = *type.mass_kg;
      vp.yaw_inertia_kgm2 *= k;
      vp.cf_npr *= k;
      vp.cr_npr *= k;
    }
  }
  vp.friction = p.friction;
  vp.kinematic_below_mps = p.kinematic_below_mps;
  vp.friction_limited = p.friction_limited_lateral;
  return vp;
}

// The speed below which a vehicle of `type` is simulated with the kinematic model: every speed
// for the kinematic classes (bicycles, rail), else SeamSpeed.
double SeamSpeedOf(const core::VehicleParams& vp, const VehicleType& type, const Params& p) {
  if (KinematicClass(type, p)) return HUGE_VAL;
  return core::SeamSpeed(vp, p.step_s, p.euler_stability_factor);
}

// Binds a vehicle (or the ego) to its track (a rail vehicle, after SetPaths gave it its one
// path): it moves along its reference path (its own lane's centre) at the normal offset it
// starts at, from the foot of its centre on the path (one Newton step from straight across).
void PutOnTrack(core::HypothesisSet* h) {
  const core::Parabola& c = h->reference_path;
  double xr, yr;
  c.ToFrame(0.0, 0.0, &xr, &yr);
  const double m = c.Slope(xr);
  const double foot = xr + (yr - c.Eval(xr)) * m / (1.0 + m * m);
  const double mf = c.Slope(foot);
  h->on_track = true;
  h->track_x0 = foot;
  h->track_offset = (-(xr - foot) * mf + (yr - c.Eval(foot))) / std::sqrt(1.0 + mf * mf);
}

// Binds a vehicle to its way (Params::bodies_on_way, after SetPose gave it its box) where the
// way puts it within kWayMaxShiftM and kWayMaxTurnRad of its measured pose (a way that does
// not pass it is not its way): its pose is then the way's, moved by that difference at every
// step. Returns whether it is bound; if not, the set is left as it was.
constexpr double kWayMaxShiftM = 1.0;
constexpr double kWayMaxTurnRad = 0.35;
static_assert(core::kMaxWayPointsCore == kMaxWayPoints, "the core holds every point of a way");
bool PutOnWay(const Way& way, core::HypothesisSet* h) {
  const int n = static_cast<int>(std::min<size_t>(way.points.size(), core::kMaxWayPointsCore));
  double at = 0.0;
  for (int k = 0; k < n; ++k) {
    if (k > 0) {
      at += std::hypot(way.points[k].x - way.points[k - 1].x,
                       way.points[k].y - way.points[k - 1].y);
    }
    h->way_x[k] = way.points[k].x;
    h->way_y[k] = way.points[k].y;
    h->way_s[k] = at;
  }
  h->n_way = n;
  h->way_body = way.front_m - way.back_m;
  double x, y, yaw;
  core::WayPose(*h, way.front_m, false, 0.0, &x, &y, &yaw);
  const double c = std::cos(yaw), s = std::sin(yaw);
  const double dx = -c * x - s * y, dy = s * x - c * y;
  if (std::hypot(dx, dy) > kWayMaxShiftM || std::fabs(yaw) > kWayMaxTurnRad) {
    std::fill(h->way_x, h->way_x + n, 0.0);
    std::fill(h->way_y, h->way_y + n, 0.0);
    std::fill(h->way_s, h->way_s + n, 0.0);
    h->n_way = 0;
    h->way_body = 0.0;
    return false;
  }
  h->on_way = true;
  h->track_x0 = way.front_m;
  h->way_dx = dx;
  h->way_dy = dy;
  h->way_dyaw = -yaw;
  return true;
}

// Pose and motion state; for vehicles after h->vehicle is set.
void SetPose(const ObjectState& s, double length, double width, core::HypothesisSet* h) {
  h->X_WL = core::Pose2{s.x_m, s.y_m, s.yaw_rad};
  h->v0 = s.speed_mps;
  h->beta0 = s.sideslip_rad;
  h->yaw_rate0 = s.yaw_rate_radps;
  // A vehicle's measured state must be drivable too: a yaw rate whose lateral acceleration v r
  // exceeds the friction limit is a measurement artefact (SUMO's headings jump on junction
  // lanes), limited to mu g / v.
  if (h->vehicle.friction_limited && h->v0 > 0.0) {
    const double limit = h->vehicle.friction * core::kGravity / h->v0;
    h->yaw_rate0 = core::Clamp(h->yaw_rate0, -limit, limit);
  }
  h->accel0 = s.accel_mps2;
  h->half_length = 0.5 * length;
  h->half_width = 0.5 * width;
}

// Params::route_end_leaves: a vehicle whose route ends ahead leaves the scene there.
void SetRouteEnd(const ObjectState& s, const Params& p, core::HypothesisSet* h) {
  if (p.route_end_leaves && s.route_end_m) h->leave_distance = *s.route_end_m;
}

// Params::curve_speed_reference: the constant acceleration that brings a vehicle at speed v,
// by each of 20 points of its lane centre within v x horizon, to the speed at which that
// point's curvature asks curve_lateral_accel_mps2; the lowest of them, at least
// -curve_decel_max_mps2; +inf where no point asks for less speed.
double CurveAccel(double v, const core::Parabola& centre, const Params& p) {
  if (!p.curve_speed_reference || !(v > 0.0)) return HUGE_VAL;
  double x0, y0;
  centre.ToFrame(0.0, 0.0, &x0, &y0);
  const double reach = v * p.horizon_s;
  const int n = 20;
  double a = HUGE_VAL;
  for (int i = 1; i <= n; ++i) {
    const double s = reach * i / n;
    const double k = centre.Curvature(core::XAfterArc(centre, x0, s));
    const double v_curve2 = k > 0.0 ? p.curve_lateral_accel_mps2 / k : HUGE_VAL;
    if (v_curve2 < v * v) a = std::fmin(a, (v_curve2 - v * v) / (2.0 * s));
  }
  return a == HUGE_VAL ? a : std::fmax(a, -p.curve_decel_max_mps2);
}

// The expected acceleration the caller gives, where Params::expected_accel_reference uses it;
// HUGE_VAL where there is none (so that fmin with it changes nothing).
double ExpectedAccelInForce(const ObjectState& s, const Params& p) {
  return p.expected_accel_reference && s.expected_accel_mps2 ? *s.expected_accel_mps2 : HUGE_VAL;
}

// The acceleration of the reference hypothesis: the current one, or lower where the caller
// gives a lower expected one (Params::expected_accel_reference) or the lane's curve asks for
// less speed (Params::curve_speed_reference); higher where the vehicle brakes harder than any
// reason to brake that the caller knows (Params::release_unexplained_braking).
double ReferenceAccel(const ObjectState& s, const core::Parabola& centre, const Params& p) {
  const double expected = ExpectedAccelInForce(s, p);
  const double curve = CurveAccel(s.speed_mps, centre, p);
  if (p.release_unexplained_braking && s.braking_causes_known) {
    const double asked = std::fmin(0.0, std::fmin(expected, curve));
    if (s.accel_mps2 < asked) return asked;
  }
  return std::fmin(s.accel_mps2, std::fmin(expected, curve));
}

// The path part of the scores: d_path (the lateral part of d_str) and c_com * c_cou.
struct PathScore {
  double d_path{1.0};
  double penalty{1.0};
};

// The profile part: n_acc, and d_lon, the longitudinal part of d_str (naturalistic scoring:
// how far the profile takes the object from the reference trajectory along its way).
struct ProfileScore {
  double n_acc{1.0};
  double d_lon{1.0};
};

// Params::steer_curvature_feedforward: whether a vehicle is already turning the way its lane
// turns at its position (yaw rate of the lane's sign and at least kFeedforwardMinYawRate). A
// parabola through three samples spreads a junction turn's curvature over the straight before
// it; a vehicle still driving straight at the turn gets no feed-forward, which would turn it
// in early across the lanes beside it.
constexpr double kFeedforwardMinYawRate = 0.1;  // rad/s
bool TurningAlongLane(const core::HypothesisSet& h, const core::Parabola& centre, const Params& p) {
  if (!p.steer_curvature_feedforward || !p.lateral_controller) return false;
  const double lane_turn = centre.a;  // the sign of its curvature (a frame keeps its sense)
  return std::fabs(h.yaw_rate0) >= kFeedforwardMinYawRate && lane_turn * h.yaw_rate0 > 0.0;
}

// Fills the lateral part of a vehicle's hypothesis set and scores its paths; `lanes` of the
// ego's lane samples (-1, 0, +1) when asked.
std::vector<PathScore> SetPaths(const FittedLanes& lanes, const Params& p, bool combine,
                                double a_ref, core::HypothesisSet* h,
                                std::vector<int>* sample_lanes = nullptr,
                                bool centre_only = false) {
  const double held = centre_only ? -1.0 : HeldLineFraction(lanes, h->half_width, p);
  const std::vector<LateralSample> samples = LateralSamples(lanes, p, centre_only, held);
  const int n_lat = static_cast<int>(samples.size());
  const int n_inst = static_cast<int>(p.path_sample_times_s.size());
  h->n_instants = n_inst;
  h->n_lateral = n_lat;
  h->combine_sections = combine;
  for (int k = 0; k < n_inst; ++k) {
    h->instant_time[k] = p.path_sample_times_s[k];
    for (int l = 0; l < n_lat; ++l) h->section[k][l] = samples[l].curve;
  }
  if (sample_lanes) {
    sample_lanes->clear();
    for (const LateralSample& ls : samples) sample_lanes->push_back(ls.lane);
  }
  int n_paths = n_lat;
  if (combine) {
    n_paths = 1;
    for (int k = 0; k < n_inst; ++k) n_paths *= n_lat;
  }
  h->n_paths = n_paths;

  // The reference path: the own lane's centre, or the held line. Offsets of each sample from
  // it where the reference trajectory is at each sample instant.
  const core::Parabola reference = held >= 0.0 ? lanes.own->At(held) : lanes.own->Centre();
  h->reference_path = reference;
  h->steer_feedforward = TurningAlongLane(*h, reference, p);
  std::vector<double> offset(static_cast<size_t>(n_inst) * n_lat);
  for (int k = 0; k < n_inst; ++k) {
    const double x =
        core::XAfterArc(reference, 0.0, ReferenceDistance(h->v0, a_ref, p.path_sample_times_s[k]));
    for (int l = 0; l < n_lat; ++l) {
      const double across = samples[l].curve.Eval(x) - reference.Eval(x);
      offset[k * n_lat + l] = std::fabs(across);
      if (h->on_way) h->way_lateral[k][l] = across;  // its paths along its way
    }
  }
  std::vector<PathScore> scores(n_paths);
  for (int path = 0; path < n_paths; ++path) {
    double mean = 0.0, mean_z2 = 0.0;
    int changes = 0, crossings = 0, lane = 0;
    bool counter = false;
    for (int k = 0; k < n_inst; ++k) {
      const int l = core::SectionOfPath(*h, path, k);
      const double off = offset[k * n_lat + l];
      mean += off;
      mean_z2 += (off / p.lateral_offset_sigma_m) * (off / p.lateral_offset_sigma_m);
      counter = counter || samples[l].counter_traffic;
      if (k > 0 && l != core::SectionOfPath(*h, path, k - 1)) ++changes;
      crossings += std::abs(samples[l].lane - lane);
      lane = samples[l].lane;
    }
    mean /= n_inst;
    mean_z2 /= n_inst;
    if (Naturalistic(p)) {
      scores[path].d_path = core::GaussianScore(mean_z2);
      scores[path].penalty = std::pow(p.lane_crossing_penalty, crossings) *
                             (counter ? p.counter_traffic_penalty : 1.0);
    } else {
      scores[path].d_path = core::DeviationScore(mean, p.path_score_scale_m);
      scores[path].penalty =
          (1.0 + p.complexity_penalty * changes) * (counter ? p.counter_traffic_penalty : 1.0);
    }
  }
  return scores;
}

// Scores every (profile, path) hypothesis and L1-normalises them into probabilities:
// n_h = (w_acc n_acc + w_str d_str) / (c_com c_cou), d_str = d_path (paper-literal) or
// d_path * d_lon (naturalistic: the position deviation along and across the road).
void AppendProbabilities(const std::vector<ProfileScore>& profiles,
                         const std::vector<PathScore>& paths, const Params& p,
                         std::vector<double>* out) {
  const size_t first = out->size();
  double sum = 0.0;
  const bool naturalistic = Naturalistic(p);
  for (const ProfileScore& ps : profiles) {
    for (const PathScore& path : paths) {
      const double d_str = naturalistic ? path.d_path * ps.d_lon : path.d_path;
      const double score =
          core::HypothesisScore(p.w_acc, ps.n_acc, p.w_str, d_str, path.penalty, 1.0);
      out->push_back(score);
      sum += score;
    }
  }
  for (size_t i = first; i < out->size(); ++i) (*out)[i] /= sum;
}

// The profile targets in acceleration (m/s^2): the paper's samples (minimum, negative spread,
// zero, maximum), with the one nearest the current acceleration replaced by it when asked
// (the reference hypothesis). Returns the index of the reference profile, -1 without one.
int ProfileAccelerations(int n, double lo, double hi, double current, bool include_current,
                         bool equally_spaced, std::vector<double>* out) {
  out->resize(n);
  for (int k = 0; k < n; ++k) {
    (*out)[k] = equally_spaced ? core::EquallySpaced(k, n, lo, hi)
                               : core::VehicleProfileTarget(k, n, lo, hi);
  }
  if (!include_current) return -1;
  const double a = core::Clamp(current, lo, hi);
  int nearest = 1;
  for (int k = 2; k < n - 1; ++k) {
    if (std::fabs((*out)[k] - a) < std::fabs((*out)[nearest] - a)) nearest = k;
  }
  (*out)[nearest] = a;
  return nearest;
}

// Distance covered by each sample instant under an acceleration profile (1-D: the profile's
// latency and ramp, the drive limit, never reversing; pedestrians within their speed limit),
// stepped as the motion models step it. `scale` turns profile values into m/s^2.
std::vector<double> ProfileDistances(const core::HypothesisSet& h, double target, double scale,
                                     const Params& p, bool pedestrian) {
  const double tau = p.step_s;
  const int steps = p.TimeSteps();
  std::vector<double> at(p.path_sample_times_s.size(), 0.0);
  std::vector<int> step_of(at.size());
  for (size_t i = 0; i < at.size(); ++i) {
    step_of[i] = static_cast<int>(std::llround(p.path_sample_times_s[i] / tau));
  }
  double x = 0.0, v = pedestrian ? core::Clamp(h.v0, 0.0, h.max_speed) : h.v0;
  for (int n = 0; n < steps; ++n) {
    const double t = n * tau;
    if (pedestrian) {
      double py = 0.0;
      core::PedestrianStep(0.0, target, h.max_speed, tau, &x, &py, &v);
    } else {
      double a = scale * core::RampedValue(t, h.profile_start, target, h.latency, h.rate);
      if (h.power_limited && a > 0.0) a = core::Min(a, core::DriveAccelLimit(h, v));
      a = core::NonReversingAccel(v, core::TopSpeedAccel(v, a, tau, h.top_speed), tau);
      x += v * tau + 0.5 * a * tau * tau;
      v = core::Max(0.0, v + a * tau);
    }
    for (size_t i = 0; i < at.size(); ++i) {
      if (step_of[i] == n + 1) at[i] = x;
    }
  }
  return at;
}

// d_lon of every profile: exp(-mean_i (dx_i / sigma_x(t_i))^2 / 2), dx_i the distance the
// profile gains or loses on the reference profile by sample instant t_i. For vehicles,
// sigma_x(t) is what a profile one sigma_a off the reference gains or loses by then, through
// the same latency, ramp and drive limit (so d_lon measures the same deviation as n_acc, in
// distance: what a stop or the power limit make of it); for pedestrians sigma_v t, the spread
// of walking speeds.
void SetLongitudinalScores(const core::HypothesisSet& h, int reference, double scale,
                           const Params& p, bool pedestrian, std::vector<ProfileScore>* out) {
  if (reference < 0) return;
  const double ref_target = h.profile_target[reference];
  const std::vector<double> ref = ProfileDistances(h, ref_target, scale, p, pedestrian);
  std::vector<double> slower, faster;
  if (!pedestrian) {
    slower = ProfileDistances(h, ref_target - p.decel_score_sigma_mps2 / scale, scale, p, false);
    faster = ProfileDistances(h, ref_target + p.accel_score_sigma_mps2 / scale, scale, p, false);
  }
  constexpr double kMinSigma = 0.01;  // m: a stopped vehicle cannot lose distance
  for (int k = 0; k < h.n_profiles; ++k) {
    const std::vector<double> d = ProfileDistances(h, h.profile_target[k], scale, p, pedestrian);
    double z2 = 0.0;
    for (size_t i = 0; i < d.size(); ++i) {
      const double t = p.path_sample_times_s[i];
      double sigma = p.pedestrian_speed_sigma_mps * t;
      if (!pedestrian) sigma = std::fabs((d[i] < ref[i] ? slower[i] : faster[i]) - ref[i]);
      sigma = core::Max(sigma, kMinSigma);
      z2 += ((d[i] - ref[i]) / sigma) * ((d[i] - ref[i]) / sigma);
    }
    (*out)[k].d_lon = core::GaussianScore(z2 / static_cast<double>(d.size()));
  }
}

// A vehicle's stop obligation as the estimator uses it (Params::stop_obligations).
struct StopObligation {
  double distance_m{0.0};  ///< front bumper to the line
};

// The obligation of a vehicle (or the ego) in `state` with `line` when it counts: enabled,
// naturalistic scoring, and complying is consistent with what the vehicle does (the
// deceleration it needs, v^2 / 2d, is comfortable, or it already brakes at least half that
// hard). `comfortable_mps2`: Params::stop_comfortable_decel_mps2, or more for a vehicle whose
// type brakes harder as a matter of course (ComfortableStopDecel).
std::optional<StopObligation> CredibleStop(const std::optional<StopLine>& line,
                                           const ObjectState& state, const Params& p,
                                           double comfortable_mps2) {
  if (!line || !p.stop_obligations || !Naturalistic(p) || p.profiles < 4) return {};
  const double d = line->distance_m;
  const double speed = state.speed_mps;
  if (speed <= 0.0) return StopObligation{d};
  const double needed = speed * speed / (2.0 * d);  // +inf at the line
  if (needed <= comfortable_mps2 || -state.accel_mps2 >= 0.5 * needed) {
    return StopObligation{d};
  }
  return {};
}

// The constant acceleration that stops a vehicle at `speed` with its front at the line: -v^2 / 2d
// (0 for a vehicle that stands).
double StopAtLineAccel(double speed, const StopObligation& stop) {
  return speed <= 0.0 ? 0.0 : -speed * speed / (2.0 * stop.distance_m);
}

// How hard another vehicle brakes to stop at a line as a matter of course: the comfortable
// deceleration, or its type's normal largest deceleration where that is more and
// Params::stop_obligation_at_once says it acts as SUMO's drivers do (they brake up to it to
// stop at a junction's line).
double ComfortableStopDecel(const VehicleType& type, const Params& p) {
  double d = p.stop_comfortable_decel_mps2;
  if (p.stop_obligation_at_once && type.decel_mps2) d = std::fmax(d, *type.decel_mps2);
  return d;
}

// Params::ego_stop_obligations: the ego's reference acceleration `a_ref`, or the constant
// deceleration that stops its front at a credible stop line (holding it where it stands) where
// that is lower.
double EgoReferenceWithStop(const Ego& ego, double a_ref, const Params& p) {
  if (!p.ego_stop_obligations) return a_ref;
  const std::optional<StopObligation> stop =
      CredibleStop(ego.stop_line, ego.state, p, p.stop_comfortable_decel_mps2);
  if (!stop) return a_ref;
  return std::fmin(a_ref, StopAtLineAccel(ego.state.speed_mps, *stop));
}

// Where another vehicle's profiles start (held through the latency): its current acceleration, or
// lower where it acts now on what it is expected to do: its expected acceleration
// (Params::expected_accel_at_once) or the deceleration that stops it at a credible stop line
// (Params::stop_obligation_at_once).
double ProfileStartAccel(const ObjectState& s, const std::optional<StopObligation>& stop,
                         const Params& p) {
  double start = s.accel_mps2;
  if (p.expected_accel_at_once) start = std::fmin(start, ExpectedAccelInForce(s, p));
  if (p.stop_obligation_at_once && stop && s.speed_mps > 0.0 && stop->distance_m > 0.0)
    start = std::fmin(start, StopAtLineAccel(s.speed_mps, *stop));
  return start;
}

// Where a vehicle comes to rest (or how far it gets within `limit_s`) under a one-track profile
// target: the same latency, ramp and non-reversing step as the motion models.
double StopDistance(const core::HypothesisSet& h, double target, const Params& p) {
  constexpr double kLimitS = 60.0;
  const double tau = p.step_s;
  double x = 0.0, v = h.v0;
  for (double t = 0.0; t < kLimitS && v > 0.0; t += tau) {
    double a = core::RampedValue(t, h.profile_start, target, h.latency, h.rate);
    if (h.power_limited && a > 0.0) a = core::Min(a, core::DriveAccelLimit(h, v));
    a = core::NonReversingAccel(v, core::TopSpeedAccel(v, a, tau, h.top_speed), tau);
    x += v * tau + 0.5 * a * tau * tau;
    v = core::Max(0.0, v + a * tau);
  }
  return x;
}

// Puts the stopping profile into `a` (one-track targets): the constant deceleration that stops
// the front at the line (bisection on StopDistance, to 1e-4 m/s^2; a standing vehicle: the
// comfortable deceleration, which holds it), in the slot nearest to it among those that are
// neither the minimum, the maximum nor the reference. Returns its index, or -1 (the estimate is
// then the one without a line) when the current acceleration already stops the vehicle before
// the line (it complies as it is), when even the minimum overshoots the line (it cannot comply)
// or when no slot is free.
int StopProfile(const core::HypothesisSet& h, const StopObligation& stop, int reference,
                double lo_accel, const Params& p, std::vector<double>* a) {
  const int n = static_cast<int>(a->size());
  // Already stopping before the line at its current acceleration: that complies, and stays the
  // reference (nothing to add).
  if (reference >= 0 && StopDistance(h, (*a)[reference], p) <= stop.distance_m) return -1;
  double lo = lo_accel, hi = 0.0;
  if (StopDistance(h, lo, p) > stop.distance_m) return -1;
  for (int i = 0; i < 60 && hi - lo > 1e-4; ++i) {
    const double mid = 0.5 * (lo + hi);
    (StopDistance(h, mid, p) > stop.distance_m ? hi : lo) = mid;
  }
  const double target = h.v0 > 0.0 ? lo : -p.stop_comfortable_decel_mps2;
  int slot = -1;
  for (int k = 1; k < n - 1; ++k) {
    if (k == reference) continue;
    if (slot < 0 || std::fabs((*a)[k] - target) < std::fabs((*a)[slot] - target)) slot = k;
  }
  if (slot >= 0) (*a)[slot] = target;
  return slot;
}

// The longitudinal part of a vehicle's hypothesis set (the ego: two-track, driven by slip or
// by tyre force demand; others: one-track accelerations) and its profile scores. `accel` gets
// each profile's target acceleration and `slip` its slip (the ego's, for reports).
// `a_ref` is the reference acceleration (ReferenceAccel), `r` the range of its type (RangeOf:
// profiles, scores' ranges, the stopping profile and the top speed). With `stop` (a credible stop
// obligation, other vehicles only), one profile becomes the stopping profile and its index is
// written to `stop_profile` (-1 when none fits: see StopProfile).
std::vector<ProfileScore> SetVehicleProfiles(const Params& p, double a_ref, double start_accel,
                                             const ProfileRange& r, core::HypothesisSet* h,
                                             std::vector<double>* accel = nullptr,
                                             std::vector<double>* slip = nullptr,
                                             const StopObligation* stop = nullptr,
                                             int* stop_profile = nullptr) {
  h->n_profiles = p.profiles;
  h->latency = p.latency_s;
  h->steer_latency = p.steer_latency_s;
  h->power_limited = p.power_limited_drive;
  h->top_speed = r.top_speed;
  const double mu_g = h->vehicle.friction * core::kGravity;
  h->drive_traction = p.drive_traction_share * mu_g;
  const bool ego = h->model == core::MotionModelKind::kTwoTrack;
  std::vector<ProfileScore> scores(p.profiles);
  std::vector<double> a;
  int reference = ProfileAccelerations(p.profiles, r.lo, r.hi, a_ref,
                                       p.profiles_include_current_accel, false, &a);
  for (double& x : a) x = std::fmax(x, r.floor);
  const double current = r.Clamp(a_ref);
  // A typed vehicle's profiles start from its current acceleration within its range, so that
  // not even the latency before a profile acts leaves the range.
  const double start = r.typed ? r.Clamp(start_accel) : start_accel;
  double scale = 1.0;  // profile value -> m/s^2
  if (ego && !p.ego_profiles_in_accel) {
    // Paper: longitudinal slip, equally spaced as the accelerations are; no reference profile.
    // A typed ego's slips stay within what its range's accelerations need.
    reference = -1;
    double slip_lo = p.ego_slip_min, slip_hi = p.ego_slip_max;
    if (r.typed) {
      slip_lo = std::fmax(slip_lo, core::SlipFromAccel(h->vehicle, r.lo));
      slip_hi = std::fmin(slip_hi, core::SlipFromAccel(h->vehicle, r.hi));
    }
    std::vector<double> s_targets;
    ProfileAccelerations(p.profiles, slip_lo, slip_hi, 0.0, false, false, &s_targets);
    h->profile_start = core::SlipFromAccel(h->vehicle, start);
    h->rate = p.ego_slip_max * p.jerk_mps3 / p.vehicle_accel_max_mps2;
    const double range = p.accel_score_scale * std::fmax(std::fabs(slip_lo), std::fabs(slip_hi));
    for (int k = 0; k < p.profiles; ++k) {
      h->profile_target[k] = s_targets[k];
      a[k] = core::AccelFromSlip(h->vehicle, s_targets[k]);
      scores[k].n_acc = core::DeviationScore(h->profile_target[k] - h->profile_start, range);
    }
    if (Naturalistic(p)) {
      for (int k = 0; k < p.profiles; ++k) {
        scores[k].n_acc = AccelScore(p, a[k] - current);
      }
    }
  } else {
    if (ego) {
      // Tyre force demand a / (mu g) on the four wheels, ramped in acceleration.
      h->force_profiles = true;
      scale = mu_g;
      h->profile_start = core::Clamp(start / mu_g, -1.0, 1.0);
      h->rate = p.jerk_mps3 / mu_g;
      const double a_ref_target = r.typed ? current : a_ref;
      for (int k = 0; k < p.profiles; ++k) {
        h->profile_target[k] = k == reference ? core::Clamp(a_ref_target / mu_g, -1.0, 1.0)
                                              : core::Clamp(a[k] / mu_g, -1.0, 1.0);
      }
    } else {
      h->profile_start = start;
      h->rate = p.jerk_mps3;
      if (stop) *stop_profile = StopProfile(*h, *stop, reference, r.floor, p, &a);
      for (int k = 0; k < p.profiles; ++k) h->profile_target[k] = a[k];
    }
    const double range = p.accel_score_scale * std::fmax(std::fabs(r.lo), std::fabs(r.hi));
    for (int k = 0; k < p.profiles; ++k) {
      if (Naturalistic(p)) {
        scores[k].n_acc = AccelScore(p, a[k] - current);
      } else {
        scores[k].n_acc = core::DeviationScore(h->profile_target[k] - h->profile_start, range);
      }
    }
  }
  if (Naturalistic(p)) SetLongitudinalScores(*h, reference, scale, p, false, &scores);
  if (accel) *accel = a;
  if (slip) {
    slip->resize(p.profiles);
    for (int k = 0; k < p.profiles; ++k) {
      (*slip)[k] = h->force_profiles ? core::SlipFromAccel(h->vehicle, a[k]) : h->profile_target[k];
    }
  }
  return scores;
}

// Ego lane dividers (ego frame) that the segment from (x0, y0) to (x1, y1) crosses.
int DividerCrossings(const FittedLanes& lanes, double x0, double y0, double x1, double y1) {
  std::vector<const core::Parabola*> dividers;
  if (lanes.right) dividers.push_back(&lanes.right->right);
  dividers.push_back(&lanes.own->right);
  dividers.push_back(&lanes.own->left);
  if (lanes.left) dividers.push_back(&lanes.left->left);
  int n = 0;
  for (const core::Parabola* d : dividers) {
    if ((d->OffsetFrom(x0, y0) < 0.0) != (d->OffsetFrom(x1, y1) < 0.0)) ++n;
  }
  return n;
}

// Whether (x, y) (ego frame) lies between the ego's outermost lane dividers.
bool InsideLanes(const FittedLanes& lanes, double x, double y) {
  const core::Parabola& leftmost = lanes.left ? lanes.left->left : lanes.own->left;
  const core::Parabola& rightmost = lanes.right ? lanes.right->right : lanes.own->right;
  return leftmost.OffsetFrom(x, y) > 0.0 && rightmost.OffsetFrom(x, y) < 0.0;
}

}  // namespace

std::vector<std::int16_t> FoldCarriages(const Problem& pb,
                                        const std::vector<std::int16_t>& first_step) {
  const int n_ego = pb.EgoTrajectories(), n_all = pb.CoTrajectories();
  const int n_obj = pb.ObjectTrajectories();
  std::vector<std::int16_t> folded(static_cast<size_t>(n_ego) * n_obj);
  for (int i = 0; i < n_ego; ++i) {
    const std::int16_t* row = first_step.data() + static_cast<size_t>(i) * n_all;
    std::int16_t* out = folded.data() + static_cast<size_t>(i) * n_obj;
    std::copy(row, row + n_obj, out);
    for (size_t s = pb.objects.size(); s < pb.cos.size(); ++s) {
      const int o = pb.carriage_object[s - pb.objects.size()];
      const int first = pb.co_offset[o], count = pb.co_offset[o + 1] - first;
      for (int t = 0; t < count; ++t) {
        const std::int16_t hit =
            row[pb.co_offset[s] + pb.CarriageTrajectory(static_cast<int>(s), t)];
        std::int16_t& f = out[first + t];
        if (hit > 0 && (f == 0 || hit < f)) f = hit;
      }
    }
  }
  return folded;
}

Problem ObjectProblem(const Problem& pb) {
  Problem out = pb;
  const size_t n_sets = pb.objects.size();
  const int n_obj = pb.ObjectTrajectories();
  out.cos.resize(n_sets);
  out.co_offset.resize(n_sets + 1);
  out.co_object_of.resize(n_obj);
  out.co_probability.resize(n_obj);
  out.carriage_object.clear();
  out.counts.co_trajectories = n_obj;
  return out;
}

WorkCounts ResultCounts(const Problem& pb) {
  WorkCounts c = pb.counts;
  c.co_trajectories = pb.ObjectTrajectories();
  c.carriage_trajectories = pb.CoTrajectories() - c.co_trajectories;
  return c;
}

std::uint64_t WorkloadBytes(std::uint64_t ego_trajectories, std::uint64_t co_trajectories,
                            std::uint64_t steps, std::uint64_t objects) {
  const std::uint64_t poses = (ego_trajectories + co_trajectories) * steps;
  return poses * 5 * sizeof(double) + ego_trajectories * co_trajectories * sizeof(std::int16_t) +
         ego_trajectories * (steps + objects) * sizeof(double);
}

Problem BuildProblem(const Scene& scene, const Params& params) {
  ValidateScene(scene, params);
  Problem pb;
  pb.sim.tau = params.step_s;
  pb.sim.n_steps = params.TimeSteps();
  pb.sim.controller = core::ControllerLimits{params.max_steer_rad,     params.max_steer_rate_radps,
                                             params.preview_s_per_mps, params.preview_min_s,
                                             params.preview_max_s,     params.lateral_controller};

  // Street data: the ego's lanes (virtual own lane when missing), fitted in its frame.
  const LaneSet ego_lanes = params.road_model
                                ? CompleteEgoLanes(scene.ego, params)
                                : VirtualLaneSet(scene.ego.state, params.virtual_lane_width_m);
  const FittedLanes ego_fitted = FitLanes(ego_lanes, "scene.ego.lanes", params);

  // The ego: two-track model, every combination of path sections.
  {
    core::HypothesisSet& h = pb.ego;
    h.model = core::MotionModelKind::kTwoTrack;
    // Its type's limits and model (Params::road_user_classes); its body stays one box.
    const VehicleType& type = scene.ego.type;
    h.vehicle =
        VehicleModelParams(scene.ego.length_m, scene.ego.width_m, scene.ego.height_m, type, params);
    SetPose(scene.ego.state, scene.ego.length_m, scene.ego.width_m, &h);
    SetRouteEnd(scene.ego.state, params, &h);
    h.seam_speed = SeamSpeedOf(h.vehicle, type, params);
    const double a_ref = EgoReferenceWithStop(
        scene.ego, ReferenceAccel(scene.ego.state, ego_fitted.own->Centre(), params), params);
    const std::vector<ProfileScore> profiles =
        SetVehicleProfiles(params, a_ref, scene.ego.state.accel_mps2,  // its driver's latency
                           RangeOf(type, params), &h, &pb.ego_profile_accel, &pb.ego_profile_slip);
    const bool track = TrackBound(type, params);
    // On its way (Params::ego_on_way) where the way passes it: as any vehicle on its way, one
    // path along it, or (Params::way_lateral_paths) its sections as offsets beside the way
    // (SetPaths stores them), its lateral latency kept.
    const bool on_way = !track && params.ego_on_way && params.bodies_on_way && scene.ego.way &&
                        PutOnWay(*scene.ego.way, &h);
    const bool one_path = track || (on_way && !params.way_lateral_paths);
    if (one_path) h.steer_latency = 0.0;
    const std::vector<PathScore> paths =
        SetPaths(ego_fitted, params, /*combine=*/true, a_ref, &h, &pb.ego_sample_lane, one_path);
    if (track) PutOnTrack(&h);
    AppendProbabilities(profiles, paths, params, &pb.ego_probability);
    pb.ego_lane_centre = ego_fitted.own->Centre();
    for (size_t i = 1; i < pb.ego_probability.size(); ++i) {
      if (pb.ego_probability[i] > pb.ego_probability[pb.ego_reference_trajectory])
        pb.ego_reference_trajectory = static_cast<int>(i);
    }
  }

  const core::Pose2 X_WE{scene.ego.state.x_m, scene.ego.state.y_m, scene.ego.state.yaw_rad};
  // The lanes a vehicle (or a carriage) at `s` uses: associated by its centre of gravity with
  // the ego's lanes, if it drives along them (within 45 deg either way), it uses, without lanes
  // of its own, the ego's lanes seen from its frame; crossing traffic without lanes of its own
  // gets a virtual lane.
  auto lanes_of = [&](const ObjectState& s, const std::optional<LaneSet>& own,
                      LaneIndex* associated) {
    core::Pose2 X_EV;
    core::WorldToLocal(X_WE, s.x_m, s.y_m, &X_EV.x, &X_EV.y);
    X_EV.yaw = core::WrapAngle(s.yaw_rad - X_WE.yaw);
    const LaneIndex lane = std::fabs(std::cos(X_EV.yaw)) >= std::cos(core::kPi / 4)
                               ? AssociateLane(ego_fitted, X_EV.x, X_EV.y)
                               : LaneIndex::kNone;
    if (associated) *associated = lane;
    LaneSet lanes = !params.road_model ? VirtualLaneSet(s, params.virtual_lane_width_m)
                    : own              ? *own
                                       : EgoLanesSeenBy(ego_lanes, X_EV, lane);
    if (!lanes.own) lanes.own = VirtualLane(s, params.virtual_lane_width_m);
    return lanes;
  };
  int offset = 0;
  pb.co_offset.push_back(0);
  std::vector<core::HypothesisSet> carriage_sets;  // appended after every object
  for (size_t i = 0; i < scene.vehicles.size(); ++i) {
    const Vehicle& v = scene.vehicles[i];
    const std::string where = ObjectName("scene.vehicles", i, v.id);
    core::HypothesisSet h;
    h.model = core::MotionModelKind::kOneTrack;
    h.vehicle = VehicleModelParams(v.length_m, v.width_m, v.height_m, v.type, params);
    SetPose(v.state, v.length_m, v.width_m, &h);
    SetRouteEnd(v.state, params, &h);
    h.seam_speed = SeamSpeedOf(h.vehicle, v.type, params);
    ObjectResult info;
    info.id = v.id;
    info.kind = ObjectKind::kVehicle;
    LaneIndex lane = LaneIndex::kNone;
    const LaneSet lanes = lanes_of(v.state, v.lanes, &lane);
    info.lane = static_cast<int>(lane);
    const FittedLanes fitted = FitLanes(lanes, where + ".lanes", params);
    const double a_ref = ReferenceAccel(v.state, fitted.own->Centre(), params);
    const std::optional<StopObligation> stop =
        CredibleStop(v.stop_line, v.state, params, ComfortableStopDecel(v.type, params));
    std::vector<double> accel;
    int stop_profile = -1;
    const std::vector<ProfileScore> profiles = SetVehicleProfiles(
        params, a_ref, ProfileStartAccel(v.state, stop, params), RangeOf(v.type, params), &h,
        &accel, nullptr, stop ? &*stop : nullptr, &stop_profile);
    const bool track = TrackBound(v.type, params);
    // On its way (Params::bodies_on_way) where the way passes it: its lanes' lateral samples
    // as paths along it (Params::way_lateral_paths), else one path, as on a track.
    const bool on_way = !track && params.bodies_on_way && v.way && PutOnWay(*v.way, &h);
    const bool one_path = track || (on_way && !params.way_lateral_paths);
    if (one_path) h.steer_latency = 0.0;
    const std::vector<PathScore> paths =
        SetPaths(fitted, params, /*combine=*/false, a_ref, &h, nullptr, one_path);
    if (track) PutOnTrack(&h);
    AppendProbabilities(profiles, paths, params, &pb.co_probability);
    if (stop_profile >= 0) {
      // A mixture: complying (every hypothesis scored against the stopping profile as the
      // reference) with 1 - stop_violation_probability, driving on as without a line (the
      // scores above) with stop_violation_probability.
      std::vector<ProfileScore> complying(profiles.size());
      for (size_t k = 0; k < complying.size(); ++k) {
        complying[k].n_acc = AccelScore(params, accel[k] - accel[stop_profile]);
      }
      SetLongitudinalScores(h, stop_profile, 1.0, params, false, &complying);
      std::vector<double> q;
      AppendProbabilities(complying, paths, params, &q);
      const double eps = params.stop_violation_probability;
      double* mine = pb.co_probability.data() + pb.co_probability.size() - q.size();
      for (size_t j = 0; j < q.size(); ++j) mine[j] = eps * mine[j] + (1.0 - eps) * q[j];
    }
    info.first_trajectory = offset;
    info.trajectories = h.Trajectories();
    offset += info.trajectories;
    // Its carriages (estimator/ALGORITHM.md, "Long and articulated bodies"): each a hypothesis
    // set of its own pose, lanes and box with the vehicle's profiles (so it moves with the
    // vehicle's speed along its own lane), folded into the vehicle's columns before the risk.
    for (size_t k = 0; k < v.carriages.size(); ++k) {
      const Carriage& car = v.carriages[k];
      core::HypothesisSet c = h;  // profiles, latencies, limits, route end, top speed
      c.vehicle = VehicleModelParams(car.length_m, car.width_m, std::nullopt, v.type, params);
      // The vehicle's drive, so that its speed is the vehicle's at every step.
      c.vehicle.power_per_mass_wpkg = h.vehicle.power_per_mass_wpkg;
      ObjectState cs = v.state;
      cs.x_m = car.x_m;
      cs.y_m = car.y_m;
      cs.yaw_rad = car.yaw_rad;
      cs.yaw_rate_radps = car.yaw_rate_radps;
      cs.sideslip_rad = 0.0;
      SetPose(cs, car.length_m, car.width_m, &c);
      c.seam_speed = SeamSpeedOf(c.vehicle, v.type, params);
      const FittedLanes car_fitted =
          FitLanes(lanes_of(cs, car.lanes, nullptr),
                   where + ".carriages[" + std::to_string(k) + "].lanes", params);
      // Its paths: those of the vehicle (the same lateral samples of its own lanes) where its
      // lanes have the vehicle's neighbours, else (and on a track) its own lane's centre for
      // every hypothesis.
      const bool same_lanes = car_fitted.left.has_value() == fitted.left.has_value() &&
                              car_fitted.right.has_value() == fitted.right.has_value();
      if (on_way) {  // its own lane, steered as any vehicle's (the way is the vehicle's)
        c.on_way = false;
        c.n_way = 0;
        std::fill(&c.way_lateral[0][0], &c.way_lateral[0][0] + sizeof c.way_lateral / sizeof(double),
                  0.0);
        c.steer_latency = params.steer_latency_s;
      }
      SetPaths(car_fitted, params, /*combine=*/false, a_ref, &c, nullptr,
               track || on_way || !same_lanes);
      if (track) PutOnTrack(&c);  // its own track, replacing the copy of the vehicle's
      carriage_sets.push_back(c);
      pb.carriage_object.push_back(static_cast<int>(i));
    }
    pb.cos.push_back(h);
    pb.objects.push_back(info);
    pb.co_offset.push_back(offset);
  }
  for (size_t i = 0; i < scene.pedestrians.size(); ++i) {
    const Pedestrian& ped = scene.pedestrians[i];
    core::HypothesisSet h;
    h.model = core::MotionModelKind::kPedestrian;
    SetPose(ped.state, ped.length_m, ped.width_m, &h);
    h.max_speed = params.pedestrian_max_speed_mps;
    h.n_profiles = params.profiles;
    h.n_paths = params.pedestrian_headings;
    h.profile_start = h.accel0;
    // The reference: the current acceleration, or a lower expected one (a person stopping
    // where it must wait; Params::expected_accel_reference).
    const double a_ref = std::fmin(h.accel0, ExpectedAccelInForce(ped.state, params));
    std::vector<double> a;
    const int reference = ProfileAccelerations(
        h.n_profiles, params.pedestrian_accel_min_mps2, params.pedestrian_accel_max_mps2, a_ref,
        params.profiles_include_current_accel, /*equally_spaced=*/true, &a);
    const double scale =
        params.accel_score_scale * std::fmax(std::fabs(params.pedestrian_accel_min_mps2),
                                             std::fabs(params.pedestrian_accel_max_mps2));
    std::vector<ProfileScore> profiles(h.n_profiles);
    const double current =
        core::Clamp(a_ref, params.pedestrian_accel_min_mps2, params.pedestrian_accel_max_mps2);
    for (int k = 0; k < h.n_profiles; ++k) {
      h.profile_target[k] = a[k];
      if (Naturalistic(params)) {
        profiles[k].n_acc = AccelScore(params, a[k] - current);
      } else {
        profiles[k].n_acc = core::DeviationScore(h.profile_target[k] - h.accel0, scale);
      }
    }
    if (Naturalistic(params)) SetLongitudinalScores(h, reference, 1.0, params, true, &profiles);
    // Headings; naturalistic c_com: the ego lane dividers each heading line crosses within the
    // pedestrian's current speed x horizon, against the straight-on heading's.
    double px, py;
    core::WorldToLocal(X_WE, ped.state.x_m, ped.state.y_m, &px, &py);
    const double reach = h.v0 * params.horizon_s;
    auto crossings = [&](double heading_W) {
      const double d = heading_W - X_WE.yaw;
      return DividerCrossings(ego_fitted, px, py, px + reach * std::cos(d),
                              py + reach * std::sin(d));
    };
    // Params::footway_pedestrians: outside the ego's lanes on a footway it keeps to, every
    // crossing onto them counts; otherwise against the straight-on heading's.
    const bool keeps_off =
        params.footway_pedestrians && ped.stays_on_footway && !InsideLanes(ego_fitted, px, py);
    const int straight_on = keeps_off ? 0 : crossings(ped.state.yaw_rad);
    std::vector<PathScore> headings(h.n_paths);
    for (int l = 0; l < h.n_paths; ++l) {
      const double turn = core::WrapAngle(2.0 * core::kPi * l / h.n_paths);
      h.heading[l] = ped.state.yaw_rad + turn;
      if (Naturalistic(params)) {
        const double z = turn / params.heading_score_sigma_rad;
        headings[l].d_path = core::GaussianScore(z * z);
        headings[l].penalty =
            std::pow(params.lane_crossing_penalty, std::abs(crossings(h.heading[l]) - straight_on));
      } else {
        headings[l].d_path = core::DeviationScore(turn, params.heading_score_scale_rad);
      }
    }
    AppendProbabilities(profiles, headings, params, &pb.co_probability);
    ObjectResult info;
    info.id = ped.id;
    info.kind = ObjectKind::kPedestrian;
    info.lane = static_cast<int>(LaneIndex::kNone);
    info.first_trajectory = offset;
    info.trajectories = h.Trajectories();
    offset += info.trajectories;
    pb.cos.push_back(h);
    pb.objects.push_back(info);
    pb.co_offset.push_back(offset);
  }

  // The carriages' sets after every object, so that the objects' columns of the pair matrix
  // come first (FoldCarriages). Their probabilities are never used (the vehicle's are); each
  // set gets a uniform distribution so that the unfolded problem stays well-formed.
  for (const core::HypothesisSet& c : carriage_sets) {
    pb.cos.push_back(c);
    const int n = c.Trajectories();
    for (int t = 0; t < n; ++t) pb.co_probability.push_back(1.0 / n);
    offset += n;
    pb.co_offset.push_back(offset);
  }

  // The world's position update (estimator/ALGORITHM.md, "The simulator's position update").
  pb.ego.position_lead = 0.5 * scene.euler_update_step_s;
  for (core::HypothesisSet& h : pb.cos) h.position_lead = 0.5 * scene.euler_update_step_s;
  if (params.collisions_at_world_steps && scene.euler_update_step_s > 0.0) {
    const double ratio = scene.euler_update_step_s / pb.sim.tau;
    const int hold = static_cast<int>(std::lround(ratio));
    if (hold > 1 && std::fabs(ratio - hold) < 1e-6 * ratio) {
      pb.ego.pose_hold_steps = hold;
      pb.ego.hold_stops = params.euler_stops;
      for (core::HypothesisSet& h : pb.cos) {
        h.pose_hold_steps = hold;
        h.hold_stops = params.euler_stops;
      }
    }
  }
  // Where the world puts bodies in a turn (Scene::bodies_on_path).
  pb.ego.body_on_path = scene.bodies_on_path;
  for (core::HypothesisSet& h : pb.cos)
    h.body_on_path = scene.bodies_on_path && h.model != core::MotionModelKind::kPedestrian;

  pb.counts.time_steps = pb.sim.n_steps;
  pb.counts.ego_trajectories = pb.ego.Trajectories();
  pb.counts.co_trajectories = offset;
  pb.counts.pose_combinations = static_cast<std::uint64_t>(pb.counts.ego_trajectories) *
                                static_cast<std::uint64_t>(offset) *
                                static_cast<std::uint64_t>(pb.sim.n_steps);
  const std::uint64_t bytes =
      WorkloadBytes(pb.counts.ego_trajectories, offset, pb.sim.n_steps, pb.cos.size());
  if (bytes > params.max_memory_bytes) {
    std::ostringstream msg;
    msg << "workload too large: " << pb.counts.ego_trajectories << " ego x " << offset
        << " CO trajectories x " << pb.sim.n_steps << " steps need " << (bytes >> 20)
        << " MiB, above params.max_memory_bytes = " << (params.max_memory_bytes >> 20)
        << " MiB; reduce the objects, profiles, lane samples or horizon, or raise the limit";
    throw WorkloadError(msg.str());
  }
  pb.co_object_of.resize(offset);
  for (size_t o = 0; o < pb.cos.size(); ++o) {
    for (int j = pb.co_offset[o]; j < pb.co_offset[o + 1]; ++j)
      pb.co_object_of[j] = static_cast<int>(o);
  }
  return pb;
}

}  // namespace criticality::internal
