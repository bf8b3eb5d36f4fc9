#pragma once
// Splits [0, n) into contiguous chunks run on `threads` threads (the caller's thread included).
// Each index is processed by exactly one thread, so results written per index are the same
// whatever the thread count: determinism is kept by reducing afterwards in index order.
#include <algorithm>
#include <exception>
#include <thread>
#include <vector>

namespace criticality::internal {

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
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker, t);
  worker(0);
  for (std::thread& th : pool) th.join();
  for (const std::exception_ptr& e : errors) {
    if (e) std::rethrow_exception(e);
  }
}

}  // namespace criticality::internal
