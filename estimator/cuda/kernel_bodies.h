#pragma once
// The per-thread bodies of the CUDA backend's kernels, as plain CRIT_HD functions: the kernels
// (cuda_backend.cu) only compute their index and call these. Because they are ordinary C++,
// tests run them on the CPU over every index, with the device's data layout, and compare with
// the CPU backend (tests/estimator/cuda/kernel_bodies_test.cc), so the GPU path's logic is
// checked even on machines without a GPU.
//
// Everything works on a BATCH of problems (one estimate = a batch of one): the hypotheses of
// all problems are concatenated and BatchLayout's prefix sums say where each problem's part
// starts. Layouts: poses step-major over the whole batch, x[n * total + t]; each problem's pair
// matrix ego-major, [pair_base[p] + i * n_co + j].
#include <cstddef>
#include <cstdint>

#include "core/chronological_risk.h"
#include "core/hd.h"
#include "core/hypothesis_set.h"
#include "core/min_max.h"
#include "core/oriented_box.h"
#include "core/trajectory_generation.h"

namespace criticality::cuda {

struct Poses {
  const double* x;
  const double* y;
  const double* c;
  const double* s;
};

/** Where each problem p of a batch lives (all prefix sums have problems + 1 entries). */
struct BatchLayout {
  int problems{0};
  int steps{0};
  int total_ego{0};
  int total_co{0};
  const int* set_base;            ///< [p]: index of problem p's ego set; its COs follow
  const int* ego_base;            ///< prefix sums of ego trajectories
  const int* co_base;             ///< prefix sums of CO trajectories
  const long long* pair_base;     ///< prefix sums of n_ego * n_co
  const int* obj_base;            ///< prefix sums of objects
  const long long* ego_obj_base;  ///< prefix sums of n_ego * n_obj
  const int* out_base;            ///< prefix sums of (steps + n_obj + 1) risk outputs
  const int* co_object_of;        ///< [global CO trajectory]: LOCAL object index
  const int* co_offset;           ///< [obj_base[p] + o]: object o's first LOCAL CO trajectory
  const double* co_half_length;   ///< [global CO trajectory]
  const double* co_half_width;
  const double* ego_half_length;  ///< [p]
  const double* ego_half_width;
};

/** The problem p with base[p] <= index < base[p + 1] (problems with an empty range are
 *  skipped); base has problems + 1 entries. */
template <typename T>
CRIT_HD int ProblemOf(const T* base, int problems, T index) {
  int lo = 0, hi = problems - 1;
  while (lo < hi) {  // smallest p with base[p + 1] > index
    const int mid = (lo + hi) / 2;
    if (base[mid + 1] > index)
      hi = mid;
    else
      lo = mid + 1;
  }
  return lo;
}

struct RiskScratch {
  int* histogram;    ///< total_ego x (steps + 1)
  int* events;       ///< one per pair
  double* contrib;   ///< one per pair
  double* hit_mass;  ///< n_ego x n_obj per problem (ego_obj_base)
};

/** Thread g < total_ego: that ego hypothesis; else CO trajectory g - total_ego. */
CRIT_HD void TrajectoryBody(int g, const core::HypothesisSet* sets, const BatchLayout& b,
                            const core::SimulationConfig& cfg, double* ex, double* ey, double* eyaw,
                            double* cx, double* cy, double* cyaw) {
  if (g < b.total_ego) {
    const int p = ProblemOf(b.ego_base, b.problems, g);
    const core::HypothesisSet& h = sets[b.set_base[p]];
    const int i = g - b.ego_base[p];
    core::SimulateHypothesis(h, cfg, i / h.n_paths, i % h.n_paths, ex + g, ey + g, eyaw + g,
                             b.total_ego);
  } else if (g < b.total_ego + b.total_co) {
    const int j = g - b.total_ego;
    const int p = ProblemOf(b.co_base, b.problems, j);
    const int o = b.co_object_of[j];
    const core::HypothesisSet& h = sets[b.set_base[p] + 1 + o];
    const int t = j - b.co_base[p] - b.co_offset[b.obj_base[p] + o];
    core::SimulateHypothesis(h, cfg, t / h.n_paths, t % h.n_paths, cx + j, cy + j, cyaw + j,
                             b.total_co);
  }
}

CRIT_HD void TrigBody(size_t k, const double* yaw, double* c, double* s) {
  c[k] = std::cos(yaw[k]);
  s[k] = std::sin(yaw[k]);
}

/** Steps per block of the trajectories' bounds (BoundsBody). */
constexpr int kBoundsBlock = 10;

CRIT_HD int BoundsBlocks(int steps) { return (steps + kBoundsBlock - 1) / kBoundsBlock; }

/** Thread t (a trajectory of `total`, step-major poses x[n * total + t]): for each block of
 *  kBoundsBlock steps, the least and greatest x and y of its centre, stored at
 *  bounds[(4 * block + {0: min x, 1: max x, 2: min y, 3: max y}) * total + t]. */
CRIT_HD void BoundsBody(int t, int total, int steps, const double* x, const double* y,
                        double* bounds) {
  for (int block = 0; block * kBoundsBlock < steps; ++block) {
    const int begin = block * kBoundsBlock;
    const int end = begin + kBoundsBlock < steps ? begin + kBoundsBlock : steps;
    double x0 = x[static_cast<size_t>(begin) * total + t], x1 = x0;
    double y0 = y[static_cast<size_t>(begin) * total + t], y1 = y0;
    for (int n = begin + 1; n < end; ++n) {
      const double px = x[static_cast<size_t>(n) * total + t];
      const double py = y[static_cast<size_t>(n) * total + t];
      x0 = core::Min(x0, px);
      x1 = core::Max(x1, px);
      y0 = core::Min(y0, py);
      y1 = core::Max(y1, py);
    }
    const size_t at = static_cast<size_t>(4 * block) * total + t;
    bounds[at] = x0;
    bounds[at + total] = x1;
    bounds[at + 2 * static_cast<size_t>(total)] = y0;
    bounds[at + 3 * static_cast<size_t>(total)] = y1;
  }
}

/** Whether the centres of two trajectories stay farther apart than `gap` in x or in y over a
 *  whole block (their bounds, BoundsBody). Then every step of the block fails the collision
 *  test's centre-distance check by more than rounding (gap exceeds the reach by a micrometre),
 *  so skipping the block changes no answer. */
CRIT_HD bool BlockApart(const double* ego_bounds, int total_ego, int i, const double* co_bounds,
                        int total_co, int j, int block, double gap) {
  const double* e = ego_bounds + static_cast<size_t>(4 * block) * total_ego + i;
  const double* c = co_bounds + static_cast<size_t>(4 * block) * total_co + j;
  const size_t se = total_ego, sc = total_co;         // strides between min x, max x, min y, max y
  return c[0] - e[se] > gap || e[0] - c[sc] > gap ||  // apart in x
         c[2 * sc] - e[3 * se] > gap || e[2 * se] - c[3 * sc] > gap;  // apart in y
}

/** Thread k (a pair of the batch): the first colliding step (1-based, 0 = none) of its ego and
 *  CO trajectory, with blocks of steps whose bounds keep the two apart skipped (BlockApart), a
 *  bounding-circle test before the exact one and early exit. A pair that collides marks its
 *  ego hypothesis in ego_hits (every writer writes 1; zeroed before the launch). */
CRIT_HD void CollisionBody(long long k, const BatchLayout& b, const Poses& ego, const Poses& co,
                           const double* ego_bounds, const double* co_bounds, std::int16_t* first,
                           char* ego_hits) {
  const int p = ProblemOf(b.pair_base, b.problems, k);
  const int n_co = b.co_base[p + 1] - b.co_base[p];
  const long long local = k - b.pair_base[p];
  const int i = b.ego_base[p] + static_cast<int>(local / n_co);
  const int j = b.co_base[p] + static_cast<int>(local % n_co);
  const double ehl = b.ego_half_length[p], ehw = b.ego_half_width[p];
  const double chl = b.co_half_length[j], chw = b.co_half_width[j];
  const double reach = core::BoundingRadius(ehl, ehw) + core::BoundingRadius(chl, chw) + 1e-9;
  const double reach2 = reach * reach;
  const double gap = reach + 1e-6;
  std::int16_t hit = 0;
  for (int n = 0; n < b.steps; ++n) {
    if (n % kBoundsBlock == 0 &&
        BlockApart(ego_bounds, b.total_ego, i, co_bounds, b.total_co, j, n / kBoundsBlock, gap)) {
      n += kBoundsBlock - 1;
      continue;
    }
    const size_t a = static_cast<size_t>(n) * b.total_ego + i;
    const size_t c = static_cast<size_t>(n) * b.total_co + j;
    const double dx = co.x[c] - ego.x[a], dy = co.y[c] - ego.y[a];
    if (dx * dx + dy * dy > reach2) continue;
    const core::OrientedBox<double> ba{ego.x[a], ego.y[a], ego.c[a], ego.s[a], ehl, ehw};
    const core::OrientedBox<double> bb{co.x[c], co.y[c], co.c[c], co.s[c], chl, chw};
    if (core::BoxesOverlap(ba, bb)) {
      hit = static_cast<std::int16_t>(n + 1);
      break;
    }
  }
  first[k] = hit;
  if (hit) ego_hits[i] = 1;
}

/** Where ego hypothesis g's row of the batch lives: its problem, its index there, the
 *  problem's CO trajectories and objects, and the row's first pair and first ego x object. */
struct EgoRow {
  int p, i, n_co, n_obj;
  size_t pairs, objs;
};
CRIT_HD EgoRow EgoRowOf(const BatchLayout& b, int g) {
  EgoRow r;
  r.p = ProblemOf(b.ego_base, b.problems, g);
  r.i = g - b.ego_base[r.p];
  r.n_co = b.co_base[r.p + 1] - b.co_base[r.p];
  r.n_obj = b.obj_base[r.p + 1] - b.obj_base[r.p];
  r.pairs = static_cast<size_t>(b.pair_base[r.p]) + static_cast<size_t>(r.i) * r.n_co;
  r.objs = static_cast<size_t>(b.ego_obj_base[r.p]) + static_cast<size_t>(r.i) * r.n_obj;
  return r;
}

/** Thread g (an ego hypothesis of the batch): its colliding CO trajectories in chronological
 *  order (counting sort by step, stable in j), the paper's chronological approximation, and
 *  its split over steps and objects (not yet weighted by p_EGO). A hypothesis that no pair
 *  marked in ego_hits (CollisionBody; the marks are also the hits the host reads) collides
 *  with nothing: its collision probability is 0 and its row is not read (ReduceBody skips it). */
CRIT_HD void RiskBody(int g, const BatchLayout& b, const std::int16_t* first, const double* p_co,
                      const char* ego_hits, const RiskScratch& w, double* ego_col, double* by_step,
                      double* by_object) {
  if (!ego_hits[g]) {
    ego_col[g] = 0.0;
    return;
  }
  const EgoRow r = EgoRowOf(b, g);
  const int p = r.p, n_co = r.n_co, n_obj = r.n_obj, steps = b.steps;
  const size_t pairs = r.pairs, objs = r.objs;
  const int* object_of = b.co_object_of + b.co_base[p];
  int n_events = 0;
  ego_col[g] = core::SplitEgoRisk(
      first + pairs, n_co, steps, n_obj, p_co + b.co_base[p], object_of,
      w.histogram + static_cast<size_t>(g) * (steps + 1), w.events + pairs, w.contrib + pairs,
      w.hit_mass + objs, by_step + static_cast<size_t>(g) * steps, by_object + objs, &n_events);
}

/** Lanes of a warp (RiskRowBody). */
constexpr int kWarp = 32;

/** One warp's shared memory in RiskRowBody: a row's histogram, hit masses and sums, and the
 *  stage of 32 events at a time. */
struct RiskRowScratch {
  double* hit_mass;   ///< n_obj
  double* by_object;  ///< n_obj
  double* by_step;    ///< steps
  double* stage_p;    ///< kWarp
  int* hist;          ///< steps + 1
  int* stage_o;       ///< kWarp
  int* stage_s;       ///< kWarp
  int* total;         ///< 1: the row's number of events
};

/** Bytes of one warp's RiskRowScratch (a multiple of 8). */
CRIT_HD size_t RiskRowBytes(int steps, int max_obj) {
  const size_t doubles = 2 * static_cast<size_t>(max_obj) + steps + kWarp;
  const size_t ints = static_cast<size_t>(steps) + 1 + 2 * kWarp + 1;
  return (doubles * sizeof(double) + ints * sizeof(int) + 7) / 8 * 8;
}

/** The scratch laid out from `base` (8-byte aligned, RiskRowBytes long). */
CRIT_HD RiskRowScratch RiskRowScratchAt(void* base, int steps, int max_obj) {
  RiskRowScratch s;
  double* d = static_cast<double*>(base);
  s.hit_mass = d;
  s.by_object = d + max_obj;
  s.by_step = d + 2 * max_obj;
  s.stage_p = s.by_step + steps;
  int* i = reinterpret_cast<int*>(s.stage_p + kWarp);
  s.hist = i;
  s.stage_o = i + steps + 1;
  s.stage_s = s.stage_o + kWarp;
  s.total = s.stage_s + kWarp;
  return s;
}

/** A warp as the CPU emulates it: each lane-parallel phase runs lane after lane. */
struct HostWarp {
  template <typename F>
  void Lanes(F f) const {
    for (int lane = 0; lane < kWarp; ++lane) f(lane);
  }
  template <typename F>
  void Lane0(F f) const {
    f();
  }
  void Sync() const {}
  void Increment(int* a) const { ++*a; }
};

/** Warp g (an ego hypothesis of the batch): what RiskBody computes, with the row's work spread
 *  over the warp's lanes and its scratch in shared memory (`s`, RiskRowScratch). The lanes
 *  clear the scratch, read the row (coalesced) and count its events by step; lane 0 turns the
 *  counts into offsets and places the events (a counting sort, stable in j, into `events`, the
 *  pair-sized scratch); the lanes stage 32 events at a time and lane 0 runs the paper's
 *  chronological approximation over them; the lanes write the sums. Every sum is taken in the
 *  order core::SplitEgoRisk takes it, so the results are the same bits. `Warp` gives Lanes,
 *  Lane0, Sync and Increment: on the device each lane runs its own part (HostWarp emulates). */
template <typename Warp>
CRIT_HD void RiskRowBody(const Warp& warp, int g, const BatchLayout& b, const std::int16_t* first,
                         const double* p_co, const char* ego_hits, int* events_scratch,
                         const RiskRowScratch& s, double* ego_col, double* by_step,
                         double* by_object) {
  if (g >= b.total_ego) return;
  if (!ego_hits[g]) {
    warp.Lane0([&] { ego_col[g] = 0.0; });
    return;
  }
  const EgoRow r = EgoRowOf(b, g);
  const int p = r.p, n_co = r.n_co, n_obj = r.n_obj, steps = b.steps;
  const size_t pairs = r.pairs, objs = r.objs;
  const std::int16_t* row = first + pairs;
  const int* object_of = b.co_object_of + b.co_base[p];
  const double* pc = p_co + b.co_base[p];
  int* events = events_scratch + pairs;
  warp.Lanes([&](int lane) {
    for (int n = lane; n <= steps; n += kWarp) s.hist[n] = 0;
    for (int n = lane; n < steps; n += kWarp) s.by_step[n] = 0.0;
    for (int o = lane; o < n_obj; o += kWarp) {
      s.hit_mass[o] = 0.0;
      s.by_object[o] = 0.0;
    }
  });
  warp.Sync();
  warp.Lanes([&](int lane) {
    for (int j = lane; j < n_co; j += kWarp) {
      if (row[j] > 0) warp.Increment(&s.hist[row[j]]);
    }
  });
  warp.Sync();
  warp.Lane0([&] {
    int total = 0;
    for (int n = 1; n <= steps; ++n) {  // counts -> start offsets
      const int c = s.hist[n];
      s.hist[n] = total;
      total += c;
    }
    for (int j = 0; j < n_co; ++j) {
      if (row[j] > 0) events[s.hist[row[j]]++] = j;
    }
    *s.total = total;
  });
  warp.Sync();
  const int total = *s.total;
  double p_row = 0.0;  // lane 0's sum
  for (int base = 0; base < total; base += kWarp) {
    const int count = total - base < kWarp ? total - base : kWarp;
    warp.Lanes([&](int lane) {
      if (lane < count) {
        const int j = events[base + lane];
        s.stage_o[lane] = object_of[j];
        s.stage_p[lane] = pc[j];
        s.stage_s[lane] = row[j];
      }
    });
    warp.Sync();
    warp.Lane0([&] {  // core::ChronologicalCollisionProbability, then SplitEgoRisk's split
      for (int e = 0; e < count; ++e) {
        const int o = s.stage_o[e];
        double survive_others = 1.0;
        for (int k = 0; k < n_obj; ++k) {
          if (k != o) survive_others *= 1.0 - s.hit_mass[k];
        }
        const double c = s.stage_p[e] * survive_others;
        s.hit_mass[o] += s.stage_p[e];
        p_row += c;
        s.by_step[s.stage_s[e] - 1] += c;
        s.by_object[o] += c;
      }
    });
    warp.Sync();
  }
  warp.Lanes([&](int lane) {
    for (int n = lane; n < steps; n += kWarp)
      by_step[static_cast<size_t>(g) * steps + n] = s.by_step[n];
    for (int o = lane; o < n_obj; o += kWarp) by_object[objs + o] = s.by_object[o];
  });
  warp.Lane0([&] { ego_col[g] = p_row; });
}

/** Thread q (a risk output of the batch: per problem its steps, objects, then p_cra): summed
 *  over the problem's colliding ego hypotheses in ego order, as the CPU does. */
CRIT_HD void ReduceBody(int q, const BatchLayout& b, const double* p_ego, const double* ego_col,
                        const double* by_step, const double* by_object, double* out) {
  const int p = ProblemOf(b.out_base, b.problems, q);
  const int local = q - b.out_base[p];
  const int steps = b.steps;
  const int n_obj = b.obj_base[p + 1] - b.obj_base[p];
  double sum = 0.0;
  for (int g = b.ego_base[p]; g < b.ego_base[p + 1]; ++g) {
    if (ego_col[g] == 0.0) continue;
    const size_t objs =
        static_cast<size_t>(b.ego_obj_base[p]) + static_cast<size_t>(g - b.ego_base[p]) * n_obj;
    const double v = local < steps           ? by_step[static_cast<size_t>(g) * steps + local]
                     : local < steps + n_obj ? by_object[objs + (local - steps)]
                                             : ego_col[g];
    sum += p_ego[g] * v;
  }
  out[q] = sum;
}

/** One warp's shared memory in ReduceWarpBody: 32 terms at a time and whether each counts. */
struct ReduceScratch {
  double* term;  ///< kWarp
  int* counts;   ///< kWarp
};

/** Warp q (a risk output of the batch): what ReduceBody computes, with the lanes reading 32 ego
 *  hypotheses at a time (coalesced) and lane 0 adding their terms in ego order, so the sum is
 *  the same bits as ReduceBody's and the CPU's. */
template <typename Warp>
CRIT_HD void ReduceWarpBody(const Warp& warp, int q, const BatchLayout& b, const double* p_ego,
                            const double* ego_col, const double* by_step, const double* by_object,
                            const ReduceScratch& s, double* out) {
  const int p = ProblemOf(b.out_base, b.problems, q);
  const int local = q - b.out_base[p];
  const int steps = b.steps;
  const int n_obj = b.obj_base[p + 1] - b.obj_base[p];
  double sum = 0.0;  // lane 0's
  for (int base = b.ego_base[p]; base < b.ego_base[p + 1]; base += kWarp) {
    warp.Lanes([&](int lane) {
      const int g = base + lane;
      s.counts[lane] = g < b.ego_base[p + 1] && ego_col[g] != 0.0;
      if (!s.counts[lane]) return;
      const size_t objs =
          static_cast<size_t>(b.ego_obj_base[p]) + static_cast<size_t>(g - b.ego_base[p]) * n_obj;
      const double v = local < steps           ? by_step[static_cast<size_t>(g) * steps + local]
                       : local < steps + n_obj ? by_object[objs + (local - steps)]
                                               : ego_col[g];
      s.term[lane] = p_ego[g] * v;
    });
    warp.Sync();
    warp.Lane0([&] {
      for (int lane = 0; lane < kWarp; ++lane) {
        if (s.counts[lane]) sum += s.term[lane];
      }
    });
    warp.Sync();
  }
  warp.Lane0([&] { out[q] = sum; });
}

}  // namespace criticality::cuda
