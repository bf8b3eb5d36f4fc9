#include "src/problem.h"

#include <cmath>
#include <sstream>
#include <string>

#include "core/geometry.h"
#include "core/one_track.h"
#include "core/profiles.h"
#include "core/scoring.h"
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
};

// Lateral samples right to left: neighbour_lane_samples across the right lane, own_lane_samples
// across the own lane, neighbour_lane_samples across the left lane, each equally distributed
// over its lane's width (fractions i / (n + 1)).
std::vector<LateralSample> LateralSamples(const FittedLanes& lanes, const Params& p) {
  std::vector<LateralSample> out;
  auto add = [&](const std::optional<FittedLane>& lane, int n) {
    if (!lane) return;
    for (int i = 1; i <= n; ++i) {
      out.push_back({lane->At(static_cast<double>(i) / (n + 1)), lane->counter_traffic});
    }
  };
  add(lanes.right, p.neighbour_lane_samples);
  add(lanes.own, p.own_lane_samples);
  add(lanes.left, p.neighbour_lane_samples);
  return out;
}

// Distance the reference trajectory (current acceleration, never reversing) covers by time t.
double ReferenceDistance(double v0, double a0, double t) {
  if (a0 < 0.0 && v0 + a0 * t < 0.0) return v0 * v0 / (2.0 * -a0);
  return v0 * t + 0.5 * a0 * t * t;
}

core::VehicleParams VehicleModelParams(double length, double width, std::optional<double> height,
                                       const Params& p) {
  core::VehicleParams vp = VehicleParamsFor(ClassifyVehicle(length, width, height), length, width);
  vp.friction = p.friction;
  vp.kinematic_below_mps = p.kinematic_below_mps;
  return vp;
}

void SetPose(const ObjectState& s, double length, double width, core::HypothesisSet* h) {
  h->X_WL = core::Pose2{s.x_m, s.y_m, s.yaw_rad};
  h->v0 = s.speed_mps;
  h->beta0 = s.sideslip_rad;
  h->yaw_rate0 = s.yaw_rate_radps;
  h->accel0 = s.accel_mps2;
  h->half_length = 0.5 * length;
  h->half_width = 0.5 * width;
}

// Fills the lateral part of a vehicle's hypothesis set and returns one score factor per path:
// d_str / (c_com * c_cou) split as {d_str, c_com * c_cou}.
struct PathScore {
  double d_str{1.0};
  double penalty{1.0};
};

std::vector<PathScore> SetPaths(const FittedLanes& lanes, const Params& p, bool combine,
                                core::HypothesisSet* h) {
  const std::vector<LateralSample> samples = LateralSamples(lanes, p);
  const int n_lat = static_cast<int>(samples.size());
  const int n_inst = static_cast<int>(p.path_sample_times_s.size());
  h->n_instants = n_inst;
  h->n_lateral = n_lat;
  h->combine_sections = combine;
  for (int k = 0; k < n_inst; ++k) {
    h->instant_time[k] = p.path_sample_times_s[k];
    for (int l = 0; l < n_lat; ++l) h->section[k][l] = samples[l].curve;
  }
  int n_paths = n_lat;
  if (combine) {
    n_paths = 1;
    for (int k = 0; k < n_inst; ++k) n_paths *= n_lat;
  }
  h->n_paths = n_paths;

  // Offsets of each sample from the own lane's centre where the reference trajectory is at
  // each sample instant.
  const core::Parabola centre = lanes.own->Centre();
  std::vector<double> offset(static_cast<size_t>(n_inst) * n_lat);
  for (int k = 0; k < n_inst; ++k) {
    const double x = ReferenceDistance(h->v0, h->accel0, p.path_sample_times_s[k]);
    for (int l = 0; l < n_lat; ++l) {
      offset[k * n_lat + l] = std::fabs(samples[l].curve.Eval(x) - centre.Eval(x));
    }
  }
  std::vector<PathScore> scores(n_paths);
  for (int path = 0; path < n_paths; ++path) {
    double mean = 0.0;
    int changes = 0;
    bool counter = false;
    for (int k = 0; k < n_inst; ++k) {
      const int l = core::SectionOfPath(*h, path, k);
      mean += offset[k * n_lat + l];
      counter = counter || samples[l].counter_traffic;
      if (k > 0 && l != core::SectionOfPath(*h, path, k - 1)) ++changes;
    }
    mean /= n_inst;
    scores[path].d_str = core::DeviationScore(mean, p.path_score_scale_m);
    scores[path].penalty =
        (1.0 + p.complexity_penalty * changes) * (counter ? p.counter_traffic_penalty : 1.0);
  }
  return scores;
}

// Scores every (profile, path) hypothesis and L1-normalises them into probabilities.
void AppendProbabilities(const std::vector<double>& n_acc, const std::vector<PathScore>& paths,
                         const Params& p, std::vector<double>* out) {
  const size_t first = out->size();
  double sum = 0.0;
  for (double na : n_acc) {
    for (const PathScore& ps : paths) {
      const double score = core::HypothesisScore(p.w_acc, na, p.w_str, ps.d_str, ps.penalty, 1.0);
      out->push_back(score);
      sum += score;
    }
  }
  for (size_t i = first; i < out->size(); ++i) (*out)[i] /= sum;
}

void SetVehicleProfiles(const Params& p, core::HypothesisSet* h, std::vector<double>* n_acc) {
  h->n_profiles = p.profiles;
  h->latency = p.latency_s;
  const bool ego = h->model == core::MotionModelKind::kTwoTrack;
  const double lo = ego ? p.ego_slip_min : p.vehicle_accel_min_mps2;
  const double hi = ego ? p.ego_slip_max : p.vehicle_accel_max_mps2;
  h->profile_start = ego ? core::SlipFromAccel(h->vehicle, h->accel0) : h->accel0;
  h->rate = ego ? p.ego_slip_max * p.jerk_mps3 / p.vehicle_accel_max_mps2 : p.jerk_mps3;
  const double scale = p.accel_score_scale * std::fmax(std::fabs(lo), std::fabs(hi));
  for (int k = 0; k < p.profiles; ++k) {
    h->profile_target[k] = core::VehicleProfileTarget(k, p.profiles, lo, hi);
    n_acc->push_back(core::DeviationScore(h->profile_target[k] - h->profile_start, scale));
  }
}

}  // namespace

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
  pb.sim.controller =
      core::ControllerLimits{params.max_steer_rad, params.max_steer_rate_radps,
                             params.preview_s_per_mps, params.preview_min_s, params.preview_max_s};

  // Street data: the ego's lanes (virtual own lane when missing), fitted in its frame.
  const LaneSet ego_lanes = CompleteEgoLanes(scene.ego, params);
  const FittedLanes ego_fitted = FitLanes(ego_lanes, "scene.ego.lanes");

  // The ego: two-track model, every combination of path sections.
  {
    core::HypothesisSet& h = pb.ego;
    h.model = core::MotionModelKind::kTwoTrack;
    SetPose(scene.ego.state, scene.ego.length_m, scene.ego.width_m, &h);
    h.vehicle =
        VehicleModelParams(scene.ego.length_m, scene.ego.width_m, scene.ego.height_m, params);
    h.seam_speed = core::SeamSpeed(h.vehicle, params.step_s, params.euler_stability_factor);
    std::vector<double> n_acc;
    SetVehicleProfiles(params, &h, &n_acc);
    const std::vector<PathScore> paths = SetPaths(ego_fitted, params, /*combine=*/true, &h);
    AppendProbabilities(n_acc, paths, params, &pb.ego_probability);
  }

  const core::Pose2 X_WE{scene.ego.state.x_m, scene.ego.state.y_m, scene.ego.state.yaw_rad};
  int offset = 0;
  pb.co_offset.push_back(0);
  for (size_t i = 0; i < scene.vehicles.size(); ++i) {
    const Vehicle& v = scene.vehicles[i];
    const std::string where = "scene.vehicles[" + std::to_string(i) + "]";
    core::HypothesisSet h;
    h.model = core::MotionModelKind::kOneTrack;
    SetPose(v.state, v.length_m, v.width_m, &h);
    h.vehicle = VehicleModelParams(v.length_m, v.width_m, v.height_m, params);
    h.seam_speed = core::SeamSpeed(h.vehicle, params.step_s, params.euler_stability_factor);
    ObjectResult info;
    info.id = v.id;
    info.kind = ObjectKind::kVehicle;
    info.lane = static_cast<int>(LaneIndex::kNone);
    // Associate by centre of gravity with the ego's lanes, if it drives along them (within
    // 45 deg either way). Without lanes of its own it then uses the ego's lanes seen from its
    // frame; crossing traffic without lanes of its own gets a virtual lane.
    core::Pose2 X_EV;
    core::WorldToLocal(X_WE, v.state.x_m, v.state.y_m, &X_EV.x, &X_EV.y);
    X_EV.yaw = core::WrapAngle(v.state.yaw_rad - X_WE.yaw);
    const LaneIndex lane = std::fabs(std::cos(X_EV.yaw)) >= std::cos(core::kPi / 4)
                               ? AssociateLane(ego_fitted, X_EV.x, X_EV.y)
                               : LaneIndex::kNone;
    info.lane = static_cast<int>(lane);
    LaneSet lanes = v.lanes ? *v.lanes : EgoLanesSeenBy(ego_lanes, X_EV, lane);
    if (!lanes.own) lanes.own = VirtualLane(v.state, params.virtual_lane_width_m);
    const FittedLanes fitted = FitLanes(lanes, where + ".lanes");
    std::vector<double> n_acc;
    SetVehicleProfiles(params, &h, &n_acc);
    const std::vector<PathScore> paths = SetPaths(fitted, params, /*combine=*/false, &h);
    AppendProbabilities(n_acc, paths, params, &pb.co_probability);
    info.first_trajectory = offset;
    info.trajectories = h.Trajectories();
    offset += info.trajectories;
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
    const double scale =
        params.accel_score_scale * std::fmax(std::fabs(params.pedestrian_accel_min_mps2),
                                             std::fabs(params.pedestrian_accel_max_mps2));
    std::vector<double> n_acc;
    for (int k = 0; k < h.n_profiles; ++k) {
      h.profile_target[k] = core::EquallySpaced(k, h.n_profiles, params.pedestrian_accel_min_mps2,
                                                params.pedestrian_accel_max_mps2);
      n_acc.push_back(core::DeviationScore(h.profile_target[k] - h.accel0, scale));
    }
    std::vector<PathScore> headings(h.n_paths);
    for (int l = 0; l < h.n_paths; ++l) {
      const double turn = core::WrapAngle(2.0 * core::kPi * l / h.n_paths);
      h.heading[l] = ped.state.yaw_rad + turn;
      headings[l].d_str = core::DeviationScore(turn, params.heading_score_scale_rad);
    }
    AppendProbabilities(n_acc, headings, params, &pb.co_probability);
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
