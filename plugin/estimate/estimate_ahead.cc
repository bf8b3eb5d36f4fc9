#include "plugin/estimate/estimate_ahead.h"

#include <chrono>
#include <stdexcept>

namespace criticality::plugin {
namespace {
using Clock = std::chrono::steady_clock;
double Ms(Clock::duration d) { return std::chrono::duration<double, std::milli>(d).count(); }
}  // namespace

EstimateAhead::EstimateAhead(EstimateStage* stage)
    : stage_(stage), thread_(&EstimateAhead::Loop, this) {}

EstimateAhead::~EstimateAhead() {
  {
    std::lock_guard<std::mutex> lock(m_);
    stop_ = true;
    job_ = nullptr;  // one not yet begun is not begun
  }
  cv_.notify_all();
  thread_.join();  // the loop finishes a running estimate first
}

void EstimateAhead::Start(const SceneBatch* batch) {
  if (busy_) throw std::logic_error("EstimateAhead::Start while an estimate runs");
  {
    std::lock_guard<std::mutex> lock(m_);
    job_ = batch;
    done_ = false;
    error_ = nullptr;
  }
  busy_ = true;
  cv_.notify_all();
}

std::vector<Result> EstimateAhead::Finish(double* ms, double* wait_ms) {
  if (!busy_) throw std::logic_error("EstimateAhead::Finish without Start");
  const Clock::time_point t0 = Clock::now();
  std::unique_lock<std::mutex> lock(m_);
  cv_.wait(lock, [&] { return done_; });
  busy_ = false;
  if (wait_ms) *wait_ms = Ms(Clock::now() - t0);
  if (ms) *ms = ms_;
  if (error_) std::rethrow_exception(error_);
  return std::move(results_);
}

void EstimateAhead::Loop() {
  std::unique_lock<std::mutex> lock(m_);
  for (;;) {
    cv_.wait(lock, [&] { return stop_ || job_ != nullptr; });
    if (job_ == nullptr) return;  // stop_, nothing left to do
    const SceneBatch* batch = job_;
    job_ = nullptr;
    lock.unlock();
    std::vector<Result> results;
    std::exception_ptr error;
    const Clock::time_point t0 = Clock::now();
    try {
      results = stage_->Run(*batch);
    } catch (...) {
      error = std::current_exception();
    }
    const double ms = Ms(Clock::now() - t0);
    lock.lock();
    results_ = std::move(results);
    error_ = error;
    ms_ = ms;
    done_ = true;
    cv_.notify_all();
  }
}

}  // namespace criticality::plugin
