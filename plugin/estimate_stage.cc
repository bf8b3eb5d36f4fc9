#include "plugin/estimate_stage.h"

#include <algorithm>

namespace criticality::plugin {
namespace {
constexpr size_t kChunk = 2;  // scenes a worker takes at a time
}

EstimateStage::EstimateStage(const DriverOptions& o) {
  whole_ = std::make_unique<Estimator>(o.params, o.estimator);
  const int threads = whole_->threads();
  spread_ = whole_->options().backend != Backend::kCuda && threads > 1;
  if (!spread_) return;
  // Ego hypothesis steps (with all three lanes): below ~50,000 an estimate takes well under a
  // millisecond on one thread, and starting threads for it costs more than it saves.
  const Params& p = o.params;
  double ego_steps = p.profiles * static_cast<double>(p.TimeSteps());
  for (size_t k = 0; k < p.path_sample_times_s.size(); ++k)
    ego_steps *= p.LateralSamplesThreeLanes();
  small_ = ego_steps < 5e4;
  EstimatorOptions one = whole_->options();
  one.threads = 1;
  for (int k = 0; k < threads; ++k) single_.push_back(std::make_unique<Estimator>(o.params, one));
  errors_.resize(threads);
  for (int k = 1; k < threads; ++k) pool_.emplace_back([this, k] { Work(k); });
}

EstimateStage::~EstimateStage() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    quit_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : pool_) t.join();
}

void EstimateStage::RunChunks(int worker) {
  try {
    for (;;) {
      size_t begin;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        begin = next_;
        next_ = std::min(scenes_->size(), next_ + kChunk);
      }
      if (begin >= scenes_->size()) return;
      const size_t end = std::min(scenes_->size(), begin + kChunk);
      const std::vector<Scene> chunk(scenes_->begin() + begin, scenes_->begin() + end);
      std::vector<Result> r = single_[worker]->EstimateBatch(chunk);
      for (size_t k = begin; k < end; ++k) (*results_)[k] = std::move(r[k - begin]);
    }
  } catch (...) {
    errors_[worker] = std::current_exception();
  }
}

void EstimateStage::Work(int worker) {
  long long seen = 0;
  for (;;) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return quit_ || generation_ != seen; });
      if (quit_) return;
      seen = generation_;
    }
    RunChunks(worker);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      --busy_;
    }
    done_.notify_one();
  }
}

std::vector<Result> EstimateStage::Run(const SceneBatch& batch) {
  if (!spread_) return whole_->EstimateBatch(batch.scenes);
  if (batch.scenes.size() == 1) {
    // One scene: every thread on it, unless it is too small to pay for starting threads.
    return (small_ ? single_.front() : whole_)->EstimateBatch(batch.scenes);
  }
  std::vector<Result> results(batch.scenes.size());
  {
    std::lock_guard<std::mutex> lock(mutex_);
    scenes_ = &batch.scenes;
    results_ = &results;
    next_ = 0;
    busy_ = static_cast<int>(pool_.size());
    ++generation_;
    std::fill(errors_.begin(), errors_.end(), nullptr);
  }
  wake_.notify_all();
  RunChunks(0);
  {
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [&] { return busy_ == 0; });
  }
  for (const std::exception_ptr& e : errors_) {
    if (e) std::rethrow_exception(e);
  }
  return results;
}

}  // namespace criticality::plugin
