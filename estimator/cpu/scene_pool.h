#pragma once
// The cpu backend's batch parallelism (Estimator::EstimateBatch with threads > 1): a persistent
// pool that spreads the scenes of a batch over `workers` workers, the caller's thread being
// worker 0. Each worker owns a single-threaded Estimator and takes chunks of kChunk scenes in
// turn, so that a worker with cheap scenes takes more of them. Whole estimates side by side
// need no synchronisation inside an estimate, which the threads of one estimate do per module
// (bench/RESULTS.md, "Driver": 2 threads on one estimate were slower than 1 on busy cores).
// The threads start with the pool and wait between batches: no thread start-up per batch.
// Every estimate runs whole on one worker and is deterministic, so results do not depend on
// the split: results[k] is Estimate(scenes[k]) bit for bit, but for Result::times. The workers
// share one ObjectPathsCache: another road user that several scenes of the batch see is
// simulated once (whichever worker comes first; the copies are bit for bit the same).
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "cpu/object_paths_cache.h"
#include "criticality/estimator.h"

namespace criticality {

class ScenePool {
 public:
  /** Scenes a worker takes at a time: small, so that uneven scenes balance; more than one, so
   *  that workers do not queue on the pool's lock for every small estimate. */
  static constexpr size_t kChunk = 2;

  /** `workers` >= 1 estimators with `params` and `options` (resolved: backend cpu), each on
   *  one thread (options.threads is replaced by 1), and workers - 1 threads. */
  ScenePool(const Params& params, const EstimatorOptions& options, int workers);
  /** Stops and joins the threads. */
  ~ScenePool();
  ScenePool(const ScenePool&) = delete;
  ScenePool& operator=(const ScenePool&) = delete;

  /** results[k] is Estimate(scenes[k]) on some worker. A batch of one scene runs on the
   *  caller's thread only (worker 0's estimator), without waking the pool.
   *  @throws what the first failing scene in batch order threw (InputError, WorkloadError...);
   *  no further chunks are handed out once a scene failed. The pool stays usable. */
  std::vector<Result> EstimateBatch(const std::vector<Scene>& scenes);

  int workers() const { return static_cast<int>(estimators_.size()); }

 private:
  // A pool thread: waits for a batch, runs chunks of it, reports that it is done.
  void Work(int worker);
  // Takes chunks of the current batch until none is left (or a scene failed).
  void RunChunks(int worker);
  void Stop();

  /** Other road users' paths the workers' scenes share within a batch (null: off); declared
   *  before the estimators, whose backends point to it, so that it outlives them. */
  std::unique_ptr<internal::ObjectPathsCache> paths_cache_;
  std::vector<std::unique_ptr<Estimator>> estimators_;  ///< one per worker, single-threaded
  std::vector<std::thread> threads_;                    ///< workers 1..n-1
  std::mutex mutex_;
  std::condition_variable wake_;  ///< a new batch (generation_) or quit_
  std::condition_variable done_;  ///< busy_ reached 0
  long long generation_{0};       ///< batches started so far
  int busy_{0};                   ///< pool threads still on the current batch
  bool quit_{false};
  // The current batch, under mutex_ (results_ entries are written by the worker that took
  // their chunk, and read by the caller after busy_ reached 0).
  const std::vector<Scene>* scenes_{nullptr};
  std::vector<Result>* results_{nullptr};
  size_t next_{0};  ///< first scene not handed out yet
  size_t failed_at_{0};
  std::exception_ptr error_;  ///< of the failing scene with the lowest index, failed_at_
};

}  // namespace criticality
