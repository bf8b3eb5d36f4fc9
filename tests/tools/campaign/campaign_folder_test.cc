#include "tools/campaign/campaign_folder.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include "tests/tools/campaign/campaign_test_util.h"
#include "tools/campaign/campaign_error.h"

namespace criticality::campaign {
namespace {

using testing::TempDir;
using testing::WriteFile;

Plan MakePlan(const TempDir& d, const std::string& seeds) {
  WriteFile(d / "s/scenario.cfg", "sumo-config = x.sumocfg\n");
  WriteFile(d / "c.yaml",
            "output: out\nscenarios: [s/scenario.cfg]\ngrid:\n  sumo:\n    seed: " + seeds + "\n");
  return Plan(LoadCampaignFile(d / "c.yaml"));
}

TEST(CampaignFolder, PrepareRecordsThePlanAndTakesAChangedOneThatDropsNoResult) {
  TempDir d;
  const Plan p = MakePlan(d, "[1, 2, 3]");
  const CampaignFolder f = CampaignFolder::Prepare(d / "out", p);
  EXPECT_EQ(f.runs(), 3u);
  EXPECT_EQ(f.info()["fingerprint"], p.FingerprintHex());
  EXPECT_TRUE(std::filesystem::exists(d / "out/campaign.yaml"));
  EXPECT_EQ(CampaignFolder::Prepare(d / "out", p).runs(), 3u);  // the same plan again: fine
  EXPECT_TRUE(CampaignFolder::Prepare(d / "out", p).changes().empty());
  // Another plan over a folder without results: taken, the earlier one kept beside it
  // (refusing a changed plan that drops results: replan_test.cc).
  const Plan other = MakePlan(d, "[1, 2]");
  const CampaignFolder g = CampaignFolder::Prepare(d / "out", other);
  EXPECT_EQ(g.runs(), 2u);
  EXPECT_EQ(g.info()["fingerprint"], other.FingerprintHex());
  EXPECT_FALSE(g.changes().empty());
  EXPECT_TRUE(std::filesystem::exists(d / "out" / ("campaign." + p.FingerprintHex() + ".json")));
  EXPECT_THROW(CampaignFolder::Open(d / "nothing"), CampaignError);
}

TEST(CampaignFolder, RunNamesArePaddedToTheWidth) {
  TempDir d;
  const CampaignFolder f = CampaignFolder::Prepare(d / "out", MakePlan(d, "{range: [1, 3]}"));
  EXPECT_EQ(f.RunName(7), "000007");
  EXPECT_EQ(f.RunDir(2), d.path() / "out/runs/000002");
  EXPECT_EQ(f.PartialDir(2), d.path() / "out/runs/000002.partial");
}

TEST(RunClaim, OneHolderAtATimeAndCompleteIsAtomic) {
  TempDir d;
  const CampaignFolder f = CampaignFolder::Prepare(d / "out", MakePlan(d, "[1, 2]"));
  {
    std::optional<RunClaim> a = RunClaim::TryClaim(f, 0);
    ASSERT_TRUE(a);
    // flock conflicts between open file descriptions, also within one process.
    EXPECT_FALSE(RunClaim::TryClaim(f, 0));
    EXPECT_TRUE(RunClaim::TryClaim(f, 1));
    const auto work = a->StartWork();
    WriteFile(work / "run.json", "{}");
    EXPECT_FALSE(f.IsComplete(0));
    a->Complete();
    EXPECT_TRUE(f.IsComplete(0));
    EXPECT_FALSE(std::filesystem::exists(work));
    EXPECT_TRUE(std::filesystem::exists(f.RunDir(0) / "run.json"));
  }
  EXPECT_FALSE(std::filesystem::exists(f.LockFile(0)));
  EXPECT_FALSE(RunClaim::TryClaim(f, 0));  // complete: nothing to claim
  EXPECT_TRUE(RunClaim::TryClaim(f, 0, /*redo_complete=*/true));
}

TEST(RunClaim, AKilledHolderReleasesTheClaimAndItsPartialIsRedone) {
  TempDir d;
  const CampaignFolder f = CampaignFolder::Prepare(d / "out", MakePlan(d, "[1]"));
  int ready[2];
  ASSERT_EQ(pipe(ready), 0);
  const pid_t child = fork();
  if (child == 0) {
    std::optional<RunClaim> c = RunClaim::TryClaim(f, 0);
    if (c) WriteFile(c->StartWork() / "half-written", "x");
    (void)!write(ready[1], "1", 1);
    pause();  // killed here, holding the claim
    _exit(0);
  }
  char b;
  ASSERT_EQ(read(ready[0], &b, 1), 1);
  EXPECT_FALSE(RunClaim::TryClaim(f, 0));  // the child holds it
  kill(child, SIGKILL);
  waitpid(child, nullptr, 0);
  EXPECT_TRUE(std::filesystem::exists(f.PartialDir(0) / "half-written"));
  std::optional<RunClaim> c = RunClaim::TryClaim(f, 0);
  ASSERT_TRUE(c);
  const auto work = c->StartWork();
  EXPECT_FALSE(std::filesystem::exists(work / "half-written"));  // a fresh folder
  EXPECT_FALSE(f.IsComplete(0));
}

}  // namespace
}  // namespace criticality::campaign
