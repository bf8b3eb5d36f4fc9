#pragma once
// The per-thread bodies of the CUDA backend's kernels, as plain CRIT_HD functions: the kernels
// (cuda_backend.cu) only compute their index and call these. Because they are ordinary C++,
// tests run them on the CPU over every index, with the device's data layout, and compare with
// the CPU backend (tests/estimator/cuda/kernel_bodies_test.cc) — so the GPU path's logic is
// checked even on machines without a GPU.
//
// Layouts: poses step-major, x[n * count + t]; pair matrix ego-major, [i * n_co + j].
#include <cstddef>
#include <cstdint>

#include "core/chronological_risk.h"
#include "core/hd.h"
#include "core/hypothesis_set.h"
#include "core/oriented_box.h"
#include "core/trajectory_generation.h"

namespace criticality::cuda {

struct Poses {
  const double* x;
  const double* y;
  const double* c;
  const double* s;
};

struct RiskScratch {
  int* histogram;    ///< n_ego x (steps + 1)
  int* events;       ///< n_ego x n_co
  double* contrib;   ///< n_ego x n_co
  double* hit_mass;  ///< n_ego x n_obj
};

/** Thread g < n_ego: ego hypothesis g; else CO trajectory g - n_ego. sets[0] is the ego's,
 *  sets[1 + o] CO o's. */
CRIT_HD void TrajectoryBody(int g, const core::HypothesisSet* sets, const int* co_object_of,
                            const int* co_offset, int n_ego, int n_co,
                            const core::SimulationConfig& cfg, double* ex, double* ey, double* eyaw,
                            double* cx, double* cy, double* cyaw) {
  if (g < n_ego) {
    const core::HypothesisSet& h = sets[0];
    core::SimulateHypothesis(h, cfg, g / h.n_paths, g % h.n_paths, ex + g, ey + g, eyaw + g, n_ego);
  } else if (g < n_ego + n_co) {
    const int j = g - n_ego;
    const int o = co_object_of[j];
    const core::HypothesisSet& h = sets[1 + o];
    const int t = j - co_offset[o];
    core::SimulateHypothesis(h, cfg, t / h.n_paths, t % h.n_paths, cx + j, cy + j, cyaw + j, n_co);
  }
}

CRIT_HD void TrigBody(size_t k, const double* yaw, double* c, double* s) {
  c[k] = std::cos(yaw[k]);
  s[k] = std::sin(yaw[k]);
}

/** Thread k = i * n_co + j: the first colliding step (1-based, 0 = none) of ego trajectory i
 *  and CO trajectory j, with a bounding-circle test before the exact one and early exit. */
CRIT_HD void CollisionBody(size_t k, int n_ego, int n_co, int steps, const Poses& ego,
                           const Poses& co, double ego_hl, double ego_hw, const double* co_hl,
                           const double* co_hw, std::int16_t* first) {
  const int i = static_cast<int>(k / n_co), j = static_cast<int>(k % n_co);
  const double reach =
      core::BoundingRadius(ego_hl, ego_hw) + core::BoundingRadius(co_hl[j], co_hw[j]) + 1e-9;
  const double reach2 = reach * reach;
  std::int16_t hit = 0;
  for (int n = 0; n < steps; ++n) {
    const size_t a = static_cast<size_t>(n) * n_ego + i, b = static_cast<size_t>(n) * n_co + j;
    const double dx = co.x[b] - ego.x[a], dy = co.y[b] - ego.y[a];
    if (dx * dx + dy * dy > reach2) continue;
    const core::OrientedBox<double> ba{ego.x[a], ego.y[a], ego.c[a], ego.s[a], ego_hl, ego_hw};
    const core::OrientedBox<double> bb{co.x[b], co.y[b], co.c[b], co.s[b], co_hl[j], co_hw[j]};
    if (core::BoxesOverlap(ba, bb)) {
      hit = static_cast<std::int16_t>(n + 1);
      break;
    }
  }
  first[k] = hit;
}

/** Thread i: ego hypothesis i's colliding CO trajectories in chronological order (counting
 *  sort by step, stable in j), the paper's chronological approximation, and its split over
 *  steps and objects (not yet weighted by p_EGO). */
CRIT_HD void RiskBody(int i, int n_co, int steps, int n_obj, const std::int16_t* first,
                      const double* p_co, const int* object_of, const RiskScratch& w,
                      double* ego_col, char* ego_hit, double* by_step, double* by_object) {
  const std::int16_t* row = first + static_cast<size_t>(i) * n_co;
  int* hist = w.histogram + static_cast<size_t>(i) * (steps + 1);
  int* ev = w.events + static_cast<size_t>(i) * n_co;
  double* contrib = w.contrib + static_cast<size_t>(i) * n_co;
  double* mass = w.hit_mass + static_cast<size_t>(i) * n_obj;
  double* step_row = by_step + static_cast<size_t>(i) * steps;
  double* obj_row = by_object + static_cast<size_t>(i) * n_obj;
  for (int n = 0; n <= steps; ++n) hist[n] = 0;
  for (int j = 0; j < n_co; ++j) {
    if (row[j] > 0) ++hist[row[j]];
  }
  int total = 0;
  for (int n = 1; n <= steps; ++n) {  // counts -> start offsets
    const int c = hist[n];
    hist[n] = total;
    total += c;
  }
  for (int j = 0; j < n_co; ++j) {
    if (row[j] > 0) ev[hist[row[j]]++] = j;
  }
  for (int o = 0; o < n_obj; ++o) {
    mass[o] = 0.0;
    obj_row[o] = 0.0;
  }
  for (int n = 0; n < steps; ++n) step_row[n] = 0.0;
  ego_hit[i] = total > 0;
  ego_col[i] = total > 0 ? core::ChronologicalCollisionProbability(total, ev, p_co, object_of,
                                                                   n_obj, mass, contrib)
                         : 0.0;
  for (int e = 0; e < total; ++e) {
    step_row[row[ev[e]] - 1] += contrib[e];
    obj_row[object_of[ev[e]]] += contrib[e];
  }
}

/** Thread q: output q (steps, then objects, then p_cra), summed over colliding ego hypotheses
 *  in ego order, as the CPU does. */
CRIT_HD void ReduceBody(int q, int n_ego, int steps, int n_obj, const double* p_ego,
                        const double* ego_col, const double* by_step, const double* by_object,
                        double* out) {
  double sum = 0.0;
  for (int i = 0; i < n_ego; ++i) {
    if (ego_col[i] == 0.0) continue;
    const double v = q < steps           ? by_step[static_cast<size_t>(i) * steps + q]
                     : q < steps + n_obj ? by_object[static_cast<size_t>(i) * n_obj + (q - steps)]
                                         : ego_col[i];
    sum += p_ego[i] * v;
  }
  out[q] = sum;
}

}  // namespace criticality::cuda
