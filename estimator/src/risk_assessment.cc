#include "src/risk_assessment.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "core/chronological_risk.h"
#include "core/trajectory_generation.h"
#include "src/parallel_for.h"

namespace criticality::internal {

void AssessRisk(const Problem& pb, const Params& params, const std::int16_t* first_step,
                int threads, Result* result) {
  const int n_ego = pb.EgoTrajectories();
  const int n_co = pb.CoTrajectories();
  const int steps = pb.Steps();
  const int n_obj = static_cast<int>(pb.cos.size());

  // Per ego hypothesis: its collision probability and how it splits over steps and objects
  // (not yet weighted by p_EGO). Each chunk of rows keeps its rows' nonzero shares, in row
  // order, under its first row (no matrix of rows x steps to allocate and clear); adding them
  // up chunk after chunk then adds every sum's terms in row order, whatever the thread count.
  struct Share {
    int row, index;  // index: a step, or steps + an object
    double value;
  };
  std::vector<double> ego_col(n_ego, 0.0);
  std::vector<char> ego_hit(n_ego, 0);
  std::vector<std::vector<Share>> shares(n_ego);
  ParallelFor(n_ego, threads, [&](int begin, int end) {
    std::vector<int> histogram(steps + 1), events(n_co);
    std::vector<double> contribution(n_co), hit_mass(n_obj), by_step(steps), by_object(n_obj);
    std::vector<Share>& out = shares[begin];
    // The last row with a hit, and where its shares begin in `out`: a row equal to it (the
    // paths of a still subtree, cpu/cpu_backend.h, share every entry) has the same split.
    int last = -1;
    size_t last_out = 0;
    for (int i = begin; i < end; ++i) {
      const std::int16_t* row = first_step + static_cast<size_t>(i) * n_co;
      if (std::all_of(row, row + n_co, [](std::int16_t s) { return s == 0; })) continue;
      if (last >= 0 && std::equal(row, row + n_co, first_step + static_cast<size_t>(last) * n_co)) {
        ego_col[i] = ego_col[last];
        ego_hit[i] = ego_hit[last];
        const size_t from = last_out, to = out.size();
        last_out = to;
        for (size_t k = from; k < to; ++k) out.push_back(Share{i, out[k].index, out[k].value});
        last = i;
        continue;
      }
      last = i;
      last_out = out.size();
      int n_events = 0;
      ego_col[i] = core::SplitEgoRisk(row, n_co, steps, n_obj, pb.co_probability.data(),
                                      pb.co_object_of.data(), histogram.data(), events.data(),
                                      contribution.data(), hit_mass.data(), by_step.data(),
                                      by_object.data(), &n_events);
      ego_hit[i] = n_events > 0;
      if (n_events == 0) continue;
      for (int n = 0; n < steps; ++n) {
        if (by_step[n] != 0.0) out.push_back(Share{i, n, by_step[n]});
      }
      for (int o = 0; o < n_obj; ++o) {
        if (by_object[o] != 0.0) out.push_back(Share{i, steps + o, by_object[o]});
      }
    }
  });

  result->p_collision = 0.0;
  result->first_collision_pmf.assign(steps, 0.0);
  result->objects = pb.objects;
  for (ObjectResult& o : result->objects) o.contribution = 0.0;
  for (int i = 0; i < n_ego; ++i) {
    if (ego_hit[i]) result->p_collision += pb.ego_probability[i] * ego_col[i];
  }
  for (const std::vector<Share>& chunk : shares) {
    for (const Share& s : chunk) {
      const double p = pb.ego_probability[s.row];
      if (s.index < steps) {
        result->first_collision_pmf[s.index] += p * s.value;
      } else {
        result->objects[s.index - steps].contribution += p * s.value;
      }
    }
  }
  result->ego_probability = pb.ego_probability;
  result->ego_collision_probability = ego_col;

  FinishDecisionOutputs(pb, params, ego_hit, result);
}

void AssessBodies(const Problem& pb, const Params& params, std::vector<std::int16_t>* first_step,
                  int threads, Result* result) {
  if (!pb.HasCarriages()) {
    AssessRisk(pb, params, first_step->data(), threads, result);
    return;
  }
  *first_step = FoldCarriages(pb, *first_step);
  AssessRisk(ObjectProblem(pb), params, first_step->data(), threads, result);
}

void FinishDecisionOutputs(const Problem& pb, const Params& params,
                           const std::vector<char>& ego_hit, Result* result) {
  const int n_ego = pb.EgoTrajectories();
  // A sum of probabilities that is 1 in exact arithmetic (every hypothesis colliding) may round
  // a few units in the last place above it: probabilities are reported within [0, 1].
  for (double& c : result->ego_collision_probability) c = std::min(c, 1.0);
  result->p_collision = std::min(result->p_collision, 1.0);
  const std::vector<double>& col = result->ego_collision_probability;
  result->reference_ego_trajectory = pb.ego_reference_trajectory;
  result->p_reference = n_ego > 0 ? col[pb.ego_reference_trajectory] : 0.0;
  result->unavoidability = n_ego > 0 ? *std::min_element(col.begin(), col.end()) : 0.0;
  result->collision_free_ego_trajectories =
      static_cast<int>(std::count(ego_hit.begin(), ego_hit.end(), char{0}));

  // Escape routes: lowest collision probability first, then most probable, then by index.
  std::vector<int> order(n_ego);
  for (int i = 0; i < n_ego; ++i) order[i] = i;
  const size_t keep = std::min<size_t>(order.size(), static_cast<size_t>(params.max_escape_routes));
  std::partial_sort(order.begin(), order.begin() + keep, order.end(), [&](int a, int b) {
    if (col[a] != col[b]) return col[a] < col[b];
    if (pb.ego_probability[a] != pb.ego_probability[b])
      return pb.ego_probability[a] > pb.ego_probability[b];
    return a < b;
  });
  result->escape_routes.clear();
  const int steps = pb.Steps();
  std::vector<double> x(steps), y(steps), yaw(steps), steer(steps);
  std::vector<core::MotionState> state(steps);
  // The manoeuvre as driven: an ego that leaves the scene at the end of its route (Params::
  // route_end_leaves) still has a place on the road to report.
  core::HypothesisSet driven = pb.ego;
  driven.leave_distance = HUGE_VAL;
  for (size_t r = 0; r < keep; ++r) {
    const int i = order[r];
    EscapeRoute e;
    e.ego_trajectory = i;
    e.profile = i / pb.ego.n_paths;
    e.profile_slip = pb.ego_profile_slip[e.profile];
    e.profile_accel_mps2 = pb.ego_profile_accel[e.profile];
    for (int k = 0; k < pb.ego.n_instants; ++k) {
      const int section = core::SectionOfPath(pb.ego, i % pb.ego.n_paths, k);
      e.sections.push_back(section);
      e.target_lanes.push_back(pb.ego_sample_lane[section]);
    }
    e.probability = pb.ego_probability[i];
    e.collision_probability = col[i];
    core::StepTrace trace{state.data(), steer.data()};
    core::SimulateHypothesis(driven, pb.sim, e.profile, i % pb.ego.n_paths, x.data(), y.data(),
                             yaw.data(), 1, &trace);
    for (int n = 0; n < steps; ++n) {
      const core::MotionState& s = state[n];
      e.time_s.push_back((n + 1) * pb.sim.tau);
      e.speed_mps.push_back(s.v);
      e.accel_mps2.push_back(s.ax);
      e.lateral_accel_mps2.push_back(s.ay);
      e.steer_rad.push_back(steer[n]);
      e.lateral_offset_m.push_back(-pb.ego_lane_centre.OffsetFrom(s.x, s.y));
    }
    e.x_m = x;
    e.y_m = y;
    e.yaw_rad = yaw;
    result->escape_routes.push_back(std::move(e));
  }
}

}  // namespace criticality::internal
