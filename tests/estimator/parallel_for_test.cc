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

TEST(ParallelFor, HelperThreadsAreKeptAcrossCalls) {
  // Each part records the thread that ran it: parts 1.. run on helpers (not the caller), and
  // the same helpers serve every call (a helper started for each call would have a new id).
  const int threads = 3, calls = 20;
  std::vector<std::thread::id> first(threads);
  for (int c = 0; c < calls; ++c) {
    std::vector<std::thread::id> ran(threads);
    CallersPool().Run(threads, [&](int part) { ran[part] = std::this_thread::get_id(); });
    EXPECT_EQ(ran[0], std::this_thread::get_id());
    for (int part = 1; part < threads; ++part) {
      EXPECT_NE(ran[part], std::this_thread::get_id()) << "part " << part << ", call " << c;
      if (c == 0) first[part] = ran[part];
      EXPECT_EQ(ran[part], first[part]) << "part " << part << ", call " << c;
    }
  }
  EXPECT_NE(first[1], first[2]);
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
