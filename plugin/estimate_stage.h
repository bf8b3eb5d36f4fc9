#pragma once
// Stage 3 of a step: every ego's scene estimated, all egos of the step as one batch
// (Estimator::EstimateBatch). On the GPU the batch is one call (one set of launches); on the
// CPU it is spread over --threads worker threads, each with its own single-threaded estimator,
// taking small chunks of the batch in turn (a batch of one scene uses one estimator with every
// thread instead, unless the hypothesis set is small). Results do not depend on the split: each
// estimate is deterministic.
#include <condition_variable>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "criticality/estimator.h"
#include "plugin/driver_options.h"
#include "plugin/scene_stage.h"

namespace criticality::plugin {

class EstimateStage {
 public:
  explicit EstimateStage(const DriverOptions& options);
  ~EstimateStage();
  EstimateStage(const EstimateStage&) = delete;
  EstimateStage& operator=(const EstimateStage&) = delete;
  /** results[k] belongs to batch.scenes[k]. */
  std::vector<Result> Run(const SceneBatch& batch);

 private:
  void Work(int worker);
  void RunChunks(int worker);

  std::unique_ptr<Estimator> whole_;  ///< every thread on one estimate (or the GPU batch)
  bool spread_{false};                ///< CPU: spread batches over workers
  bool small_{false};                 ///< estimates too small to split over threads
  std::vector<std::unique_ptr<Estimator>> single_;  ///< one single-threaded estimator per worker
  std::vector<std::thread> pool_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  long long generation_{0};
  int busy_{0};
  bool quit_{false};
  // The batch being worked on.
  const std::vector<Scene>* scenes_{nullptr};
  std::vector<Result>* results_{nullptr};
  size_t next_{0};
  std::vector<std::exception_ptr> errors_;
};

}  // namespace criticality::plugin
