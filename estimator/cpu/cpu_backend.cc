#include "cpu/cpu_backend.h"

#include <cmath>

#include "core/oriented_box.h"
#include "core/trajectory_generation.h"
#include "src/parallel_for.h"

namespace criticality {
namespace {

void CacheTrig(const internal::TrajectoryStore& t, std::vector<double>* c, std::vector<double>* s,
               int threads) {
  c->resize(t.yaw.size());
  s->resize(t.yaw.size());
  internal::ParallelFor(static_cast<int>(t.trajectories), threads, [&](int begin, int end) {
    for (size_t k = t.Offset(begin); k < t.Offset(end); ++k) {
      (*c)[k] = std::cos(t.yaw[k]);
      (*s)[k] = std::sin(t.yaw[k]);
    }
  });
}

}  // namespace

CpuBackend::CpuBackend(int threads) : threads_(internal::ResolveThreads(threads)) {}

void CpuBackend::GenerateTrajectories(const internal::Problem& pb) {
  const int steps = pb.Steps();
  ego_.Resize(pb.EgoTrajectories(), steps);
  co_.Resize(pb.CoTrajectories(), steps);
  const int n_ego = pb.EgoTrajectories();
  // One index space over ego then CO hypotheses.
  internal::ParallelFor(n_ego + pb.CoTrajectories(), threads_, [&](int begin, int end) {
    for (int g = begin; g < end; ++g) {
      if (g < n_ego) {
        const size_t at = ego_.Offset(g);
        core::SimulateHypothesis(pb.ego, pb.sim, g / pb.ego.n_paths, g % pb.ego.n_paths,
                                 &ego_.x[at], &ego_.y[at], &ego_.yaw[at]);
      } else {
        const int j = g - n_ego;
        const int o = pb.co_object_of[j];
        const core::HypothesisSet& h = pb.cos[o];
        const int t = j - pb.co_offset[o];
        const size_t at = co_.Offset(j);
        core::SimulateHypothesis(h, pb.sim, t / h.n_paths, t % h.n_paths, &co_.x[at], &co_.y[at],
                                 &co_.yaw[at]);
      }
    }
  });
  CacheTrig(ego_, &ego_cos_, &ego_sin_, threads_);
  CacheTrig(co_, &co_cos_, &co_sin_, threads_);
}

void CpuBackend::RecognizeCollisions(const internal::Problem& pb,
                                     std::vector<std::int16_t>* first_step) {
  const int n_ego = pb.EgoTrajectories(), n_co = pb.CoTrajectories(), steps = pb.Steps();
  first_step->assign(static_cast<size_t>(n_ego) * n_co, 0);
  const double ego_hl = pb.ego.half_length, ego_hw = pb.ego.half_width;
  const double ego_r = core::BoundingRadius(ego_hl, ego_hw);
  internal::ParallelFor(n_ego, threads_, [&](int begin, int end) {
    for (int i = begin; i < end; ++i) {
      const size_t ei = ego_.Offset(i);
      const double* ex = &ego_.x[ei];
      const double* ey = &ego_.y[ei];
      const double* ec = &ego_cos_[ei];
      const double* es = &ego_sin_[ei];
      std::int16_t* row = first_step->data() + static_cast<size_t>(i) * n_co;
      for (int j = 0; j < n_co; ++j) {
        const core::HypothesisSet& co = pb.cos[pb.co_object_of[j]];
        // Centres farther apart than the sum of the bounding radii cannot overlap; the small
        // margin keeps exactly touching boxes for the exact test.
        const double reach = ego_r + core::BoundingRadius(co.half_length, co.half_width) + 1e-9;
        const double reach2 = reach * reach;
        const size_t cj = co_.Offset(j);
        const double* cx = &co_.x[cj];
        const double* cy = &co_.y[cj];
        for (int n = 0; n < steps; ++n) {
          const double dx = cx[n] - ex[n], dy = cy[n] - ey[n];
          if (dx * dx + dy * dy > reach2) continue;
          const core::OrientedBox<double> a{ex[n], ey[n], ec[n], es[n], ego_hl, ego_hw};
          const core::OrientedBox<double> b{cx[n], cy[n], co_cos_[cj + n], co_sin_[cj + n],
                                            co.half_length, co.half_width};
          if (core::BoxesOverlap(a, b)) {
            row[j] = static_cast<std::int16_t>(n + 1);
            break;
          }
        }
      }
    }
  });
}

}  // namespace criticality
