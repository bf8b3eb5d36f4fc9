#pragma once
// Splits [0, n) into contiguous chunks run on `threads` threads (the caller's thread included).
// Each index is processed by exactly one thread, so results written per index are the same
// whatever the thread count: determinism is kept by reducing afterwards in index order.
// The helper threads are started once per calling thread and kept (WorkerPool), so that an
// estimate's five parallel loops do not each start and join threads.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace criticality::internal {

/** Helper threads that wait for jobs: Run(parts, job) runs job(t) for t in [0, parts), t = 0 on
 *  the calling thread and the others on helpers (started when first needed, kept until the pool
 *  is destroyed), and returns when every part is done. One caller at a time.
 *  Waking a sleeping thread costs tens of microseconds on virtual machines (75 us measured on
 *  the development VM, per call), several times per estimate: so a helper, and the caller
 *  waiting for the helpers, first spin for up to kSpin on the job counter before they sleep
 *  on the condition variable. An estimate's parallel loops follow each other within that time;
 *  Rest() at the end of an estimate sends spinning helpers to sleep at once, so that they do
 *  not take a core from SUMO (or anything else) between estimates. */
class WorkerPool {
 public:
  static constexpr std::chrono::microseconds kSpin{250};

  WorkerPool() = default;
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;
  ~WorkerPool() {
    {
      std::lock_guard<std::mutex> lock(m_);
      stop_ = true;
    }
    start_.notify_all();
    for (std::thread& t : threads_) t.join();
  }

  void Run(int parts, const std::function<void(int)>& job) {
    {
      std::lock_guard<std::mutex> lock(m_);
      // A new helper starts from the current generation, so it takes the job published below.
      while (static_cast<int>(threads_.size()) < parts - 1) {
        const int index = static_cast<int>(threads_.size()) + 1;
        threads_.emplace_back(&WorkerPool::Loop, this, index, generation_.load());
      }
      job_ = &job;
      parts_ = parts;
      resting_.store(false);
      pending_.store(parts - 1);
      generation_.fetch_add(1);
    }
    start_.notify_all();
    std::exception_ptr error;
    try {
      job(0);
    } catch (...) {
      error = std::current_exception();  // the helpers still use job: wait for them first
    }
    SpinUntil([&] { return pending_.load(std::memory_order_acquire) == 0; });
    std::unique_lock<std::mutex> lock(m_);
    done_.wait(lock, [&] { return pending_.load() == 0; });
    job_ = nullptr;
    if (error) std::rethrow_exception(error);
  }

  /** Helpers waiting for a job sleep now instead of spinning (until the next Run). */
  void Rest() { resting_.store(true, std::memory_order_release); }
  /** Whether the helpers and the waiting caller spin before they sleep (default true). */
  void SetSpin(bool spin) { spin_.store(spin, std::memory_order_release); }

 private:
  // Busy-waits until ready() or kSpin has passed (not at all when spinning is off).
  template <class Ready>
  void SpinUntil(Ready ready) const {
    if (!spin_.load(std::memory_order_acquire)) return;
    const auto until = std::chrono::steady_clock::now() + kSpin;
    for (int n = 0;; ++n) {
      if (ready()) return;
      if ((n & 63) == 63 && std::chrono::steady_clock::now() > until) return;
    }
  }

  void Loop(int index, std::uint64_t seen) {
    for (;;) {
      const std::function<void(int)>* job = nullptr;
      SpinUntil([&] {
        return generation_.load(std::memory_order_acquire) != seen ||
               resting_.load(std::memory_order_acquire);
      });
      {
        std::unique_lock<std::mutex> lock(m_);
        start_.wait(lock, [&] { return stop_ || generation_.load() != seen; });
        if (stop_) return;
        seen = generation_.load();
        if (index >= parts_) continue;  // not needed for this job
        job = job_;
      }
      (*job)(index);
      {
        std::lock_guard<std::mutex> lock(m_);
        if (pending_.fetch_sub(1) == 1) done_.notify_one();
      }
    }
  }

  std::mutex m_;
  std::condition_variable start_, done_;
  std::vector<std::thread> threads_;
  const std::function<void(int)>* job_{nullptr};
  int parts_{0};
  std::atomic<int> pending_{0};
  std::atomic<std::uint64_t> generation_{0};
  std::atomic<bool> resting_{false};
  std::atomic<bool> spin_{true};
  bool stop_{false};
};

/** The calling thread's own pool (ParallelFor from several threads at once stays correct). */
inline WorkerPool& CallersPool() {
  thread_local WorkerPool pool;
  return pool;
}

inline int ResolveThreads(int requested) {
  if (requested > 0) return requested;
  const unsigned hw = std::thread::hardware_concurrency();
  return hw == 0 ? 1 : static_cast<int>(hw);
}

/** fn(begin, end) on disjoint chunks; rethrows the first exception a chunk threw. */
template <typename Fn>
void ParallelFor(int n, int threads, Fn fn) {
  threads = std::max(1, std::min(threads, n));
  if (threads <= 1) {
    if (n > 0) fn(0, n);
    return;
  }
  // Interleaved small chunks balance uneven work (e.g. pairs far apart exit early).
  const int chunk = std::max(1, n / (threads * 8));
  std::vector<std::exception_ptr> errors(threads);
  auto worker = [&](int t) {
    try {
      for (int begin = t * chunk; begin < n; begin += threads * chunk) {
        fn(begin, std::min(n, begin + chunk));
      }
    } catch (...) {
      errors[t] = std::current_exception();
    }
  };
  CallersPool().Run(threads, worker);
  for (const std::exception_ptr& e : errors) {
    if (e) std::rethrow_exception(e);
  }
}

/** fn(i) for every i in [0, n), each index taken by whichever thread is free next: for
 *  tasks of very uneven cost whose results do not depend on the thread that runs them (each
 *  writes only its own outputs). Rethrows the first exception a task threw. */
template <typename Fn>
void ParallelForDynamic(int n, int threads, Fn fn) {
  threads = std::max(1, std::min(threads, n));
  if (threads <= 1) {
    for (int i = 0; i < n; ++i) fn(i);
    return;
  }
  std::atomic<int> next{0};
  std::vector<std::exception_ptr> errors(threads);
  auto worker = [&](int t) {
    try {
      for (int i = next.fetch_add(1); i < n; i = next.fetch_add(1)) fn(i);
    } catch (...) {
      errors[t] = std::current_exception();
      next.store(n);  // the others stop taking tasks
    }
  };
  CallersPool().Run(threads, worker);
  for (const std::exception_ptr& e : errors) {
    if (e) std::rethrow_exception(e);
  }
}

}  // namespace criticality::internal
