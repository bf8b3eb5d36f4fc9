#pragma once
// What a backend does: trajectory generation, collision recognition and, by default on the
// host, risk assessment (Run). Street data processing and hypothesis set-up are shared host
// code (BuildProblem). The CUDA backend overrides Run to keep all three on the device
// (problems with carriages fold their pair matrix and assess their risk on the host,
// AssessBodies).
#include <cstdint>
#include <vector>

#include "criticality/params.h"
#include "criticality/result.h"
#include "src/problem.h"
#include "src/trajectory_store.h"

namespace criticality {
namespace internal {
class ObjectPathsCache;
}

class EstimatorBackend {
 public:
  virtual ~EstimatorBackend() = default;
  /** Simulates every ego and CO hypothesis of `problem`. */
  virtual void GenerateTrajectories(const internal::Problem& problem) = 0;
  /** Fills the ego-major pair matrix (see AssessRisk) from the last generated trajectories. */
  virtual void RecognizeCollisions(const internal::Problem& problem,
                                   std::vector<std::int16_t>* first_step) = 0;
  virtual int Threads() const = 0;
  /** Lets the backend take other road users' paths that another scene of the batch simulated
   *  from `cache`, and store its own there (null: none). Default: not used (the reference and
   *  the CUDA backend simulate every scene's). */
  virtual void ShareObjectPaths(internal::ObjectPathsCache* /*cache*/) {}
  /** The last generated trajectories (for tests and tools). */
  virtual const internal::TrajectoryStore& EgoTrajectories() const = 0;
  virtual const internal::TrajectoryStore& CoTrajectories() const = 0;
  /** Trajectories, collisions and risk of `problem` into `result`, with module times.
   *  Default: GenerateTrajectories, RecognizeCollisions (every set, carriages included), then
   *  the host risk assessment (AssessBodies: carriages folded into their vehicles first). */
  virtual void Run(const internal::Problem& problem, const Params& params, bool keep_pair_matrix,
                   Result* result);
  /** Run on every problem of a batch. Default: one after the other; the CUDA backend runs the
   *  whole batch in one set of launches. */
  virtual void RunBatch(const std::vector<const internal::Problem*>& problems, const Params& params,
                        bool keep_pair_matrix, std::vector<Result>* results) {
    for (size_t k = 0; k < problems.size(); ++k) {
      Run(*problems[k], params, keep_pair_matrix, &(*results)[k]);
    }
  }
};

}  // namespace criticality
