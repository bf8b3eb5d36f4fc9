#pragma once
// The CPU fast path: the same core functions as the reference, iterated so that no work is
// done twice and far-apart pairs are skipped cheaply; it must give the reference's pair matrix
// bit for bit (tests/estimator/backends_agree_test.cc).
//  - Ego paths that share their first path sections share the simulation of that prefix: the
//    section tree (7 -> 49 -> 343 paths) is simulated once per node.
//    A node's span is simulated on its group's first path only; EgoTrajectories() copies the
//    shared prefixes to the group's other paths when it is asked for them.
//  - Collision recognition walks the same tree for each (ego profile, object, group of up to
//    64 of its trajectories; threads take these tasks as they come free), with the group's
//    trajectories still in play: a node's span is checked once on its representative path; a hit
//    there is every descendant's first collision (their poses are identical up to it, and no
//    earlier span hit), and that trajectory leaves play below the node; the others are checked on
//    the children's spans.
//  - Each span is split into blocks of a few steps with a bounding circle per trajectory and
//    block: when two blocks' circles (grown by the boxes' bounding radii) are apart, the block
//    is skipped; otherwise each step gets a bounding-circle test, then the exact SAT test.
//    Per node, the blocks where the object's circle (around all its trajectories) is apart
//    from the node's are skipped for every trajectory of the group.
//  - Swept bounds prune whole subtrees: each tree node has a circle around every pose of all
//    its descendant paths from its span to the horizon, each CO trajectory and each object
//    one around its poses over the same steps; when they are apart, no descendant can
//    collide (with that trajectory, or with any of the object's).
//  - Subtrees out of reach are not simulated (issue 23, item 2): the other vehicles' and
//    pedestrians' trajectories are simulated first; before a tree node below the first level is
//    simulated, the ego's reach from its start over the rest of the horizon
//    (internal::EgoReachAfter, from its parent's end state, by the end of each block) is
//    checked against each object's circle of that block (all its trajectories), once for all
//    children of a parent; when it meets none in any block, no descendant path can collide,
//    and the subtree is neither simulated nor checked. The pair
//    matrix is the same (its entries there are 0 either way); EgoTrajectories() then holds NaN
//    for the paths of skipped subtrees (ReferenceBackend has every pose).
//  - Still subtrees (every path below a node holds the node's first pose, bit for bit, to the
//    horizon: an ego waiting at a standstill under a braking profile) are checked once along the
//    node's first path from its span to the horizon, for all the paths below, and siblings that
//    hold the same pose reuse those first hits: the same tests on the same poses.
//  - Other road users that another scene of the batch simulated already are copied from the
//    batch's ObjectPathsCache (cpu/object_paths_cache.h), bit for bit what simulating them gives.
//  - cos/sin of every pose computed once; threads over each level's packs of nodes and over the
//    collision tasks.
//  - With simd (the default), the nodes of one profile and level, and another vehicle's paths
//    of one profile, are simulated together in SIMD lanes (cpu/sibling_steps.h), with cos/sin
//    from vector math: the pair matrix then equals the reference's except for grazing
//    contacts.
#include <algorithm>
#include <vector>

#include "core/hypothesis_set.h"
#include "src/backend.h"

namespace criticality {

class CpuBackend final : public EstimatorBackend {
 public:
  /** @param simd sibling ego paths in SIMD lanes and vector cos/sin (EstimatorOptions::simd). */
  CpuBackend(int threads, bool simd, bool skip_out_of_reach = true);
  void GenerateTrajectories(const internal::Problem& problem) override;
  void RecognizeCollisions(const internal::Problem& problem,
                           std::vector<std::int16_t>* first_step) override;
  int Threads() const override { return threads_; }
  void ShareObjectPaths(internal::ObjectPathsCache* cache) override { paths_cache_ = cache; }
  /** Every ego path's poses (NaN in skipped subtrees): the shared prefixes are copied to each
   *  path of a node's group on the first call after GenerateTrajectories. */
  const internal::TrajectoryStore& EgoTrajectories() const override;
  const internal::TrajectoryStore& CoTrajectories() const override { return co_; }
  /** Tree nodes the last GenerateTrajectories skipped (out of reach, or below a skipped node),
   *  and the nodes whose reach it tested (below the first level, children of nodes that were
   *  simulated; 0 with skip_out_of_reach off). */
  int SkippedNodes() const { return skipped_nodes_; }
  /** Tree nodes the last GenerateTrajectories found still (every path below holds one pose). */
  int StillNodes() const {
    return static_cast<int>(std::count(node_still_.begin(), node_still_.end(), char{1}));
  }
  int CheckedNodes() const { return checked_nodes_; }

  /** Steps per collision block (bounding circles; one block's box tests go through the SIMD
   *  lanes together). 8 fills an AVX-512 vector of doubles; with 5 the city fleet spent about
   *  a fifth of its time in the lanes' box test, with most lanes empty (bench/RESULTS.md,
   *  twelfth stop). Any value gives the same answers. */
  static constexpr int kBlockSteps = 8;

 private:
  // Bounding circles of the centres of every trajectory over every block.
  struct Circle {
    double cx, cy, r;
  };
  struct BlockBounds {
    std::vector<Circle> c;  ///< [trajectory * blocks + block]: centre and radius together
  };
  // An axis-aligned box of centres (empty: x0 > x1).
  struct Box {
    double x0{1e300}, x1{-1e300}, y0{1e300}, y1{-1e300};
  };
  /** Sizes b for t's trajectories (FinishSpan fills it). */
  void ResizeBounds(const internal::TrajectoryStore& t, BlockBounds* b) const;
  // cos/sin of steps [n0, n1) (unless trig_done: the simulation wrote them) and bounds of
  // blocks [q0, q1) of one trajectory; span_box (unless null): the box around their poses.
  void FinishSpan(const internal::TrajectoryStore& t, std::vector<double>* c,
                  std::vector<double>* s, BlockBounds* b, int trajectory, int n0, int n1, int q0,
                  int q1, bool trig_done = false, Box* span_box = nullptr) const;

  int threads_;
  bool simd_;
  internal::ObjectPathsCache* paths_cache_{nullptr};  // not owned; null: none
  bool skip_out_of_reach_;
  int skipped_nodes_{0}, checked_nodes_{0};
  // Per (profile, tree node): 1 when out of reach (not simulated, not checked).
  std::vector<char> node_skipped_;
  // Per (collision object set, block): a circle around every pose of all its trajectories in
  // the block.
  BlockBounds object_blocks_;
  // The last tree's shape, and whether EgoTrajectories() still has prefixes to copy.
  struct Tree {
    int n_profiles, n_paths, n_instants, n_lateral;
  } tree_{};
  mutable bool shared_prefixes_pending_{false};
  mutable internal::TrajectoryStore ego_;
  internal::TrajectoryStore co_;
  std::vector<double> ego_cos_, ego_sin_, co_cos_, co_sin_;
  // Step partition: instant k spans steps [boundary_[k], boundary_[k+1]); blocks split each
  // span; block_begin_[q] is block q's first step, phase_block_[k] the first block of span k.
  int boundary_[core::kMaxSampleInstants + 1]{};
  std::vector<int> block_begin_;
  std::vector<int> phase_block_;
  // Per block: 0 when every pose in it repeats one of an earlier block (held poses), so the
  // box tests skip it; 1 otherwise.
  std::vector<char> block_new_pose_;
  BlockBounds ego_bounds_, co_bounds_;
  // Swept bounds: node_bounds_ per (profile, tree node) (node index: the nodes of instant k
  // follow those of instant k-1, k's group g at node_offset_[k] + g); co_tail_ per (CO
  // trajectory, instant k) over steps [boundary_[k], n_steps).
  BlockBounds node_bounds_, co_tail_;
  // Per (profile, tree node): 1 when every path below it holds one pose from its span to the
  // horizon (a standstill: cpu/sibling_steps.cc), bit for bit, checked on the poses.
  std::vector<char> node_still_;
  // Per (profile, tree node): the box around its span's poses (FinishSpan's, for the sweep).
  std::vector<Box> node_span_box_;
  // object_tail_ per (collision object set, instant k): around its trajectories' co_tail_.
  BlockBounds object_tail_;
  int node_offset_[core::kMaxSampleInstants + 1]{};
};

}  // namespace criticality
