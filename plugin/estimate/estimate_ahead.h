#pragma once
// The estimate of one step on a thread of its own, so that the loop can let SUMO make the next
// step meanwhile (pipelined driver, plugin/README.md "Pipelining"). One estimate at a time: Start
// hands over a batch, Finish waits for its results. The thread is started once and kept, and the
// estimator's own helper threads stay with it (they are kept per calling thread), so no step
// starts a thread. The results are those of EstimateStage::Run on the same batch, bit for bit:
// only the thread that computes them differs.
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "plugin/estimate/estimate_stage.h"

namespace criticality::plugin {

class EstimateAhead {
 public:
  explicit EstimateAhead(EstimateStage* stage);
  /** Waits for an estimate still running (its results are dropped), then ends the thread. */
  ~EstimateAhead();
  EstimateAhead(const EstimateAhead&) = delete;
  EstimateAhead& operator=(const EstimateAhead&) = delete;

  /** Starts estimating `batch`, which must stay unchanged until Finish returns. Only when
   *  idle (not busy()). */
  void Start(const SceneBatch* batch);
  /** Whether an estimate was started and not yet finished. */
  bool busy() const { return busy_; }
  /** Waits for the started estimate; rethrows what it threw. `ms`: the estimate's own wall
   *  time, `wait_ms`: how long this call waited for it. */
  std::vector<Result> Finish(double* ms, double* wait_ms);

 private:
  void Loop();

  EstimateStage* stage_;
  std::mutex m_;
  std::condition_variable cv_;
  const SceneBatch* job_{nullptr};  ///< set: to be estimated
  bool done_{false}, stop_{false};
  bool busy_{false};  ///< the loop's view: between Start and Finish
  std::vector<Result> results_;
  std::exception_ptr error_;
  double ms_{0.0};
  std::thread thread_;
};

}  // namespace criticality::plugin
