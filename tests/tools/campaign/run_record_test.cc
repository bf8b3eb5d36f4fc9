#include "tools/campaign/run_record.h"

#include <gtest/gtest.h>
#include <signal.h>

#include "tests/tools/campaign/campaign_test_util.h"

namespace criticality::campaign {
namespace {

using testing::TempDir;
using testing::WriteFile;

TEST(RunRecord, LastJsonLineNeedsAnObjectWithStatus) {
  TempDir d;
  EXPECT_TRUE(
      LastJsonLine(WriteFile(d / "a", "progress\n{\"status\":\"completed\",\"steps\":3}\n")));
  EXPECT_EQ((*LastJsonLine(d / "a"))["steps"], 3);
  EXPECT_FALSE(LastJsonLine(WriteFile(d / "b", "{\"status\":\"x\"}\nnot json\n")));
  EXPECT_FALSE(LastJsonLine(WriteFile(d / "c", "{\"steps\":3}\n")));
  EXPECT_FALSE(LastJsonLine(WriteFile(d / "e", "")));
  EXPECT_FALSE(LastJsonLine(d / "missing"));
}

TEST(RunRecord, TailKeepsTheLastLines) {
  TempDir d;
  std::string text;
  for (int i = 0; i < 50; ++i) text += "line " + std::to_string(i) + "\n";
  WriteFile(d / "err", text);
  const std::string tail = TailOfFile(d / "err", 3, 4000);
  EXPECT_EQ(tail, "line 47\nline 48\nline 49");
  EXPECT_EQ(TailOfFile(d / "err", 20, 8), "line 49");
}

TEST(RunRecord, StatusFromExitSignalTimeoutAndSummary) {
  const nlohmann::json completed{{"status", "completed"}};
  const nlohmann::json interrupted{{"status", "interrupted"}};
  ChildResult c;
  c.exit_code = 0;
  EXPECT_EQ(RunStatus(c, completed), "ok");
  EXPECT_EQ(RunStatus(c, interrupted), "failed");
  EXPECT_EQ(RunStatus(c, std::nullopt), "failed");
  c.exit_code = 5;
  EXPECT_EQ(RunStatus(c, completed), "failed");
  c.exit_code = -1;
  c.signal = SIGKILL;
  EXPECT_EQ(RunStatus(c, std::nullopt), "killed");
  c.timed_out = true;
  EXPECT_EQ(RunStatus(c, std::nullopt), "timeout");
}

}  // namespace
}  // namespace criticality::campaign
