// LoadRunMetrics on hand-made merged databases: false alarms through the result views (the
// report's grace, each run by its run_index), and run files of older drivers that lack
// critical_events, collisions or the columns a figure needs.
#include "tools/campaign/run_metrics.h"

#include <gtest/gtest.h>

#include <algorithm>

#include <string>
#include <vector>

#include "tests/tools/campaign/campaign_test_util.h"

namespace criticality::campaign {
namespace {

using testing::TempDir;

// campaign_runs and plan_params as merge writes them (the columns LoadRunMetrics reads), two
// ok runs, and the run tables `tables` creates (run_id 1 in every run, as merged).
void MakeMerged(SqliteDb& db, const std::string& tables) {
  db.Exec(
      "CREATE TABLE campaign_runs(run_index INTEGER, scenario TEXT, label TEXT, status TEXT, "
      "wall_s REAL);"
      "CREATE TABLE plan_params(run_index INTEGER, name TEXT, value TEXT);"
      "INSERT INTO campaign_runs VALUES(0, 's', 'act=warn', 'ok', 1.0), "
      "(1, 's', 'act=brake', 'ok', 1.0);"
      "INSERT INTO plan_params VALUES(0, 'act', 'warn'), (1, 'act', 'brake');" +
      tables);
}

const char* kWarnings =
    "CREATE TABLE warnings(run_index INTEGER, run_id INTEGER, ego TEXT, start_s REAL, "
    "end_s REAL);"
    "INSERT INTO warnings VALUES(0, 1, 'a', 1.0, 2.0), (0, 1, 'b', 1.0, 2.0), "
    "(0, 1, 'c', 1.0, 2.0), (1, 1, 'a', 1.0, 2.0);";

TEST(RunMetrics, FalseAlarmsAreTheWarningsThatNothingFollowedWithinTheGrace) {
  TempDir d;
  SqliteDb db((d / "campaign.sqlite").string(), true);
  MakeMerged(db, std::string(kWarnings) +
                     "CREATE TABLE collisions(run_index INTEGER, run_id INTEGER, time_s REAL, "
                     "collider TEXT, victim TEXT, involves_ego INTEGER, anticipation_s REAL);"
                     "CREATE TABLE critical_events(run_index INTEGER, run_id INTEGER, time_s REAL, "
                     "ego TEXT, kind TEXT);"
                     // run 0: a collides at end + grace, b overlaps after it, c before its start
                     "INSERT INTO collisions VALUES(0, 1, 3.0, 'x', 'a', 1, NULL);"
                     "INSERT INTO critical_events VALUES(0, 1, 3.5, 'b', 'overlap'), "
                     "(0, 1, 0.5, 'c', 'hard-braking');"
                     // run 1 (same run_id): its a braked hard within the grace
                     "INSERT INTO critical_events VALUES(1, 1, 2.5, 'a', 'hard-braking');");
  const RunMetricsSet one = LoadRunMetrics(db, 1.0);
  ASSERT_EQ(one.runs.size(), 2u);
  EXPECT_TRUE(one.available.false_alarms);
  EXPECT_EQ(one.runs[0].false_alarms, 2);
  EXPECT_EQ(one.runs[0].false_alarm_egos, (std::vector<std::string>{"b", "c"}));
  EXPECT_EQ(one.runs[1].false_alarms, 0);
  // Again on the same connection with another grace: the views are made anew.
  const RunMetricsSet two = LoadRunMetrics(db, 2.0);
  EXPECT_EQ(two.runs[0].false_alarm_egos, (std::vector<std::string>{"c"}));
  const RunMetricsSet half = LoadRunMetrics(db, 0.5);
  EXPECT_EQ(half.runs[0].false_alarm_egos, (std::vector<std::string>{"a", "b", "c"}));
  EXPECT_EQ(half.runs[1].false_alarms, 0);  // its hard braking at exactly end + grace
}

TEST(RunMetrics, WithoutCollisionsOrCriticalEventsTablesEveryWarningIsJudgedOnWhatThereIs) {
  TempDir d;
  SqliteDb db((d / "campaign.sqlite").string(), true);
  MakeMerged(db, kWarnings);
  const RunMetricsSet m = LoadRunMetrics(db, 1.0);
  EXPECT_FALSE(m.available.collisions);
  EXPECT_TRUE(m.available.warnings);
  EXPECT_TRUE(m.available.false_alarms);
  EXPECT_EQ(m.runs[0].warnings, 3);
  EXPECT_EQ(m.runs[0].false_alarms, 3);
  EXPECT_EQ(m.runs[1].false_alarms, 1);
  EXPECT_EQ(m.notes,
            (std::vector<std::string>{
                "steps and estimator time: no run has a steps table (no results?)",
                "collisions: no run has a collisions table",
                "exposure (vehicle-hours, vehicle-km) and rates: the run files have no "
                "runs.step_length_s (a driver older than the exposure columns)",
                "rates per vehicle class: the run files have no egos table (a driver older than "
                "it)"}));
}

TEST(RunMetrics, CollisionsWithoutRolesLeaveFalseAlarmsUncomputed) {
  TempDir d;
  SqliteDb db((d / "campaign.sqlite").string(), true);
  MakeMerged(db, std::string(kWarnings) +
                     "CREATE TABLE collisions(run_index INTEGER, run_id INTEGER, "
                     "time_s REAL);"
                     "INSERT INTO collisions VALUES(0, 1, 1.5);");
  const RunMetricsSet m = LoadRunMetrics(db, 1.0);
  EXPECT_TRUE(m.available.collisions);
  EXPECT_EQ(m.runs[0].collisions, 1);
  EXPECT_FALSE(m.available.false_alarms);
  EXPECT_NE(std::find(m.notes.begin(), m.notes.end(),
                      "false alarms: warnings need ego, start_s, end_s and collisions time_s, "
                      "collider, victim"),
            m.notes.end());
}

}  // namespace
}  // namespace criticality::campaign
