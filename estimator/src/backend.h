#pragma once
// What a backend does: trajectory generation and collision recognition (the two modules whose
// iteration differs between backends). Street data processing and risk assessment are shared
// host code; risk assessment is told how many threads it may use.
#include <cstdint>
#include <vector>

#include "src/problem.h"
#include "src/trajectory_store.h"

namespace criticality {

class EstimatorBackend {
 public:
  virtual ~EstimatorBackend() = default;
  /** Simulates every ego and CO hypothesis of `problem`. */
  virtual void GenerateTrajectories(const internal::Problem& problem) = 0;
  /** Fills the ego-major pair matrix (see AssessRisk) from the last generated trajectories. */
  virtual void RecognizeCollisions(const internal::Problem& problem,
                                   std::vector<std::int16_t>* first_step) = 0;
  virtual int Threads() const = 0;
  /** The last generated trajectories (for tests and tools). */
  virtual const internal::TrajectoryStore& EgoTrajectories() const = 0;
  virtual const internal::TrajectoryStore& CoTrajectories() const = 0;
};

}  // namespace criticality
