#include "src/reach_filter.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "core/oriented_box.h"
#include "core/trajectory_generation.h"
#include "core/vehicle_params.h"
#include "cpu/object_paths_cache.h"
#include "cpu/sibling_steps.h"

namespace criticality::internal {
namespace {

// Rounding between backends (and summation order) is far below a millimetre.
constexpr double kMarginM = 1e-3;

}  // namespace

std::vector<double> EgoReachBound(const core::HypothesisSet& ego,
                                  const core::SimulationConfig& sim) {
  return EgoReachBoundFrom(ego, sim, ego.v0, std::hypot(ego.accel0, ego.v0 * ego.yaw_rate0),
                           sim.n_steps);
}

namespace {

// What the bound is made of (EgoReachBoundFrom).
struct ReachTerms {
  double mu_g, a_first, a_later, dv_max, stretch, turned, chord, way;
};

ReachTerms TermsOf(const core::HypothesisSet& ego, const core::SimulationConfig& sim,
                   double v_start, double accel) {
  ReachTerms t;
  t.mu_g = ego.vehicle.friction * core::kGravity;
  const double wheelbase = ego.vehicle.lf_m + ego.vehicle.lr_m;
  // The kinematic model runs below the seam speed; an ego that is kinematic at every speed (a
  // bicycle, a rail vehicle) never gets faster than v0 + mu g T within the horizon.
  const double v_seam =
      std::isinf(ego.seam_speed) ? ego.v0 + t.mu_g * sim.n_steps * sim.tau : ego.seam_speed;
  const double turn_kinematic =
      v_seam * v_seam * std::tan(sim.controller.max_steer_rad) / wheelbase;
  t.a_later = std::sqrt(t.mu_g * t.mu_g + turn_kinematic * turn_kinematic);
  t.a_first = accel;
  // A simulator's Euler update shifts each pose along the course by (v - v0) * lead, and
  // |v - v0| grows by at most the largest acceleration per step.
  t.dv_max = std::max(t.a_first, t.a_later) * sim.tau;
  // On a track (HypothesisSet::on_track) the centre keeps its offset d from the track, so it
  // covers up to (1 + |d| kappa) times the track's arc, kappa <= 2|a| on a parabola.
  t.stretch = ego.on_track
                  ? 1.0 + std::fabs(ego.track_offset) * 2.0 * std::fabs(ego.reference_path.a)
                  : 1.0;
  // From a later state the shift already in its pose, (v - v0) lead along its course, may turn
  // with the course: at most twice its length.
  t.turned = 2.0 * std::fabs(v_start - ego.v0) * ego.position_lead;
  // A body on its path (HypothesisSet::body_on_path) starts its model centre up to c / 4
  // from its measured one and stores each pose up to c / 4 from its model centre.
  t.chord = ego.body_on_path && !ego.on_track ? ego.half_length : 0.0;
  // On its way (HypothesisSet::on_way) its front moves along the way by each step's distance
  // (at most the bound's travel); its centre, half its length behind the front along its
  // heading and then moved by its offset from the way (at most |(way_dx, way_dy)| plus the
  // largest sideways offset a path asks), may turn about the front: at most twice both.
  t.way = 0.0;
  if (ego.on_way) {
    double side = 0.0;
    for (int k = 0; k < ego.n_instants && k < core::kMaxSampleInstants; ++k) {
      for (int l = 0; l < ego.n_lateral && l < core::kMaxLateralSamples; ++l)
        side = std::max(side, std::fabs(ego.way_lateral[k][l]));
    }
    t.way = 2.0 * (ego.half_length + std::hypot(ego.way_dx, ego.way_dy) + side);
  }
  return t;
}

}  // namespace

std::vector<double> EgoReachBoundFrom(const core::HypothesisSet& ego,
                                      const core::SimulationConfig& sim, double v_start,
                                      double accel, int steps) {
  const double tau = sim.tau;
  const ReachTerms t = TermsOf(ego, sim, v_start, accel);
  std::vector<double> bound(steps + 1, 0.0);
  double v = v_start;
  for (int n = 0; n < steps; ++n) {
    const double a = n == 0 ? t.a_first : t.a_later;
    bound[n + 1] = bound[n] + t.stretch * (v * tau + a * 0.5 * tau * tau);
    v += t.mu_g * tau;
  }
  for (int n = 1; n <= steps; ++n)
    bound[n] += t.dv_max * n * ego.position_lead + t.turned + t.chord + t.way;
  return bound;
}

double EgoReachAfter(const core::HypothesisSet& ego, const core::SimulationConfig& sim,
                     double v_start, double accel, int steps) {
  if (steps <= 0) return 0.0;
  const double tau = sim.tau, m = steps;
  const ReachTerms t = TermsOf(ego, sim, v_start, accel);
  // sum_{n<m} (v + mu g n tau) tau + (a_first + (m - 1) a_later) tau^2 / 2
  const double travel = v_start * m * tau + t.mu_g * tau * tau * m * (m - 1.0) / 2.0 +
                        (t.a_first + (m - 1.0) * t.a_later) * 0.5 * tau * tau;
  return t.stretch * travel + t.dv_max * m * ego.position_lead + t.turned + t.chord + t.way;
}

std::vector<char> OutOfReach(const Problem& pb, bool simd, ObjectPathsCache* cache) {
  const std::vector<double> bound = EgoReachBound(pb.ego, pb.sim);
  const double ego_r = core::BoundingRadius(pb.ego.half_length, pb.ego.half_width);
  const double x0 = pb.ego.X_WL.x, y0 = pb.ego.X_WL.y;
  const int steps = pb.sim.n_steps;
  std::vector<double> x(steps), y(steps), yaw(steps);
  std::vector<double> lx, ly, lyaw;  // the paths of one profile in SIMD lanes
  // Whether any hypothesis of set s can come near any ego hypothesis.
  auto reachable = [&](size_t s) {
    const core::HypothesisSet& h = pb.cos[s];
    const double r = ego_r + core::BoundingRadius(h.half_length, h.half_width) + kMarginM;
    // Starting within the ego's final reach: kept without simulating (it would be, or nearly).
    if (std::hypot(h.X_WL.x - x0, h.X_WL.y - y0) <= bound[steps] + r) return true;
    auto near = [&](const double* px, const double* py) {
      for (int n = 0; n < steps; ++n) {  // pose n is after n + 1 steps
        const double dx = px[n] - x0, dy = py[n] - y0, reach = bound[n + 1] + r;
        if (!(dx * dx + dy * dy > reach * reach)) return true;  // squared: no libm per pose
      }
      return false;
    };
    if (simd && cache && SiblingStepsApply(h, pb.sim)) {
      // Another scene of the batch may have stored the set's paths; else, while the cache has
      // room, they are simulated whole and stored, for the backend and the other scenes to copy
      // (without room: profile by profile below, stopping at the first that comes near).
      std::string key = ObjectPathsCache::KeyOf(h, pb.sim, 1);
      std::shared_ptr<const ObjectPathsCache::Paths> paths = cache->Find(key);
      if (!paths && cache->HasRoom(h.Trajectories(), steps)) {
        paths = SimulateLanePaths(h, pb.sim);
        cache->Store(std::move(key), paths);
      }
      if (paths) {
        for (int t = 0; t < h.Trajectories(); ++t) {
          const size_t at = static_cast<size_t>(t) * steps;
          if (near(&paths->x[at], &paths->y[at])) return true;
        }
        return false;
      }
    }
    if (simd && SiblingStepsApply(h, pb.sim)) {
      // The paths of each profile together, as the CPU backend simulates them (within 1e-9 m
      // of the scalar poses, far inside the margin).
      const size_t n = static_cast<size_t>(h.n_paths) * steps;
      lx.resize(n);
      ly.resize(n);
      lyaw.resize(n);
      for (int profile = 0; profile < h.n_profiles; ++profile) {
        SimulateProfilePaths(h, pb.sim, profile, lx.data(), ly.data(), lyaw.data(), steps);
        for (int path = 0; path < h.n_paths; ++path) {
          const size_t at = static_cast<size_t>(path) * steps;
          if (near(&lx[at], &ly[at])) return true;
        }
      }
      return false;
    }
    for (int t = 0; t < h.Trajectories(); ++t) {
      core::SimulateHypothesis(h, pb.sim, t / h.n_paths, t % h.n_paths, x.data(), y.data(),
                               yaw.data());
      if (near(x.data(), y.data())) return true;
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
