#include "src/risk_assessment.h"

#include <algorithm>
#include <utility>
#include <vector>

#include "core/chronological_risk.h"
#include "core/two_track.h"
#include "src/parallel_for.h"

namespace criticality::internal {

void AssessRisk(const Problem& pb, const Params& params, const std::int16_t* first_step,
                int threads, Result* result) {
  const int n_ego = pb.EgoTrajectories();
  const int n_co = pb.CoTrajectories();
  const int steps = pb.Steps();
  const int n_obj = static_cast<int>(pb.cos.size());

  // Per ego hypothesis: its collision probability and how it splits over steps and objects
  // (not yet weighted by p_EGO). Rows are independent, so threads write disjoint rows.
  std::vector<double> ego_col(n_ego, 0.0);
  std::vector<char> ego_hit(n_ego, 0);
  std::vector<double> by_step(static_cast<size_t>(n_ego) * steps, 0.0);
  std::vector<double> by_object(static_cast<size_t>(n_ego) * n_obj, 0.0);
  ParallelFor(n_ego, threads, [&](int begin, int end) {
    std::vector<int> histogram(steps + 1), events(n_co);
    std::vector<double> contribution(n_co), hit_mass(n_obj);
    for (int i = begin; i < end; ++i) {
      int n_events = 0;
      ego_col[i] = core::SplitEgoRisk(first_step + static_cast<size_t>(i) * n_co, n_co, steps,
                                      n_obj, pb.co_probability.data(), pb.co_object_of.data(),
                                      histogram.data(), events.data(), contribution.data(),
                                      hit_mass.data(), &by_step[static_cast<size_t>(i) * steps],
                                      &by_object[static_cast<size_t>(i) * n_obj], &n_events);
      ego_hit[i] = n_events > 0;
    }
  });

  result->p_collision = 0.0;
  result->first_collision_pmf.assign(steps, 0.0);
  result->objects = pb.objects;
  for (ObjectResult& o : result->objects) o.contribution = 0.0;
  for (int i = 0; i < n_ego; ++i) {
    if (!ego_hit[i]) continue;
    const double p = pb.ego_probability[i];
    result->p_collision += p * ego_col[i];
    for (int n = 0; n < steps; ++n) {
      result->first_collision_pmf[n] += p * by_step[static_cast<size_t>(i) * steps + n];
    }
    for (int o = 0; o < n_obj; ++o) {
      result->objects[o].contribution += p * by_object[static_cast<size_t>(i) * n_obj + o];
    }
  }
  result->ego_probability = pb.ego_probability;
  result->ego_collision_probability = ego_col;

  FillEscapeRoutes(pb, params, ego_hit, result);
}

void FillEscapeRoutes(const Problem& pb, const Params& params, const std::vector<char>& ego_hit,
                      Result* result) {
  const int n_ego = pb.EgoTrajectories();
  // Ego hypotheses that collide with no CO hypothesis, most probable first.
  std::vector<int> free;
  for (int i = 0; i < n_ego; ++i) {
    if (!ego_hit[i]) free.push_back(i);
  }
  result->collision_free_ego_trajectories = static_cast<int>(free.size());
  std::stable_sort(free.begin(), free.end(),
                   [&](int a, int b) { return pb.ego_probability[a] > pb.ego_probability[b]; });
  if (static_cast<int>(free.size()) > params.max_escape_routes)
    free.resize(params.max_escape_routes);
  result->escape_routes.clear();
  for (int i : free) {
    EscapeRoute r;
    r.ego_trajectory = i;
    r.profile = i / pb.ego.n_paths;
    r.profile_slip = pb.ego.profile_target[r.profile];
    r.profile_accel_mps2 = core::AccelFromSlip(pb.ego.vehicle, r.profile_slip);
    for (int k = 0; k < pb.ego.n_instants; ++k) {
      r.sections.push_back(core::SectionOfPath(pb.ego, i % pb.ego.n_paths, k));
    }
    r.probability = pb.ego_probability[i];
    result->escape_routes.push_back(std::move(r));
  }
}

}  // namespace criticality::internal
