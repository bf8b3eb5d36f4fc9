// ParallelFor (src/parallel_for.h): every index once whatever the thread count, errors passed
// on, and the helper threads kept from one call to the next instead of started for each.
#include "src/parallel_for.h"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <thread>
#include <vector>

namespace criticality::internal {
namespace {

TEST(ParallelFor, EveryIndexOnceWhateverTheThreads) {
  for (int threads : {1, 2, 3, 8}) {
    for (int n : {0, 1, 7, 1000}) {
      std::vector<std::atomic<int>> seen(n);
      ParallelFor(n, threads, [&](int begin, int end) {
        for (int i = begin; i < end; ++i) seen[i]++;
      });
      for (int i = 0; i < n; ++i) EXPECT_EQ(seen[i].load(), 1) << threads << " " << n << " " << i;
    }
  }
}

thread_local int calls_on_this_thread = 0;

TEST(ParallelFor, HelperThreadsAreKeptAcrossCalls) {
  // Each part counts the calls its thread has served: a helper started for every call would
  // count 1 each time; a kept one counts on.
  const int threads = 3, calls = 20;
  int most = 0;
  for (int c = 0; c < calls; ++c) {
    std::vector<int> counts(threads, 0);
    CallersPool().Run(threads, [&](int part) { counts[part] = ++calls_on_this_thread; });
    for (int part = 1; part < threads; ++part) most = std::max(most, counts[part]);
  }
  EXPECT_GE(most, calls);  // the helpers served every call
}

TEST(ParallelFor, AnErrorInAChunkIsRethrownAndThePoolGoesOn) {
  EXPECT_THROW(ParallelFor(100, 3,
                           [](int begin, int) {
                             if (begin == 0) throw std::runtime_error("chunk 0");
                           }),
               std::runtime_error);
  std::atomic<int> sum{0};
  ParallelFor(100, 3, [&](int begin, int end) { sum += end - begin; });
  EXPECT_EQ(sum.load(), 100);
}

TEST(ParallelFor, DynamicTasksEachOnceAndErrorsRethrown) {
  for (int threads : {1, 2, 3, 8}) {
    for (int n : {0, 1, 7, 1000}) {
      std::vector<std::atomic<int>> seen(n);
      ParallelForDynamic(n, threads, [&](int i) { seen[i]++; });
      for (int i = 0; i < n; ++i) EXPECT_EQ(seen[i].load(), 1) << threads << " " << n << " " << i;
    }
  }
  EXPECT_THROW(ParallelForDynamic(100, 3,
                                  [](int i) {
                                    if (i == 50) throw std::runtime_error("task 50");
                                  }),
               std::runtime_error);
  std::atomic<int> sum{0};
  ParallelForDynamic(100, 3, [&](int) { ++sum; });
  EXPECT_EQ(sum.load(), 100);
}

TEST(ParallelFor, HelpersThatSleptTakeTheNextJob) {
  // Past the spin window the helpers sleep on the condition variable: a job must still reach
  // them (a lost wake-up would hang here, and the ctest timeout would fail it).
  for (int c = 0; c < 6; ++c) {
    CallersPool().SetSpin(c % 2 == 0);  // also with spinning off: they sleep at once
    std::this_thread::sleep_for(2 * WorkerPool::kSpin);
    std::atomic<int> sum{0};
    ParallelFor(64, 3, [&](int begin, int end) { sum += end - begin; });
    EXPECT_EQ(sum.load(), 64);
  }
  CallersPool().SetSpin(true);
}

}  // namespace
}  // namespace criticality::internal
