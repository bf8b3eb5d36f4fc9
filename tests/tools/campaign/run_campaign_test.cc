#include "tools/campaign/run_campaign.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tests/tools/campaign/campaign_test_util.h"
#include "tools/campaign/campaign_error.h"
#include "tools/campaign/campaign_folder.h"
#include "tools/campaign/driver_locator.h"

namespace criticality::campaign {
namespace {

using nlohmann::json;
using testing::ReadFile;
using testing::StandInDriver;
using testing::TempDir;
using testing::WriteFile;

Plan MakePlan(const TempDir& d, const std::string& grid, const std::string& driver = "") {
  WriteFile(d / "a/scenario.cfg", "sumo-config = x.sumocfg\n");
  WriteFile(d / "b/scenario.cfg", "sumo-config = x.sumocfg\n");
  WriteFile(d / "c.yaml",
            "output: out\nscenarios: [a/scenario.cfg, b/scenario.cfg]\ndriver:\n"
            "  stand-in-log: " +
                (d / "executions.log").string() + "\n" + driver + "grid:\n" + grid);
  return Plan(LoadCampaignFile(d / "c.yaml"));
}

RunOptions Options(int jobs = 2) {
  RunOptions o;
  o.jobs = jobs;
  o.driver = StandInDriver();
  o.progress = nullptr;
  o.kill_after_s = 0.5;
  return o;
}

json Record(const CampaignFolder& f, std::size_t i) {
  return json::parse(ReadFile(f.RunDir(i) / "run.json"));
}

// How often each run folder was executed, from the stand-in's log.
std::map<std::string, int> Executions(const TempDir& d) {
  std::map<std::string, int> n;
  std::istringstream in(ReadFile(d / "executions.log"));
  std::string line;
  while (std::getline(in, line)) ++n[line.substr(line.find_last_of('/') + 1)];
  return n;
}

TEST(RunCampaign, RunsEverythingOnceThenResumesToNothing) {
  TempDir d;
  const Plan p = MakePlan(d, "  sumo:\n    seed: [1, 2, 3]\n");
  const RunTotals t = RunCampaign(p, d / "out", Options());
  EXPECT_EQ(t.in_range, 6u);
  EXPECT_EQ(t.ok, 6u);
  EXPECT_EQ(t.failed, 0u);
  EXPECT_EQ(t.remaining, 0u);
  const CampaignFolder f = CampaignFolder::Open(d / "out");
  for (std::size_t i = 0; i < 6; ++i) {
    ASSERT_TRUE(f.IsComplete(i));
    const json r = Record(f, i);
    EXPECT_EQ(r["status"], "ok");
    EXPECT_EQ(r["exit_code"], 0);
    EXPECT_EQ(r["index"], i);
    EXPECT_EQ(r["params"]["seed"], std::to_string(i % 3 + 1));
    EXPECT_EQ(r["summary"]["status"], "completed");
    EXPECT_TRUE(std::filesystem::exists(f.RunDir(i) / "run.sqlite"));
    EXPECT_FALSE(std::filesystem::exists(f.LockFile(i)));
  }
  const RunTotals again = RunCampaign(p, d / "out", Options());
  EXPECT_EQ(again.done_before, 6u);
  EXPECT_EQ(again.ok + again.failed, 0u);
  for (const auto& [run, n] : Executions(d)) EXPECT_EQ(n, 1) << run;
  EXPECT_EQ(Executions(d).size(), 6u);
}

TEST(RunCampaign, FailedRunsAreRecordedWhileOthersGoOnAndCanBeRetried) {
  TempDir d;
  const Plan p = MakePlan(d, "  driver:\n    stand-in-exit: [0, 3]\n");
  const RunTotals t = RunCampaign(p, d / "out", Options());
  EXPECT_EQ(t.ok, 2u);
  EXPECT_EQ(t.failed, 2u);
  const CampaignFolder f = CampaignFolder::Open(d / "out");
  const json bad = Record(f, 1);
  EXPECT_EQ(bad["status"], "failed");
  EXPECT_EQ(bad["exit_code"], 3);
  EXPECT_EQ(bad["error"], "exit code 3");
  // Resumed without --retry-failed: nothing runs, and the failed runs are counted as such.
  const RunTotals again = RunCampaign(p, d / "out", Options());
  EXPECT_EQ(again.done_before, 4u);
  EXPECT_EQ(again.failed_before, 2u);
  EXPECT_EQ(again.failed, 0u);
  RunOptions retry = Options();
  retry.retry_failed = true;
  const RunTotals r = RunCampaign(p, d / "out", retry);
  EXPECT_EQ(r.failed_before, 0u);  // they are redone
  EXPECT_EQ(r.done_before, 2u);
  EXPECT_EQ(r.failed, 2u);  // they fail again, and only they ran again
  const auto n = Executions(d);
  EXPECT_EQ(n.at("000000.partial"), 1);
  EXPECT_EQ(n.at("000001.partial"), 2);
  EXPECT_EQ(n.at("000003.partial"), 2);
}

TEST(RunCampaign, ARunPastItsTimeLimitIsStoppedAndRecorded) {
  TempDir d;
  const Plan p = MakePlan(d, "  driver:\n    stand-in-sleep: [0, 30]\n");
  RunOptions o = Options();
  o.time_limit_s = 0.5;
  const auto t0 = std::chrono::steady_clock::now();
  const RunTotals t = RunCampaign(p, d / "out", o);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 15.0);
  EXPECT_EQ(t.ok, 2u);
  EXPECT_EQ(t.failed, 2u);
  const json r = Record(CampaignFolder::Open(d / "out"), 1);
  EXPECT_EQ(r["status"], "timeout");
  EXPECT_NE(r["error"].get<std::string>().find("time limit"), std::string::npos);
}

TEST(RunCampaign, AStalePartialRunIsRedoneAndAHeldRunIsLeftAlone) {
  TempDir d;
  const Plan p = MakePlan(d, "  sumo:\n    seed: [1, 2]\n");
  const CampaignFolder f = CampaignFolder::Prepare(d / "out", p);
  WriteFile(f.PartialDir(0) / "run.sqlite", "half-written by a killed run");
  std::optional<RunClaim> held = RunClaim::TryClaim(f, 1);
  ASSERT_TRUE(held);
  const RunTotals t = RunCampaign(p, d / "out", Options());
  EXPECT_EQ(t.ok, 3u);
  EXPECT_EQ(t.remaining, 1u);
  EXPECT_TRUE(f.IsComplete(0));
  EXPECT_FALSE(f.IsComplete(1));
  EXPECT_EQ(Record(f, 0)["status"], "ok");
}

TEST(RunCampaign, ARangeRunsOnlyItsShare) {
  TempDir d;
  const Plan p = MakePlan(d, "  sumo:\n    seed: [1, 2, 3]\n");
  RunOptions o = Options();
  o.first = 2;
  o.last = 3;
  const RunTotals t = RunCampaign(p, d / "out", o);
  EXPECT_EQ(t.in_range, 2u);
  EXPECT_EQ(t.ok, 2u);
  const CampaignFolder f = CampaignFolder::Open(d / "out");
  for (std::size_t i = 0; i < 6; ++i) EXPECT_EQ(f.IsComplete(i), i == 2 || i == 3) << i;
  o.first = 6;
  o.last = 9;
  EXPECT_THROW(RunCampaign(p, d / "out", o), CampaignError);
}

TEST(RunCampaign, TwoRunCommandsOnOneFolderShareTheRuns) {
  TempDir d;
  const Plan p = MakePlan(d, "  sumo:\n    seed: {range: [1, 12]}\n", "  stand-in-sleep: 0.05\n");
  std::vector<pid_t> kids;
  for (int k = 0; k < 2; ++k) {
    const pid_t pid = fork();
    if (pid == 0) {
      const RunTotals t = RunCampaign(p, d / "out", Options(2));
      _exit(t.failed == 0 ? 0 : 1);
    }
    kids.push_back(pid);
  }
  for (pid_t k : kids) {
    int status = 0;
    waitpid(k, &status, 0);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  }
  const CampaignFolder f = CampaignFolder::Open(d / "out");
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_TRUE(f.IsComplete(i)) << i;
    EXPECT_EQ(Record(f, i)["status"], "ok");
  }
  const auto n = Executions(d);
  EXPECT_EQ(n.size(), p.size());
  for (const auto& [run, count] : n) EXPECT_EQ(count, 1) << run << " ran more than once";
}

TEST(DriverLocator, UnknownDriverOptionsNameKeyAndLine) {
  TempDir d;
  const Plan p = MakePlan(d, "  driver:\n    profils: [1, 2]\n");
  const auto known = DriverOptionNames(StandInDriver());
  EXPECT_TRUE(known.count("profiles"));
  try {
    CheckDriverOptions(p.spec(), known);
    FAIL() << "an option the driver does not know must be an error";
  } catch (const CampaignError& e) {
    EXPECT_NE(std::string(e.what()).find("c.yaml:7: grid.driver.profils: sumo-criticality has no "
                                         "option --profils"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(FindDriver((d / "nothing").string()), CampaignError);
  EXPECT_EQ(FindDriver(StandInDriver()), StandInDriver());
}

}  // namespace
}  // namespace criticality::campaign
