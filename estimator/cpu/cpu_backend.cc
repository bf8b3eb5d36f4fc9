#include "cpu/cpu_backend.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <string>

#include "core/oriented_box.h"
#include "core/trajectory_generation.h"
#include "cpu/block_contact.h"
#include "cpu/object_paths_cache.h"
#include "cpu/sibling_steps.h"
#include "src/parallel_for.h"
#include "src/reach_filter.h"

namespace criticality {
namespace {

using internal::TrajectoryStore;

// An axis-aligned box of centres, turned into a circle at the end.
struct Aabb {
  double x0{1e300}, x1{-1e300}, y0{1e300}, y1{-1e300};
  void Add(double x, double y) {
    x0 = std::min(x0, x);
    x1 = std::max(x1, x);
    y0 = std::min(y0, y);
    y1 = std::max(y1, y);
  }
  void Add(const Aabb& o) {
    x0 = std::min(x0, o.x0);
    x1 = std::max(x1, o.x1);
    y0 = std::min(y0, o.y0);
    y1 = std::max(y1, o.y1);
  }
};

template <class C>
void StoreCircle(const Aabb& a, size_t k, std::vector<C>* c) {
  // Half the box's diagonal (no overflow to guard against: sqrt, not hypot).
  const double dx = a.x1 - a.x0, dy = a.y1 - a.y0;
  (*c)[k] = C{0.5 * (a.x0 + a.x1), 0.5 * (a.y0 + a.y1), 0.5 * std::sqrt(dx * dx + dy * dy)};
}

int Power(int base, int exp) {
  int r = 1;
  for (int k = 0; k < exp; ++k) r *= base;
  return r;
}

}  // namespace

CpuBackend::CpuBackend(int threads, bool simd, bool skip_out_of_reach)
    : threads_(internal::ResolveThreads(threads)),
      simd_(simd),
      skip_out_of_reach_(skip_out_of_reach) {}

void CpuBackend::FinishSpan(const TrajectoryStore& t, std::vector<double>* c,
                            std::vector<double>* s, BlockBounds* b, int tr, int n0, int n1, int q0,
                            int q1, bool trig_done, Box* span_box) const {
  const size_t base = t.Offset(tr);
  if (trig_done) {  // the simulation wrote cos/sin already (SiblingSpan::c, s)
  } else if (simd_) {
    internal::CosSin(&t.yaw[base + n0], n1 - n0, &(*c)[base + n0], &(*s)[base + n0]);
  } else {
    for (int n = n0; n < n1; ++n) {
      (*c)[base + n] = std::cos(t.yaw[base + n]);
      (*s)[base + n] = std::sin(t.yaw[base + n]);
    }
  }
  const int blocks = static_cast<int>(block_begin_.size()) - 1;
  const double* x = &t.x[base];
  const double* y = &t.y[base];
  for (int q = q0; q < q1; ++q) {
    double x0 = x[block_begin_[q]], x1 = x0, y0 = y[block_begin_[q]], y1 = y0;
    for (int n = block_begin_[q] + 1; n < block_begin_[q + 1]; ++n) {
      x0 = std::min(x0, x[n]);
      x1 = std::max(x1, x[n]);
      y0 = std::min(y0, y[n]);
      y1 = std::max(y1, y[n]);
    }
    const size_t k = static_cast<size_t>(tr) * blocks + q;
    const double dx = x1 - x0, dy = y1 - y0;
    b->c[k] = Circle{0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.5 * std::sqrt(dx * dx + dy * dy)};
    if (span_box) {
      span_box->x0 = std::min(span_box->x0, x0);
      span_box->x1 = std::max(span_box->x1, x1);
      span_box->y0 = std::min(span_box->y0, y0);
      span_box->y1 = std::max(span_box->y1, y1);
    }
  }
}

void CpuBackend::ResizeBounds(const TrajectoryStore& t, BlockBounds* b) const {
  const int blocks = static_cast<int>(block_begin_.size()) - 1;
  const size_t n = static_cast<size_t>(t.trajectories) * blocks;
  b->c.resize(n);
}

void CpuBackend::GenerateTrajectories(const internal::Problem& pb) {
  const int steps = pb.Steps();
  const core::HypothesisSet& ego = pb.ego;
  tree_ = Tree{ego.n_profiles, ego.n_paths, ego.n_instants, ego.n_lateral};
  ego_.Resize(pb.EgoTrajectories(), steps);
  co_.Resize(pb.CoTrajectories(), steps);
  core::InstantBoundaries(ego, pb.sim, boundary_);
  const int K = ego.n_instants, L = ego.n_lateral;

  // Blocks never cross a span boundary, so a node's span is a whole number of blocks.
  block_begin_.clear();
  phase_block_.clear();
  for (int k = 0; k < K; ++k) {
    phase_block_.push_back(static_cast<int>(block_begin_.size()));
    for (int n = boundary_[k]; n < boundary_[k + 1]; n += kBlockSteps) block_begin_.push_back(n);
  }
  phase_block_.push_back(static_cast<int>(block_begin_.size()));
  block_begin_.push_back(steps);
  const int blocks = static_cast<int>(block_begin_.size()) - 1;
  // Held poses (HypothesisSet::pose_hold_steps, the same for the ego and every object): a
  // pose differs from the one before it only at step 0 and where the world looks ((n + 1) %
  // hold == 0, core::HoldPose). A block without such a step repeats poses an earlier block
  // holds, already tested (or bounded apart) for every pair still in play.
  int hold = ego.pose_hold_steps;
  for (const core::HypothesisSet& h : pb.cos) hold = h.pose_hold_steps == hold ? hold : 0;
  block_new_pose_.assign(blocks, 1);
  if (hold > 1) {
    for (int q = 0; q < blocks; ++q) {
      bool fresh = block_begin_[q] == 0;
      for (int n = block_begin_[q]; n < block_begin_[q + 1] && !fresh; ++n)
        fresh = (n + 1) % hold == 0;
      block_new_pose_[q] = fresh;
    }
  }
  ResizeBounds(ego_, &ego_bounds_);
  ResizeBounds(co_, &co_bounds_);
  ego_cos_.resize(ego_.yaw.size());
  ego_sin_.resize(ego_.yaw.size());
  co_cos_.resize(co_.yaw.size());
  co_sin_.resize(co_.yaw.size());

  // Collision objects first (their swept circles decide which ego subtrees are out of reach):
  // no shared prefixes (each keeps one lateral sample throughout); the paths of one (set,
  // profile) in SIMD lanes where they apply, else one by one. A set that another scene of the
  // batch simulated already (ObjectPathsCache) is copied from there instead: the same poses
  // and cos/sin, bit for bit.
  using CachedPaths = std::shared_ptr<const internal::ObjectPathsCache::Paths>;
  std::vector<std::string> keys(paths_cache_ ? pb.cos.size() : 0);
  std::vector<CachedPaths> cached(pb.cos.size());
  for (size_t o = 0; o < keys.size(); ++o) {
    keys[o] = internal::ObjectPathsCache::KeyOf(pb.cos[o], pb.sim, simd_ ? 1 : 0);
    cached[o] = paths_cache_->Find(keys[o]);
  }
  // The trajectories [first, first + count) of set o in the store and its cos/sin.
  auto set_range = [&](size_t o) {
    return std::make_pair(co_.Offset(pb.co_offset[o]),
                          static_cast<size_t>(pb.cos[o].Trajectories()) * steps);
  };
  std::vector<std::pair<int, int>> co_tasks;  // (set, profile), profile -1: copy the set
  for (size_t o = 0; o < pb.cos.size(); ++o) {
    if (cached[o]) {
      co_tasks.emplace_back(static_cast<int>(o), -1);
      continue;
    }
    for (int profile = 0; profile < pb.cos[o].n_profiles; ++profile)
      co_tasks.emplace_back(static_cast<int>(o), profile);
  }
  internal::ParallelFor(static_cast<int>(co_tasks.size()), threads_, [&](int begin, int end) {
    for (int task = begin; task < end; ++task) {
      const auto [o, profile] = co_tasks[task];
      const core::HypothesisSet& h = pb.cos[o];
      if (profile < 0) {
        const internal::ObjectPathsCache::Paths& p = *cached[o];
        const auto [at, n] = set_range(o);
        std::copy_n(p.x.data(), n, &co_.x[at]);
        std::copy_n(p.y.data(), n, &co_.y[at]);
        std::copy_n(p.yaw.data(), n, &co_.yaw[at]);
        std::copy_n(p.c.data(), n, &co_cos_[at]);
        std::copy_n(p.s.data(), n, &co_sin_[at]);
        for (int t = 0; t < h.Trajectories(); ++t)
          FinishSpan(co_, &co_cos_, &co_sin_, &co_bounds_, pb.co_offset[o] + t, 0, steps, 0, blocks,
                     true);
        continue;
      }
      const int j0 = pb.co_offset[o] + profile * h.n_paths;
      const bool co_lanes = simd_ && internal::SiblingStepsApply(h, pb.sim);
      if (co_lanes) {
        const size_t at = co_.Offset(j0);
        internal::SimulateProfilePaths(h, pb.sim, profile, &co_.x[at], &co_.y[at], &co_.yaw[at],
                                       co_.steps, &co_cos_[at], &co_sin_[at]);
      } else {
        for (int path = 0; path < h.n_paths; ++path) {
          const size_t at = co_.Offset(j0 + path);
          core::SimulateHypothesis(h, pb.sim, profile, path, &co_.x[at], &co_.y[at], &co_.yaw[at]);
        }
      }
      for (int path = 0; path < h.n_paths; ++path)
        FinishSpan(co_, &co_cos_, &co_sin_, &co_bounds_, j0 + path, 0, steps, 0, blocks, co_lanes);
    }
  });
  for (size_t o = 0; o < keys.size(); ++o) {
    if (cached[o] || !paths_cache_->HasRoom(pb.cos[o].Trajectories(), steps)) continue;
    auto p = std::make_shared<internal::ObjectPathsCache::Paths>();
    const auto [at, n] = set_range(o);
    p->steps = steps;
    p->x.assign(&co_.x[at], &co_.x[at] + n);
    p->y.assign(&co_.y[at], &co_.y[at] + n);
    p->yaw.assign(&co_.yaw[at], &co_.yaw[at] + n);
    p->c.assign(&co_cos_[at], &co_cos_[at] + n);
    p->s.assign(&co_sin_[at], &co_sin_[at] + n);
    paths_cache_->Store(std::move(keys[o]), std::move(p));
  }
  // Each object's circle over each block, around all its trajectories' poses.
  const int n_sets = static_cast<int>(pb.cos.size());
  object_blocks_.c.resize(static_cast<size_t>(n_sets) * blocks);
  internal::ParallelFor(n_sets, threads_, [&](int begin, int end) {
    for (int o = begin; o < end; ++o) {
      for (int q = 0; q < blocks; ++q) {
        Aabb box;
        for (int j = pb.co_offset[o]; j < pb.co_offset[o + 1]; ++j) {
          const size_t at = co_.Offset(j);
          for (int n = block_begin_[q]; n < block_begin_[q + 1]; ++n)
            box.Add(co_.x[at + n], co_.y[at + n]);
        }
        StoreCircle(box, static_cast<size_t>(o) * blocks + q, &object_blocks_.c);
      }
    }
  });

  // Ego: the section tree, one node per (profile, instant k, group of paths that share their
  // first k + 1 sections), level by level. Each node starts from its parent's end state (the
  // profile's initial state at the top) and is simulated over its span on its group's first
  // path, with its cos/sin and block bounds (EgoTrajectories() copies the span's poses to the
  // group's other paths when asked). Nodes of one level, whatever their parents and profiles, go
  // together into SIMD lanes (simd_), up to kMaxLateralSamples per call, in (profile, node)
  // order: 3 lateral samples give 3, 9, 27 nodes per profile and level, so that 8 profiles
  // fill 3, 9, 27 vectors of 8 (8, 16, 32 when packed per profile). Below the first level a
  // node whose reach meets no object is skipped with its subtree.
  node_offset_[0] = 0;
  for (int k = 0; k < K; ++k) node_offset_[k + 1] = node_offset_[k] + Power(L, k + 1);
  const int nodes = node_offset_[K];
  node_skipped_.assign(static_cast<size_t>(ego.n_profiles) * nodes, 0);
  node_span_box_.assign(node_skipped_.size(), Box{});
  skipped_nodes_ = checked_nodes_ = 0;
  const double ego_r = core::BoundingRadius(ego.half_length, ego.half_width);
  std::vector<double> object_r(n_sets);
  for (int o = 0; o < n_sets; ++o)
    object_r[o] = core::BoundingRadius(pb.cos[o].half_length, pb.cos[o].half_width);
  // Whether nothing below a node of instant k that starts at (x, y) in state st can meet any
  // object: in every block from its span to the horizon, its reach by the block's end, grown
  // by the bounding radii and a margin far above the backends' rounding, is apart from every
  // object's circle of that block.
  auto out_of_reach = [&](int k, double x, double y, const core::SimulationState& st) {
    const double accel = std::hypot(st.s.ax, st.s.ay);
    for (int q = phase_block_[k]; q < blocks; ++q) {
      const double r =
          internal::EgoReachAfter(ego, pb.sim, st.s.v, accel, block_begin_[q + 1] - boundary_[k]) +
          ego_r + 1e-3;
      for (int o = 0; o < n_sets; ++o) {
        const Circle& c = object_blocks_.c[static_cast<size_t>(o) * blocks + q];
        const double d = r + c.r + object_r[o];
        if ((x - c.cx) * (x - c.cx) + (y - c.cy) * (y - c.cy) <= d * d) return false;
      }
    }
    return true;
  };
  const bool lanes = simd_ && internal::SiblingStepsApply(ego, pb.sim);
  // A pack's lanes come from several profiles: their demands by step, computed once.
  const internal::DemandTable ego_demands =
      lanes ? internal::DemandsOf(ego, pb.sim) : internal::DemandTable{};
  constexpr int kPack = core::kMaxLateralSamples;
  std::vector<core::SimulationState> parents(ego.n_profiles,
                                             core::InitialSimulationState(ego, pb.sim));
  std::vector<core::SimulationState> nodes_state;
  // Each node's end position in the scene frame (its span's last pose; its parent's when the
  // span has no step, as when two sample instants fall within one step).
  struct Position {
    double x, y;
  };
  std::vector<Position> parents_end(ego.n_profiles, Position{ego.X_WL.x, ego.X_WL.y});
  std::vector<Position> nodes_end;
  // The nodes a pack simulates together, (profile, node) each: those of one level, across
  // profiles, so that the lanes fill up (3 lateral samples give 3 nodes per profile at the
  // first level: alone they would fill 3 lanes of 8).
  std::vector<std::vector<std::pair<int, int>>> packs;
  std::vector<std::pair<int, int>> active;
  for (int k = 0; k < K && k < core::kMaxSampleInstants; ++k) {
    const int count = Power(L, k + 1);      // nodes per profile at this level
    const int width = Power(L, K - 1 - k);  // paths below each node
    const int n0 = boundary_[k], n1 = boundary_[k + 1];
    nodes_state.resize(static_cast<size_t>(ego.n_profiles) * count);
    nodes_end.resize(nodes_state.size());
    // The nodes to simulate, in packs of kPack in (profile, node) order (those of skipped
    // parents and those out of reach left out).
    packs.clear();
    active.clear();
    for (int profile = 0; profile < ego.n_profiles; ++profile) {
      for (int parent = 0; parent < count / L; ++parent) {
        // The children of one parent start from its end state: one test for all of them.
        bool skip = false;
        if (k > 0) {
          const size_t parent_node =
              static_cast<size_t>(profile) * nodes + node_offset_[k - 1] + parent;
          skip = node_skipped_[parent_node] != 0;
          if (!skip && skip_out_of_reach_) {
            const size_t at = static_cast<size_t>(profile) * (count / L) + parent;
            checked_nodes_ += L;
            skip = out_of_reach(k, parents_end[at].x, parents_end[at].y, parents[at]);
          }
        }
        for (int g = parent * L; g < (parent + 1) * L; ++g) {
          if (skip) {
            node_skipped_[static_cast<size_t>(profile) * nodes + node_offset_[k] + g] = 1;
            ++skipped_nodes_;
          } else {
            active.emplace_back(profile, g);
          }
        }
      }
    }
    // A pack never mixes profiles that drive (target > 0) with those that do not: a vector of
    // lanes that all come to a standstill stops stepping (cpu/sibling_steps.cc), one with a
    // driving lane in it steps to the end.
    auto drives = [&](int profile) { return ego.profile_target[profile] > 0.0; };
    for (size_t a = 0; a < active.size();) {
      size_t b = a + 1;
      while (b < active.size() && b - a < static_cast<size_t>(kPack) &&
             drives(active[b].first) == drives(active[a].first))
        ++b;
      packs.emplace_back(active.begin() + a, active.begin() + b);
      a = b;
    }
    internal::ParallelFor(static_cast<int>(packs.size()), threads_, [&](int begin, int end) {
      for (int task = begin; task < end; ++task) {
        const std::vector<std::pair<int, int>>& group = packs[task];
        internal::SiblingSpan span =
            internal::SpanOf(ego, pb.sim, group[0].first, n0, n1, static_cast<int>(group.size()));
        span.demands = &ego_demands;
        for (size_t l = 0; l < group.size(); ++l) {
          const auto [profile, g] = group[l];
          const size_t at = ego_.Offset(profile * ego.n_paths + g * width);
          internal::SetLane(&span, static_cast<int>(l), g * width,
                            parents[static_cast<size_t>(profile) * (count / L) + g / L],
                            &ego_.x[at], &ego_.y[at], &ego_.yaw[at], &ego_cos_[at], &ego_sin_[at]);
          span.profile[l] = profile;
        }
        if (lanes) {
          internal::SimulateSiblingSteps(&span);
        } else {
          for (int c = 0; c < span.lanes; ++c) {
            core::SimulateVehicleSteps(ego, pb.sim, span.profile[c], span.path[c], n0, n1,
                                       &span.state[c], span.x[c], span.y[c], span.yaw[c]);
          }
        }
        // Collision recognition reads a span's poses, cos/sin and block bounds on the node's
        // first path only (it walks the same tree): the group's other paths get the poses
        // only when EgoTrajectories() is asked for them.
        for (size_t l = 0; l < group.size(); ++l) {
          const auto [profile, g] = group[l];
          nodes_state[static_cast<size_t>(profile) * count + g] = span.state[l];
          const int first = profile * ego.n_paths + g * width;
          // Where the span left the vehicle: with held poses (HypothesisSet::pose_hold_steps)
          // its last stored pose may be one it left steps ago, too far back to bound its reach.
          nodes_end[static_cast<size_t>(profile) * count + g] =
              n1 > n0 ? Position{span.state[l].pose_x, span.state[l].pose_y}
                      : parents_end[static_cast<size_t>(profile) * (count / L) + g / L];
          FinishSpan(ego_, &ego_cos_, &ego_sin_, &ego_bounds_, first, n0, n1, phase_block_[k],
                     phase_block_[k + 1], lanes,
                     &node_span_box_[static_cast<size_t>(profile) * nodes + node_offset_[k] + g]);
        }
      }
    });
    parents.swap(nodes_state);
    parents_end.swap(nodes_end);
  }

  // Swept bounds of the tree nodes (post-order: a node's span plus its children's bounds;
  // a skipped node has none and adds nothing).
  const size_t n_node_bounds = static_cast<size_t>(ego.n_profiles) * nodes;
  node_bounds_.c.resize(n_node_bounds);
  node_still_.assign(n_node_bounds, 0);
  // Whether path `first`'s poses (centre, cos, sin) over steps [n0, n1) all equal its pose at
  // step `at` (bit for bit).
  auto holds_pose = [&](int first, int at, int n0, int n1) {
    const size_t b = ego_.Offset(first);
    const double x = ego_.x[b + at], y = ego_.y[b + at], c = ego_cos_[b + at], s = ego_sin_[b + at];
    for (int n = n0; n < n1; ++n) {
      if (ego_.x[b + n] != x || ego_.y[b + n] != y || ego_cos_[b + n] != c || ego_sin_[b + n] != s)
        return false;
    }
    return true;
  };
  auto sweep = [&](auto&& self, int profile, int k, int group) -> Aabb {
    Aabb box;
    if (k >= core::kMaxSampleInstants) return box;  // never: K <= kMaxSampleInstants
    const size_t nb = static_cast<size_t>(profile) * nodes + node_offset_[k] + group;
    if (node_skipped_[nb]) return box;
    const Box& span = node_span_box_[nb];  // the span's poses (FinishSpan's block boxes)
    box.Add(Aabb{span.x0, span.x1, span.y0, span.y1});
    // Still: the span holds one pose, and every child's subtree holds the same.
    const int width = Power(L, K - 1 - k);
    const int first = profile * ego.n_paths + group * width, n0 = boundary_[k];
    bool still = boundary_[k + 1] > n0 && holds_pose(first, n0, n0 + 1, boundary_[k + 1]);
    if (k + 1 < K) {
      for (int c = 0; c < L; ++c) {
        box.Add(self(self, profile, k + 1, group * L + c));
        const size_t child =
            static_cast<size_t>(profile) * nodes + node_offset_[k + 1] + group * L + c;
        // The child's pose at its first step is its own first path's.
        if (still) {
          const int child_first = first + c * (width / L), m0 = boundary_[k + 1];
          const size_t a = ego_.Offset(first) + n0, bc = ego_.Offset(child_first) + m0;
          still = node_still_[child] && ego_.x[bc] == ego_.x[a] && ego_.y[bc] == ego_.y[a] &&
                  ego_cos_[bc] == ego_cos_[a] && ego_sin_[bc] == ego_sin_[a];
        }
      }
    }
    node_still_[nb] = still;
    StoreCircle(box, nb, &node_bounds_.c);
    return box;
  };
  internal::ParallelFor(ego.n_profiles * L, threads_, [&](int begin, int end) {
    for (int task = begin; task < end; ++task) sweep(sweep, task / L, 0, task % L);
  });
  const size_t n_tail = static_cast<size_t>(pb.CoTrajectories()) * K;
  co_tail_.c.resize(n_tail);
  object_tail_.c.resize(static_cast<size_t>(n_sets) * K);
  internal::ParallelFor(n_sets, threads_, [&](int begin, int end) {
    for (int o = begin; o < end; ++o) {
      Aabb all;  // the object's tail: around every tail of its trajectories
      std::vector<Aabb> box(pb.co_offset[o + 1] - pb.co_offset[o]);
      for (int k = K - 1; k >= 0; --k) {  // tails grow backwards from the horizon
        for (int j = pb.co_offset[o]; j < pb.co_offset[o + 1]; ++j) {
          Aabb& b = box[j - pb.co_offset[o]];
          const size_t at = co_.Offset(j);
          for (int n = boundary_[k]; n < boundary_[k + 1]; ++n) b.Add(co_.x[at + n], co_.y[at + n]);
          StoreCircle(b, static_cast<size_t>(j) * K + k, &co_tail_.c);
          all.Add(b);
        }
        StoreCircle(all, static_cast<size_t>(o) * K + k, &object_tail_.c);
      }
    }
  });
  shared_prefixes_pending_ = true;
}

const internal::TrajectoryStore& CpuBackend::EgoTrajectories() const {
  if (!shared_prefixes_pending_) return ego_;
  // Each tree node's span was simulated on its group's first path: copy it to the others.
  const int K = tree_.n_instants, L = tree_.n_lateral;
  for (int profile = 0; profile < tree_.n_profiles; ++profile) {
    for (int k = 0; k < K; ++k) {
      const int width = Power(L, K - 1 - k);
      const size_t n0 = boundary_[k], n_span = boundary_[k + 1] - boundary_[k];
      for (int g = 0; g < Power(L, k + 1); ++g) {
        const int first = profile * tree_.n_paths + g * width;
        if (node_skipped_[static_cast<size_t>(profile) * node_offset_[K] + node_offset_[k] + g]) {
          // Never simulated: no pose, rather than one left from an earlier scene.
          for (int p = 0; p < width; ++p) {
            for (std::vector<double>* v : {&ego_.x, &ego_.y, &ego_.yaw}) {
              std::fill_n(v->data() + ego_.Offset(first + p) + n0, n_span,
                          std::numeric_limits<double>::quiet_NaN());
            }
          }
          continue;
        }
        for (int p = 1; p < width; ++p) {
          for (std::vector<double>* v : {&ego_.x, &ego_.y, &ego_.yaw}) {
            std::memcpy(v->data() + ego_.Offset(first + p) + n0,
                        v->data() + ego_.Offset(first) + n0, n_span * sizeof(double));
          }
        }
      }
    }
  }
  shared_prefixes_pending_ = false;
  return ego_;
}

void CpuBackend::RecognizeCollisions(const internal::Problem& pb,
                                     std::vector<std::int16_t>* first_step) {
  const int n_ego = pb.EgoTrajectories(), n_co = pb.CoTrajectories();
  first_step->assign(static_cast<size_t>(n_ego) * n_co, 0);
  const core::HypothesisSet& ego = pb.ego;
  const int K = ego.n_instants, L = ego.n_lateral;
  const int blocks = static_cast<int>(block_begin_.size()) - 1;
  const double ego_hl = ego.half_length, ego_hw = ego.half_width;
  const double ego_r = core::BoundingRadius(ego_hl, ego_hw);

  // Work is split by (ego profile, object, group of at most kTrajectoriesPerTask of its CO
  // trajectories); each task walks the section tree once for its group, keeping at each node the
  // trajectories that are still in play: a node's circles are then read once for all of them.
  constexpr int kTrajectoriesPerTask = 64;
  struct Task {
    int profile, object, j0, j1;
  };
  std::vector<Task> tasks;
  for (int profile = 0; profile < ego.n_profiles; ++profile) {
    for (size_t o = 0; o < pb.cos.size(); ++o) {
      for (int j = pb.co_offset[o]; j < pb.co_offset[o + 1]; j += kTrajectoriesPerTask) {
        tasks.push_back(Task{profile, static_cast<int>(o), j,
                             std::min(pb.co_offset[o + 1], j + kTrajectoriesPerTask)});
      }
    }
  }
  const int nodes = node_offset_[K];
  // The box tests of a block in SIMD lanes (simd_).
  static_assert(kBlockSteps <= internal::kMaxBlockContactSteps, "a block must fit the lanes");
  const internal::FirstOverlapFn first_overlap = simd_ ? internal::FirstOverlapInBlock() : nullptr;
  // Tasks differ in cost by orders of magnitude (an object near the ego or far from it): each
  // thread takes the next one when it is free. Each task writes only its own entries.
  internal::ParallelForDynamic(static_cast<int>(tasks.size()), threads_, [&](int task) {
    // live[k]: the task's CO trajectories still in play at level k (no hit above, swept bounds
    // not apart); near: the blocks of the current span where the object's circle meets the
    // node's.
    std::vector<int> live[core::kMaxSampleInstants + 1];
    std::vector<char> near(blocks);
    const Task t = tasks[task];
    // The last still node's level and pose, and its first hits per trajectory of the task
    // (-1: not yet looked for).
    struct StillPose {
      int k;
      double x, y, c, s;
    } still_cache{-1, 0.0, 0.0, 0.0, 0.0};
    std::vector<int> still_hit(t.j1 - t.j0, -1);
    const core::HypothesisSet& co = pb.cos[t.object];
    // Centres farther apart than the sum of the bounding radii cannot overlap; the small
    // margin keeps exactly touching boxes for the exact test. The object-wide tests add a
    // margin far above rounding, as their circles enclose the trajectories' circles.
    const double reach = ego_r + core::BoundingRadius(co.half_length, co.half_width) + 1e-9;
    const double reach2 = reach * reach;
    const double object_reach = reach + 1e-6;
    live[0].clear();
    for (int j = t.j0; j < t.j1; ++j) live[0].push_back(j);
    auto walk = [&](auto&& self, int k, int group) -> void {
      if (k >= core::kMaxSampleInstants) return;  // never: K <= kMaxSampleInstants
      const size_t nb = static_cast<size_t>(t.profile) * nodes + node_offset_[k] + group;
      if (node_skipped_[nb]) return;  // out of reach: never simulated
      // Swept bounds: nothing below this node comes near the object, or a trajectory.
      const Circle& nc = node_bounds_.c[nb];
      {
        const Circle& tc = object_tail_.c[static_cast<size_t>(t.object) * K + k];
        const double sx = nc.cx - tc.cx, sy = nc.cy - tc.cy;
        const double sr = nc.r + tc.r + object_reach;
        if (sx * sx + sy * sy > sr * sr) return;
      }
      const int width = Power(L, K - 1 - k);
      const int first = t.profile * ego.n_paths + group * width;
      const size_t ei = ego_.Offset(first), eb = static_cast<size_t>(first) * blocks;
      // A still subtree (every path below holds the node's first pose to the horizon): each
      // trajectory's first hit is found once along the node's first path over every block
      // from the span on, with the same tests as node by node (there they would repeat for
      // every path, the same poses), and holds for all the paths below.
      const bool still = node_still_[nb] != 0;
      // The blocks [q0, q1) where the object (all its trajectories) comes near the node.
      const int q0 = phase_block_[k], q1 = still ? blocks : phase_block_[k + 1];
      bool any_near = false;
      for (int q = q0; q < q1; ++q) {
        const Circle &e = ego_bounds_.c[eb + q],
                     &o = object_blocks_.c[static_cast<size_t>(t.object) * blocks + q];
        const double bx = e.cx - o.cx, by = e.cy - o.cy, br = e.r + o.r + object_reach;
        near[q - q0] = bx * bx + by * by <= br * br;
        any_near |= near[q - q0] != 0;
      }
      // The node's path for the lanes' box test (its poses from step 0).
      const internal::BoxTrack ego_track{&ego_.x[ei],   &ego_.y[ei], &ego_cos_[ei],
                                         &ego_sin_[ei], ego_hl,      ego_hw};
      // The same pose at the same step as the last still node's: the same first hits.
      if (still) {
        const size_t at = ei + boundary_[k];
        const StillPose pose{k, ego_.x[at], ego_.y[at], ego_cos_[at], ego_sin_[at]};
        if (pose.k != still_cache.k || pose.x != still_cache.x || pose.y != still_cache.y ||
            pose.c != still_cache.c || pose.s != still_cache.s) {
          still_cache = pose;
          std::fill(still_hit.begin(), still_hit.end(), -1);
        }
      }
      std::vector<int>& next = live[k + 1];
      next.clear();
      for (const int j : live[k]) {
        const size_t tb = static_cast<size_t>(j) * K + k;
        const Circle& tc = co_tail_.c[tb];
        const double sx = nc.cx - tc.cx, sy = nc.cy - tc.cy;
        const double sr = nc.r + tc.r + reach;
        if (sx * sx + sy * sy > sr * sr) continue;
        // First colliding step (1-based) of the node's path and j within blocks [q0, q1).
        int hit = 0;
        if (still && still_hit[j - t.j0] >= 0) {
          hit = still_hit[j - t.j0];
        } else if (any_near) {
          const size_t cj = co_.Offset(j), cb = static_cast<size_t>(j) * blocks;
          const internal::BoxTrack co_track{&co_.x[cj],   &co_.y[cj],     &co_cos_[cj],
                                            &co_sin_[cj], co.half_length, co.half_width};
          const long readable = static_cast<long>(std::min(ego_.x.size() - ei, co_.x.size() - cj));
          for (int q = q0; q < q1 && hit == 0; ++q) {
            if (!near[q - q0] || !block_new_pose_[q]) continue;
            const Circle &e = ego_bounds_.c[eb + q], &o = co_bounds_.c[cb + q];
            const double bx = e.cx - o.cx, by = e.cy - o.cy, br = e.r + o.r + reach;
            if (bx * bx + by * by > br * br) continue;  // the whole block is apart
            if (first_overlap) {  // the block's steps in SIMD lanes, the same test
              const int n = first_overlap(ego_track, co_track, block_begin_[q], block_begin_[q + 1],
                                          reach2, readable);
              if (n >= 0) hit = n + 1;
              continue;
            }
            for (int n = block_begin_[q]; n < block_begin_[q + 1]; ++n) {
              const double dx = co_.x[cj + n] - ego_.x[ei + n], dy = co_.y[cj + n] - ego_.y[ei + n];
              if (dx * dx + dy * dy > reach2) continue;
              const core::OrientedBox<double> a{ego_.x[ei + n],   ego_.y[ei + n], ego_cos_[ei + n],
                                                ego_sin_[ei + n], ego_hl,         ego_hw};
              const core::OrientedBox<double> b{co_.x[cj + n],   co_.y[cj + n],  co_cos_[cj + n],
                                                co_sin_[cj + n], co.half_length, co.half_width};
              if (core::BoxesOverlap(a, b)) {
                hit = n + 1;
                break;
              }
            }
          }
        }
        if (still) still_hit[j - t.j0] = hit;
        if (hit > 0) {
          for (int p = 0; p < width; ++p) {
            (*first_step)[static_cast<size_t>(first + p) * n_co + j] =
                static_cast<std::int16_t>(hit);
          }
        } else if (!still) {
          next.push_back(j);
        }
      }
      if (still || next.empty() || k + 1 >= K) return;
      for (int c = 0; c < L; ++c) self(self, k + 1, group * L + c);
    };
    for (int g = 0; g < L; ++g) walk(walk, 0, g);
  });
}

}  // namespace criticality
