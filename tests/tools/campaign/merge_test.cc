#include "tools/campaign/merge.h"

#include <gtest/gtest.h>

#include "tests/tools/campaign/campaign_test_util.h"
#include "tools/campaign/run_campaign.h"
#include "tools/campaign/sqlite_db.h"

namespace criticality::campaign {
namespace {

using testing::StandInDriver;
using testing::TempDir;
using testing::WriteFile;

Plan MakePlan(const TempDir& d, const std::string& grid) {
  WriteFile(d / "a/scenario.cfg", "sumo-config = x.sumocfg\n");
  WriteFile(d / "b/scenario.cfg", "sumo-config = x.sumocfg\n");
  WriteFile(d / "c.yaml",
            "output: out\nscenarios: [a/scenario.cfg, b/scenario.cfg]\ndriver:\n"
            "  stand-in-collide: 1.0\n  stand-in-warn: 0.6\ngrid:\n" +
                grid);
  return Plan(LoadCampaignFile(d / "c.yaml"));
}

void RunAll(const Plan& p, const TempDir& d, bool retry = false) {
  RunOptions o;
  o.jobs = 2;
  o.driver = StandInDriver();
  o.progress = nullptr;
  o.retry_failed = retry;
  RunCampaign(p, d / "out", o);
}

long long Count(SqliteDb& db, const std::string& sql) {
  Statement s = db.Prepare(sql);
  return s.Step() ? s.Int(0) : -1;
}

// Every row of every table, in a stable order: equal strings mean equal databases.
std::string Dump(const std::filesystem::path& path) {
  SqliteDb db(path.string(), false, true);
  std::vector<std::string> tables;
  {
    Statement t = db.Prepare("SELECT name FROM sqlite_master WHERE type='table' ORDER BY name");
    while (t.Step()) tables.push_back(t.Text(0));
  }
  std::string out;
  for (const std::string& t : tables) {
    out += "## " + t + "\n";
    std::string order;
    for (std::size_t c = 1; c <= db.Columns(t).size(); ++c)
      order += (order.empty() ? "" : ", ") + std::to_string(c);
    Statement s = db.Prepare("SELECT * FROM " + QuoteId(t) + " ORDER BY " + order);
    while (s.Step()) {
      for (int c = 0; c < s.columns(); ++c) out += s.Text(c) + "|";
      out += "\n";
    }
  }
  return out;
}

TEST(Merge, EveryTableOfEveryRunWithItsIndex) {
  TempDir d;
  const Plan p = MakePlan(d, "  sumo:\n    seed: [1, 2]\n");
  RunAll(p, d);
  const MergeTotals t = MergeCampaign(CampaignFolder::Open(d / "out"));
  EXPECT_EQ(t.runs, 4u);
  EXPECT_EQ(t.complete, 4u);
  EXPECT_EQ(t.merged, 4u);
  EXPECT_EQ(t.tables, 5u);  // runs, steps, warnings, actions, collisions
  SqliteDb db(t.database.string(), false);
  EXPECT_EQ(Count(db, "SELECT count(*) FROM campaign_runs WHERE status = 'ok'"), 4);
  EXPECT_EQ(Count(db, "SELECT count(*) FROM steps"), 40);
  EXPECT_EQ(Count(db, "SELECT count(DISTINCT run_index) FROM steps"), 4);
  EXPECT_EQ(Count(db, "SELECT count(*) FROM collisions WHERE run_index = 3"), 1);
  EXPECT_EQ(Count(db, "SELECT count(*) FROM plan_params WHERE name = 'seed' AND value = '2'"), 2);
  EXPECT_EQ(Count(db, "SELECT count(*) FROM runs WHERE options LIKE '%--seed 2%'"), 2);
  EXPECT_EQ(Count(db, "SELECT value FROM campaign WHERE key = 'runs'"), 4);
}

TEST(Merge, ColumnsAndTablesOfNewerRunFilesArePickedUp) {
  TempDir d;
  const Plan p = MakePlan(d, "  driver:\n    stand-in-newer: [false, true]\n");
  RunAll(p, d);
  const MergeTotals t = MergeCampaign(CampaignFolder::Open(d / "out"));
  EXPECT_EQ(t.tables, 8u);  // + ego_events, egos, warning_scenes
  SqliteDb db(t.database.string(), false);
  const auto cols = db.Columns("warnings");
  EXPECT_NE(std::find(cols.begin(), cols.end(), "edge"), cols.end());
  EXPECT_EQ(Count(db, "SELECT count(*) FROM ego_events"), 2);  // runs 1 and 3
  EXPECT_EQ(Count(db, "SELECT count(*) FROM warnings WHERE edge = 'e1'"), 2);
  EXPECT_EQ(Count(db, "SELECT count(*) FROM warnings WHERE edge IS NULL"), 2);
  EXPECT_EQ(Count(db, "SELECT count(*) FROM collisions WHERE involves_ego = 1"), 2);
}

TEST(Merge, IdempotentIncrementalAndNeverHalfWritten) {
  TempDir d;
  const Plan p = MakePlan(d, "  sumo:\n    seed: [1, 2, 3]\n");
  RunAll(p, d);
  const CampaignFolder f = CampaignFolder::Open(d / "out");
  // A run that was killed half way: its folder is .partial, with a database in it.
  std::filesystem::rename(f.RunDir(5), f.PartialDir(5));
  const MergeTotals first = MergeCampaign(f);
  EXPECT_EQ(first.merged, 5u);
  EXPECT_EQ(first.incomplete, 1u);
  const std::string dump = Dump(first.database);
  const MergeTotals second = MergeCampaign(f);
  EXPECT_EQ(second.merged, 0u);
  EXPECT_EQ(second.unchanged, 5u);
  EXPECT_EQ(Dump(second.database), dump);
  {
    SqliteDb db(first.database.string(), false);
    EXPECT_EQ(Count(db, "SELECT count(*) FROM steps WHERE run_index = 5"), 0);
  }
  // Redo it (the .partial is removed and run again), and drop run 0's folder.
  std::filesystem::remove_all(f.RunDir(0));
  RunAll(p, d);
  const MergeTotals third = MergeCampaign(f);
  EXPECT_EQ(third.merged, 2u);  // runs 0 and 5 (both run again)
  EXPECT_EQ(third.unchanged, 4u);
  EXPECT_EQ(third.removed, 0u);
  SqliteDb db(third.database.string(), false);
  EXPECT_EQ(Count(db, "SELECT count(*) FROM steps"), 60);
  EXPECT_EQ(Count(db, "SELECT count(*) FROM steps WHERE run_index = 0"), 10);
  // A run whose folder is gone leaves the database.
  std::filesystem::remove_all(f.RunDir(2));
  const MergeTotals fourth = MergeCampaign(f);
  EXPECT_EQ(fourth.removed, 1u);
  SqliteDb db2(fourth.database.string(), false);
  EXPECT_EQ(Count(db2, "SELECT count(*) FROM steps WHERE run_index = 2"), 0);
  EXPECT_EQ(Count(db2, "SELECT count(*) FROM campaign_runs"), 5);
}

TEST(Merge, AnUnreadableRunFileKeepsItsRecordAndTheRestMerges) {
  TempDir d;
  const Plan p = MakePlan(d, "  sumo:\n    seed: [1, 2]\n");
  RunAll(p, d);
  const CampaignFolder f = CampaignFolder::Open(d / "out");
  WriteFile(f.RunDir(0) / "run.sqlite", std::string(4096, 'x'));  // not a database
  const MergeTotals t = MergeCampaign(f);
  EXPECT_EQ(t.merged, 4u);
  ASSERT_EQ(t.unreadable.size(), 1u);
  EXPECT_NE(t.unreadable[0].find("run 0: results not merged"), std::string::npos);
  SqliteDb db(t.database.string(), false);
  EXPECT_EQ(Count(db, "SELECT count(*) FROM campaign_runs"), 4);
  EXPECT_EQ(Count(db, "SELECT count(*) FROM campaign_runs WHERE merge_note IS NOT NULL"), 1);
  EXPECT_EQ(Count(db, "SELECT count(*) FROM steps WHERE run_index = 0"), 0);
  EXPECT_EQ(Count(db, "SELECT count(*) FROM steps"), 30);
}

}  // namespace
}  // namespace criticality::campaign
