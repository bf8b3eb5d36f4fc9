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
  const double v_seam = ego.seam_speed;
  const double turn_kinematic =
      v_seam * v_seam * std::tan(sim.controller.max_steer_rad) / wheelbase;
  const double a_later = std::sqrt(mu_g * mu_g + turn_kinematic * turn_kinematic);
  const double a_first = std::hypot(ego.accel0, ego.v0 * ego.yaw_rate0);
  std::vector<double> bound(sim.n_steps + 1, 0.0);
  double v = ego.v0;
  // A simulator's Euler update shifts each pose along the course by (v - v0) * lead, and
  // |v - v0| grows by at most the largest acceleration per step.
  const double dv_max = std::max(a_first, a_later) * tau;
  for (int n = 0; n < sim.n_steps; ++n) {
    const double a = n == 0 ? a_first : a_later;
    bound[n + 1] = bound[n] + v * tau + a * 0.5 * tau * tau;
    v += mu_g * tau;
  }
  for (int n = 1; n <= sim.n_steps; ++n) bound[n] += dv_max * n * ego.position_lead;
  return bound;
}

std::vector<char> OutOfReach(const Problem& pb) {
  const std::vector<double> bound = EgoReachBound(pb.ego, pb.sim);
  const double ego_r = core::BoundingRadius(pb.ego.half_length, pb.ego.half_width);
  const double x0 = pb.ego.X_WL.x, y0 = pb.ego.X_WL.y;
  const int steps = pb.sim.n_steps;
  std::vector<char> out(pb.cos.size(), 0);
  std::vector<double> x(steps), y(steps), yaw(steps);
  for (size_t o = 0; o < pb.cos.size(); ++o) {
    const core::HypothesisSet& h = pb.cos[o];
    const double r = ego_r + core::BoundingRadius(h.half_length, h.half_width) + kMarginM;
    // Starting within the ego's final reach: kept without simulating (it would be, or nearly).
    if (std::hypot(h.X_WL.x - x0, h.X_WL.y - y0) <= bound[steps] + r) continue;
    bool reachable = false;
    for (int t = 0; t < h.Trajectories() && !reachable; ++t) {
      core::SimulateHypothesis(h, pb.sim, t / h.n_paths, t % h.n_paths, x.data(), y.data(),
                               yaw.data());
      for (int n = 0; n < steps; ++n) {  // pose n is after n + 1 steps
        if (!(std::hypot(x[n] - x0, y[n] - y0) > bound[n + 1] + r)) {
          reachable = true;
          break;
        }
      }
    }
    out[o] = reachable ? 0 : 1;
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
  int offset = 0;
  for (size_t o = 0; o < pb.cos.size(); ++o) {
    if (drop[o]) continue;
    const int first = pb.co_offset[o], count = pb.co_offset[o + 1] - first;
    out.cos.push_back(pb.cos[o]);
    ObjectResult info = pb.objects[o];
    info.first_trajectory = offset;
    out.objects.push_back(info);
    out.co_probability.insert(out.co_probability.end(), pb.co_probability.begin() + first,
                              pb.co_probability.begin() + first + count);
    for (int j = 0; j < count; ++j)
      out.co_object_of.push_back(static_cast<int>(out.cos.size()) - 1);
    offset += count;
    out.co_offset.push_back(offset);
  }
  out.counts = pb.counts;
  out.counts.co_trajectories = offset;
  out.counts.pose_combinations = static_cast<std::uint64_t>(out.counts.ego_trajectories) *
                                 static_cast<std::uint64_t>(offset) *
                                 static_cast<std::uint64_t>(out.sim.n_steps);
  return out;
}

}  // namespace criticality::internal
