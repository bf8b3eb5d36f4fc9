#pragma once
// The CPU fast path: the same core functions as the reference, with threads over hypotheses and
// ego trajectories, cos/sin of every pose computed once, a bounding-circle rejection before the
// exact separating-axis test (it can only skip pairs that cannot overlap), and an early exit at
// a pair's first collision. Gives the same pair matrix as the reference, bit for bit.
#include "src/backend.h"

namespace criticality {

class CpuBackend final : public EstimatorBackend {
 public:
  explicit CpuBackend(int threads);
  void GenerateTrajectories(const internal::Problem& problem) override;
  void RecognizeCollisions(const internal::Problem& problem,
                           std::vector<std::int16_t>* first_step) override;
  int Threads() const override { return threads_; }
  const internal::TrajectoryStore& EgoTrajectories() const override { return ego_; }
  const internal::TrajectoryStore& CoTrajectories() const override { return co_; }

 private:
  int threads_;
  internal::TrajectoryStore ego_;
  internal::TrajectoryStore co_;
  std::vector<double> ego_cos_, ego_sin_, co_cos_, co_sin_;
};

}  // namespace criticality
