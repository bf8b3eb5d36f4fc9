// A changed campaign file over a folder with runs of the earlier one (tools/campaign/replan.h):
// runs the new plan still has are kept (renumbered where their index moved), failed changed
// runs are redone, successful ones the new plan lacks need consent and are moved aside.
#include "tools/campaign/replan.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "tests/tools/campaign/campaign_test_util.h"
#include "tools/campaign/campaign_error.h"
#include "tools/campaign/campaign_folder.h"
#include "tools/campaign/merge.h"
#include "tools/campaign/run_campaign.h"
#include "tools/campaign/sqlite_db.h"

namespace criticality::campaign {
namespace {

using nlohmann::json;
using testing::ReadFile;
using testing::StandInDriver;
using testing::TempDir;
using testing::WriteFile;

struct Fixture {
  TempDir dir;
  Fixture() {
    WriteFile(dir / "a/scenario.cfg", "sumo-config = x.sumocfg\n");
    WriteFile(dir / "b/scenario.cfg", "sumo-config = x.sumocfg\n");
  }
  Plan Make(const std::string& yaml) const {
    WriteFile(dir / "c.yaml", yaml);
    return Plan(LoadCampaignFile(dir / "c.yaml"));
  }
  RunTotals Run(const Plan& p, bool replan = false) const {
    RunOptions o;
    o.jobs = 2;
    o.driver = StandInDriver();
    o.progress = nullptr;
    o.replan = replan;
    return RunCampaign(p, dir / "out", o);
  }
  json Record(std::size_t i) const {
    return json::parse(ReadFile(CampaignFolder::Open(dir / "out").RunDir(i) / "run.json"));
  }
};

const char* kTwoSeeds =
    "output: out\nscenarios: [a/scenario.cfg, b/scenario.cfg]\ndriver:\n  act: warn\n"
    "grid:\n  sumo:\n    seed: [1, 2]\n";
const char* kThreeSeeds =
    "output: out\nscenarios: [a/scenario.cfg, b/scenario.cfg]\ndriver:\n  act: warn\n"
    "grid:\n  sumo:\n    seed: [1, 2, 3]\n";

TEST(RunIdentity, IsTheOptionsWhateverTheirOrderAndWhetherFixedOrOnTheGrid) {
  Fixture f;
  const Plan fixed = f.Make(
      "output: out\nscenarios: [a/scenario.cfg]\ndriver:\n  act: warn\n  profiles: 3\n"
      "grid:\n  sumo:\n    seed: [1]\n");
  const Plan grid = f.Make(
      "output: out\nscenarios: [a/scenario.cfg]\ndriver:\n  profiles: 3\ngrid:\n  driver:\n"
      "    act: [warn]\n  sumo:\n    seed: [1]\n");
  EXPECT_EQ(fixed.Identity(fixed.Run(0)), grid.Identity(grid.Run(0)));
  EXPECT_NE(fixed.FingerprintHex(), grid.FingerprintHex());
  // From the recorded command line (run folders written before identities were kept).
  EXPECT_EQ(RunIdentity("a/scenario.cfg", 0, fixed.Command(fixed.Run(0), "/x/drv", "run.sqlite")),
            fixed.Identity(fixed.Run(0)));
  const Plan other = f.Make(
      "output: out\nscenarios: [a/scenario.cfg]\ndriver:\n  act: warn\n  profiles: 4\n"
      "grid:\n  sumo:\n    seed: [1]\n");
  EXPECT_NE(other.Identity(other.Run(0)), fixed.Identity(fixed.Run(0)));
  // The repetition is part of it.
  const Plan reps = f.Make("output: out\nscenarios: [a/scenario.cfg]\nrepetitions: 2\n");
  EXPECT_NE(reps.Identity(reps.Run(0)), reps.Identity(reps.Run(1)));
}

TEST(Replan, ANewSeedKeepsTheRunsDoneAtTheirNewIndexAndRunsOnlyTheNewOnes) {
  Fixture f;
  const Plan two = f.Make(kTwoSeeds);
  f.Run(two);
  const json before = f.Record(2);  // b, seed=1
  EXPECT_EQ(before["label"], "seed=1");
  const Plan three = f.Make(kThreeSeeds);
  const RunTotals t = f.Run(three);
  EXPECT_EQ(t.done_before, 4u);
  EXPECT_EQ(t.ok, 2u);  // seed 3 of both scenarios, nothing else
  // b, seed=1 moved from index 2 to index 3, the same run (its attempt marked as moved).
  const json after = f.Record(3);
  EXPECT_EQ(after["scenario"], "b");
  EXPECT_EQ(after["label"], "seed=1");
  EXPECT_EQ(after["index"], 3);
  EXPECT_EQ(after["started_utc"], before["started_utc"]);
  EXPECT_EQ(after["attempt"],
            before["attempt"].get<std::string>() + "+replan:" + three.FingerprintHex());
  const CampaignFolder folder = CampaignFolder::Open(f.dir / "out");
  EXPECT_EQ(folder.info()["fingerprint"], three.FingerprintHex());
  EXPECT_TRUE(
      std::filesystem::exists(f.dir / "out" / ("campaign." + two.FingerprintHex() + ".json")));
  // merge puts every run at its new index, the moved ones included.
  MergeCampaign(folder);
  SqliteDb db((f.dir / "out/campaign.sqlite").string(), false);
  Statement s = db.Prepare(
      "SELECT group_concat(label, '|') FROM (SELECT label FROM campaign_runs "
      "ORDER BY run_index)");
  ASSERT_TRUE(s.Step());
  EXPECT_EQ(s.Text(0), "seed=1|seed=2|seed=3|seed=1|seed=2|seed=3");
}

TEST(Replan, FewerRunsDropTheirRowsFromTheMergedDatabase) {
  Fixture f;
  f.Run(f.Make(kThreeSeeds));
  MergeCampaign(CampaignFolder::Open(f.dir / "out"));
  const Plan two = f.Make(kTwoSeeds);
  // Seed 3's runs are successful and not in the new plan: consent needed.
  EXPECT_THROW(f.Run(two), CampaignError);
  f.Run(two, true);
  const CampaignFolder folder = CampaignFolder::Open(f.dir / "out");
  EXPECT_EQ(folder.runs(), 4u);
  MergeCampaign(folder);
  SqliteDb db((f.dir / "out/campaign.sqlite").string(), false);
  Statement s = db.Prepare("SELECT count(*), max(run_index) FROM campaign_runs");
  ASSERT_TRUE(s.Step());
  EXPECT_EQ(s.Int(0), 4);
  EXPECT_EQ(s.Int(1), 3);
}

TEST(Replan, AChangedValueSupersedesSuccessfulRunsOnlyWithConsent) {
  Fixture f;
  f.Run(f.Make(kTwoSeeds));
  const Plan changed = f.Make(
      "output: out\nscenarios: [a/scenario.cfg, b/scenario.cfg]\ndriver:\n  act: brake\n"
      "grid:\n  sumo:\n    seed: [1, 2]\n");
  const PlanChanges c = CompareWithFolder(f.dir / "out", changed);
  EXPECT_TRUE(c.changed);
  EXPECT_EQ(c.kept.size(), 0u);
  EXPECT_EQ(c.superseded.size(), 4u);
  try {
    f.Run(changed);
    ADD_FAILURE() << "a changed value must not throw successful runs away silently";
  } catch (const CampaignError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("superseded"), std::string::npos) << what;
    EXPECT_NE(what.find("run 0: a, seed=1 (ok)"), std::string::npos) << what;
    EXPECT_NE(what.find("--replan"), std::string::npos) << what;
  }
  const RunTotals t = f.Run(changed, true);
  EXPECT_EQ(t.ok, 4u);  // every run again, with the new value
  EXPECT_NE(f.Record(0)["command"].dump().find("brake"), std::string::npos);
  const auto aside = f.dir / "out/superseded" / c.old_fingerprint / "000000";
  ASSERT_TRUE(std::filesystem::exists(aside / "run.json"));  // kept, never deleted
  EXPECT_NE(ReadFile(aside / "run.json").find("\"warn\""), std::string::npos);
}

TEST(Replan, FailedRunsOfAnEarlierPlanAreRedoneWithoutConsent) {
  Fixture f;
  f.Run(
      f.Make("output: out\nscenarios: [a/scenario.cfg]\ndriver:\n  stand-in-exit: 3\n"
             "grid:\n  sumo:\n    seed: [1, 2]\n"));
  EXPECT_EQ(f.Record(0)["status"], "failed");
  const Plan fixed =
      f.Make("output: out\nscenarios: [a/scenario.cfg]\ngrid:\n  sumo:\n    seed: [1, 2]\n");
  const PlanChanges c = CompareWithFolder(f.dir / "out", fixed);
  EXPECT_EQ(c.redone.size(), 2u);
  EXPECT_EQ(c.superseded.size(), 0u);
  const RunTotals t = f.Run(fixed);  // no --replan, no --retry-failed needed
  EXPECT_EQ(t.ok, 2u);
  EXPECT_EQ(f.Record(0)["status"], "ok");
}

TEST(Replan, NothingChangesWhileAnotherProcessHoldsARun) {
  Fixture f;
  f.Run(f.Make(kTwoSeeds));
  const CampaignFolder folder = CampaignFolder::Open(f.dir / "out");
  const int fd = ::open(folder.LockFile(1).c_str(), O_RDWR | O_CREAT, 0644);
  ASSERT_EQ(::flock(fd, LOCK_EX), 0);
  // flock is per open file: a process of its own holds it, as another run command would.
  const pid_t child = fork();
  if (child == 0) {
    const int mine = ::open(folder.LockFile(1).c_str(), O_RDWR);
    ::flock(mine, LOCK_EX);
    ::pause();
    _exit(0);
  }
  ::close(fd);  // let the child take it
  for (int k = 0; k < 100; ++k) {
    const int probe = ::open(folder.LockFile(1).c_str(), O_RDWR);
    const bool held = ::flock(probe, LOCK_EX | LOCK_NB) != 0;
    ::close(probe);
    if (held) break;
    usleep(10000);
  }
  const Plan three = f.Make(kThreeSeeds);
  EXPECT_THROW(f.Run(three, true), CampaignError);
  kill(child, SIGKILL);
  waitpid(child, nullptr, 0);
  EXPECT_EQ(CampaignFolder::Open(f.dir / "out").info()["fingerprint"],
            f.Make(kTwoSeeds).FingerprintHex());
}

}  // namespace
}  // namespace criticality::campaign
