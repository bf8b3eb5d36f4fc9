#include "cpu/reference_backend.h"

#include "core/oriented_box.h"
#include "core/trajectory_generation.h"

namespace criticality {

void ReferenceBackend::GenerateTrajectories(const internal::Problem& pb) {
  const int steps = pb.Steps();
  ego_.Resize(pb.EgoTrajectories(), steps);
  for (int i = 0; i < pb.EgoTrajectories(); ++i) {
    const size_t at = ego_.Offset(i);
    core::SimulateHypothesis(pb.ego, pb.sim, i / pb.ego.n_paths, i % pb.ego.n_paths, &ego_.x[at],
                             &ego_.y[at], &ego_.yaw[at]);
  }
  co_.Resize(pb.CoTrajectories(), steps);
  for (size_t o = 0; o < pb.cos.size(); ++o) {
    const core::HypothesisSet& h = pb.cos[o];
    for (int t = 0; t < h.Trajectories(); ++t) {
      const size_t at = co_.Offset(pb.co_offset[o] + t);
      core::SimulateHypothesis(h, pb.sim, t / h.n_paths, t % h.n_paths, &co_.x[at], &co_.y[at],
                               &co_.yaw[at]);
    }
  }
}

void ReferenceBackend::RecognizeCollisions(const internal::Problem& pb,
                                           std::vector<std::int16_t>* first_step) {
  const int n_ego = pb.EgoTrajectories(), n_co = pb.CoTrajectories(), steps = pb.Steps();
  first_step->assign(static_cast<size_t>(n_ego) * n_co, 0);
  for (int i = 0; i < n_ego; ++i) {
    for (int j = 0; j < n_co; ++j) {
      const core::HypothesisSet& co = pb.cos[pb.co_object_of[j]];
      std::int16_t first = 0;
      for (int n = 0; n < steps; ++n) {
        const size_t a = ego_.Offset(i) + n, b = co_.Offset(j) + n;
        const auto box_ego =
            core::MakeBox(ego_.x[a], ego_.y[a], ego_.yaw[a], pb.ego.half_length, pb.ego.half_width);
        const auto box_co =
            core::MakeBox(co_.x[b], co_.y[b], co_.yaw[b], co.half_length, co.half_width);
        if (core::BoxesOverlap(box_ego, box_co) && first == 0) {
          first = static_cast<std::int16_t>(n + 1);
        }
      }
      (*first_step)[static_cast<size_t>(i) * n_co + j] = first;
    }
  }
}

}  // namespace criticality
