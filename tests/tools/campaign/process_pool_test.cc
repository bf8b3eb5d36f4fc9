#include "tools/campaign/process_pool.h"

#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <map>

#include "tests/tools/campaign/campaign_test_util.h"

namespace criticality::campaign {
namespace {

using testing::ReadFile;
using testing::TempDir;

ChildSpec Sh(const TempDir& d, std::size_t id, const std::string& script) {
  return {id,
          {"/bin/sh", "-c", script},
          d.path(),
          d / ("out" + std::to_string(id)),
          d / ("err" + std::to_string(id))};
}

std::map<std::size_t, ChildResult> WaitAll(ProcessPool& pool, double timeout_s = 20) {
  std::map<std::size_t, ChildResult> out;
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (pool.running() > 0 && std::chrono::steady_clock::now() < end) {
    for (const ChildResult& r : pool.Wait(1.0)) out[r.id] = r;
  }
  return out;
}

TEST(ProcessPool, ExitCodesOutputFilesAndWorkingDirectory) {
  TempDir d;
  ProcessPool pool(4, 0, 1);
  pool.Start(Sh(d, 0, "echo hello; echo oops >&2; pwd > where; exit 0"));
  pool.Start(Sh(d, 1, "exit 3"));
  pool.Start(Sh(d, 2, "kill -USR1 $$"));
  pool.Start({3, {(d / "no-such-program").string()}, d.path(), d / "out3", d / "err3"});
  EXPECT_EQ(pool.running(), 4u);
  const auto r = WaitAll(pool);
  ASSERT_EQ(r.size(), 4u);
  EXPECT_EQ(r.at(0).exit_code, 0);
  EXPECT_EQ(ReadFile(d / "out0"), "hello\n");
  EXPECT_EQ(ReadFile(d / "err0"), "oops\n");
  EXPECT_EQ(ReadFile(d / "where"), d.path().string() + "\n");
  EXPECT_EQ(r.at(1).exit_code, 3);
  EXPECT_EQ(r.at(2).signal, SIGUSR1);
  EXPECT_EQ(r.at(2).exit_code, -1);
  EXPECT_EQ(r.at(3).exit_code, 127);
  EXPECT_NE(ReadFile(d / "err3").find("no-such-program"), std::string::npos);
  for (const auto& [id, res] : r) EXPECT_FALSE(res.timed_out);
}

TEST(ProcessPool, FullWhenEverySlotRuns) {
  TempDir d;
  ProcessPool pool(2, 0, 1);
  pool.Start(Sh(d, 0, "sleep 0.2"));
  EXPECT_FALSE(pool.full());
  pool.Start(Sh(d, 1, "sleep 0.2"));
  EXPECT_TRUE(pool.full());
  WaitAll(pool);
  EXPECT_EQ(pool.running(), 0u);
}

TEST(ProcessPool, TimeLimitSendsTermThenKill) {
  TempDir d;
  ProcessPool pool(2, 0.3, 0.3);
  pool.Start(Sh(d, 0, "exec sleep 30"));
  pool.Start(Sh(d, 1, "trap '' TERM; sleep 30"));
  const auto t0 = std::chrono::steady_clock::now();
  const auto r = WaitAll(pool);
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_EQ(r.size(), 2u);
  EXPECT_TRUE(r.at(0).timed_out);
  EXPECT_EQ(r.at(0).signal, SIGTERM);
  EXPECT_TRUE(r.at(1).timed_out);
  EXPECT_EQ(r.at(1).signal, SIGKILL);  // ignored SIGTERM: killed after kill_after_s
  EXPECT_LT(took, 10.0);
}

TEST(ProcessPool, StopAllEndsEveryChildAndMarksThem) {
  TempDir d;
  ProcessPool pool(2, 0, 0.5);
  pool.Start(Sh(d, 0, "exec sleep 30"));
  pool.Start(Sh(d, 1, "trap '' TERM; while :; do sleep 0.05; done"));
  const auto r = pool.StopAll();
  ASSERT_EQ(r.size(), 2u);
  for (const ChildResult& c : r) EXPECT_TRUE(c.stopped);
  EXPECT_EQ(pool.running(), 0u);
}

}  // namespace
}  // namespace criticality::campaign
