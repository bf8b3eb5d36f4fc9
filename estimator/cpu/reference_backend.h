#pragma once
// The plain reference: the literal algorithm on one thread. Every hypothesis simulated on its
// own, every ego trajectory checked against every CO trajectory at every time step (no pruning,
// no early exit), the first overlapping step kept. Every faster path is checked against it.
#include "src/backend.h"

namespace criticality {

class ReferenceBackend final : public EstimatorBackend {
 public:
  void GenerateTrajectories(const internal::Problem& problem) override;
  void RecognizeCollisions(const internal::Problem& problem,
                           std::vector<std::int16_t>* first_step) override;
  int Threads() const override { return 1; }
  const internal::TrajectoryStore& EgoTrajectories() const override { return ego_; }
  const internal::TrajectoryStore& CoTrajectories() const override { return co_; }

 private:
  internal::TrajectoryStore ego_;
  internal::TrajectoryStore co_;
};

}  // namespace criticality
