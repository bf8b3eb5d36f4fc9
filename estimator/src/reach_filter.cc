#include "src/reach_filter.h"

#include <algorithm>
#include <cmath>

#include "core/oriented_box.h"
#include "core/trajectory_generation.h"
#include "core/vehicle_params.h"

namespace criticality::internal {
namespace {

// Rounding between backends (and summation order) is far below a millimetre.
constexpr double kMarginM = 1e-3;

}  // namespace

std::vector<double> EgoReachBound(const core::HypothesisSet& ego,
                                  const core::SimulationConfig& sim) {
  const double tau = sim.tau;
  const double mu_g = ego.vehicle.friction * core::kGravity;
  const double wheelbase = ego.vehicle.lf_m + ego.vehicle.lr_m;
  // The kinematic model runs below the seam speed; an ego that is kinematic at every speed (a
  // bicycle, a rail vehicle) never gets faster than v0 + mu g T within the horizon.
  const double v_seam =
      std::isinf(ego.seam_speed) ? ego.v0 + mu_g * sim.n_steps * tau : ego.seam_speed;
  const double turn_kinematic =
      v_seam * v_seam * std::tan(sim.controller.max_steer_rad) / wheelbase;
  const double a_later = std::sqrt(mu_g * mu_g + turn_kinematic * turn_kinematic);
  const double a_first = std::hypot(ego.accel0, ego.v0 * ego.yaw_rate0);
  std::vector<double> bound(sim.n_steps + 1, 0.0);
  double v = ego.v0;
  // A simulator's Euler update shifts each pose along the course by (v - v0) * lead, and
  // |v - v0| grows by at most the largest acceleration per step.
  const double dv_max = std::max(a_first, a_later) * tau;
  // On a track (HypothesisSet::on_track) the centre keeps its offset d from the track, so it
  // covers up to (1 + |d| kappa) times the track's arc, kappa <= 2|a| on a parabola.
  const double stretch =
      ego.on_track ? 1.0 + std::fabs(ego.track_offset) * 2.0 * std::fabs(ego.reference_path.a)
                   : 1.0;
  for (int n = 0; n < sim.n_steps; ++n) {
    const double a = n == 0 ? a_first : a_later;
    bound[n + 1] = ego.on_track ? bound[n] + stretch * (v * tau + a * 0.5 * tau * tau)
                                : bound[n] + v * tau + a * 0.5 * tau * tau;
    v += mu_g * tau;
  }
  // A body on its path (HypothesisSet::body_on_path) starts its model centre up to c / 4
  // from its measured one and stores each pose up to c / 4 from its model centre.
  const double chord = ego.body_on_path && !ego.on_track ? ego.half_length : 0.0;
  for (int n = 1; n <= sim.n_steps; ++n) bound[n] += dv_max * n * ego.position_lead + chord;
  return bound;
}

std::vector<char> OutOfReach(const Problem& pb) {
  const std::vector<double> bound = EgoReachBound(pb.ego, pb.sim);
  const double ego_r = core::BoundingRadius(pb.ego.half_length, pb.ego.half_width);
  const double x0 = pb.ego.X_WL.x, y0 = pb.ego.X_WL.y;
  const int steps = pb.sim.n_steps;
  std::vector<double> x(steps), y(steps), yaw(steps);
  // Whether any hypothesis of set s can come near any ego hypothesis.
  auto reachable = [&](size_t s) {
    const core::HypothesisSet& h = pb.cos[s];
    const double r = ego_r + core::BoundingRadius(h.half_length, h.half_width) + kMarginM;
    // Starting within the ego's final reach: kept without simulating (it would be, or nearly).
    if (std::hypot(h.X_WL.x - x0, h.X_WL.y - y0) <= bound[steps] + r) return true;
    for (int t = 0; t < h.Trajectories(); ++t) {
      core::SimulateHypothesis(h, pb.sim, t / h.n_paths, t % h.n_paths, x.data(), y.data(),
                               yaw.data());
      for (int n = 0; n < steps; ++n) {  // pose n is after n + 1 steps
        if (!(std::hypot(x[n] - x0, y[n] - y0) > bound[n + 1] + r)) return true;
      }
    }
    return false;
  };
  // A body (a vehicle and its carriages) is out of reach only when none of its boxes can reach.
  std::vector<char> out(pb.objects.size(), 0);
  for (size_t o = 0; o < pb.objects.size(); ++o) out[o] = reachable(o) ? 0 : 1;
  for (size_t s = pb.objects.size(); s < pb.cos.size(); ++s) {
    const int o = pb.carriage_object[s - pb.objects.size()];
    if (out[o] && reachable(s)) out[o] = 0;
  }
  return out;
}

Problem WithoutObjects(const Problem& pb, const std::vector<char>& drop) {
  // Everything about the ego (and any field added later) is copied; only the collision
  // objects' parts are rebuilt.
  Problem out = pb;
  out.cos.clear();
  out.objects.clear();
  out.co_probability.clear();
  out.co_object_of.clear();
  out.co_offset.assign(1, 0);
  out.carriage_object.clear();
  int offset = 0;
  auto keep = [&](size_t s) {
    const int first = pb.co_offset[s], count = pb.co_offset[s + 1] - first;
    out.cos.push_back(pb.cos[s]);
    out.co_probability.insert(out.co_probability.end(), pb.co_probability.begin() + first,
                              pb.co_probability.begin() + first + count);
    for (int j = 0; j < count; ++j)
      out.co_object_of.push_back(static_cast<int>(out.cos.size()) - 1);
    offset += count;
    out.co_offset.push_back(offset);
  };
  std::vector<int> new_index(pb.objects.size(), -1);
  for (size_t o = 0; o < pb.objects.size(); ++o) {
    if (drop[o]) continue;
    new_index[o] = static_cast<int>(out.objects.size());
    ObjectResult info = pb.objects[o];
    info.first_trajectory = offset;
    out.objects.push_back(info);
    keep(o);
  }
  // A kept body keeps its carriages; a dropped one drops them.
  for (size_t s = pb.objects.size(); s < pb.cos.size(); ++s) {
    const int o = pb.carriage_object[s - pb.objects.size()];
    if (drop[o]) continue;
    out.carriage_object.push_back(new_index[o]);
    keep(s);
  }
  out.counts = pb.counts;
  out.counts.co_trajectories = offset;
  out.counts.pose_combinations = static_cast<std::uint64_t>(out.counts.ego_trajectories) *
                                 static_cast<std::uint64_t>(offset) *
                                 static_cast<std::uint64_t>(out.sim.n_steps);
  return out;
}

}  // namespace criticality::internal
