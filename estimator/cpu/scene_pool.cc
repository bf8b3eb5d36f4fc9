#include "cpu/scene_pool.h"

#include <algorithm>

namespace criticality {

ScenePool::ScenePool(const Params& params, const EstimatorOptions& options, int workers) {
  EstimatorOptions one = options;
  one.threads = 1;
  if (options.shared_object_paths_mib > 0) {
    paths_cache_ = std::make_unique<internal::ObjectPathsCache>(
        static_cast<size_t>(options.shared_object_paths_mib) << 20);
  }
  for (int k = 0; k < std::max(1, workers); ++k) {
    estimators_.push_back(std::make_unique<Estimator>(params, one));
    estimators_.back()->SharePaths(paths_cache_.get());
  }
  try {
    for (int k = 1; k < workers; ++k) threads_.emplace_back([this, k] { Work(k); });
  } catch (...) {
    Stop();  // the threads already started must not outlive the pool
    throw;
  }
}

ScenePool::~ScenePool() { Stop(); }

void ScenePool::Stop() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    quit_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : threads_) t.join();
  threads_.clear();
}

void ScenePool::RunChunks(int worker) {
  Estimator& estimator = *estimators_[worker];
  const size_t n = scenes_->size();
  for (;;) {
    size_t begin;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      // After a failure the batch is lost: the remaining chunks are not worth estimating.
      // Every chunk before the failing scene was handed out already (chunks go in order), so
      // the error kept below is still the first in batch order, whatever the timing.
      if (next_ >= n || error_) return;
      begin = next_;
      next_ = std::min(n, next_ + kChunk);
    }
    const size_t end = std::min(n, begin + kChunk);
    for (size_t k = begin; k < end; ++k) {
      try {
        (*results_)[k] = estimator.Estimate((*scenes_)[k]);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!error_ || k < failed_at_) {
          error_ = std::current_exception();
          failed_at_ = k;
        }
        return;
      }
    }
  }
}

void ScenePool::Work(int worker) {
  long long seen = 0;
  for (;;) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return quit_ || generation_ != seen; });
      if (quit_) return;
      seen = generation_;
    }
    RunChunks(worker);
    bool last;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      last = --busy_ == 0;
    }
    if (last) done_.notify_one();
  }
}

std::vector<Result> ScenePool::EstimateBatch(const std::vector<Scene>& scenes) {
  // What the batch's scenes shared is forgotten after it (also when a scene throws): memory
  // holds one batch at most.
  struct ClearAfter {
    internal::ObjectPathsCache* cache;
    ~ClearAfter() {
      if (cache) cache->Clear();
    }
  } clear_after{paths_cache_.get()};
  std::vector<Result> results(scenes.size());
  if (scenes.size() <= 1 || threads_.empty()) {
    // Nothing to spread: worker 0's estimator on the caller's thread. A lone scene has no one
    // to share its objects with, so it stores no copies of them.
    struct Lone {  // detaches the cache for one scene, and attaches it again (also on a throw)
      Estimator& worker;
      internal::ObjectPathsCache* cache;
      ~Lone() { worker.SharePaths(cache); }
    } lone{*estimators_[0], paths_cache_.get()};
    if (scenes.size() == 1) lone.worker.SharePaths(nullptr);
    for (size_t k = 0; k < scenes.size(); ++k) results[k] = lone.worker.Estimate(scenes[k]);
    return results;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    scenes_ = &scenes;
    results_ = &results;
    next_ = 0;
    error_ = nullptr;
    failed_at_ = 0;
    busy_ = static_cast<int>(threads_.size());
    ++generation_;
  }
  wake_.notify_all();
  RunChunks(0);
  std::exception_ptr error;
  {
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [&] { return busy_ == 0; });
    scenes_ = nullptr;
    results_ = nullptr;
    error = error_;
    error_ = nullptr;
  }
  if (error) std::rethrow_exception(error);
  return results;
}

}  // namespace criticality
