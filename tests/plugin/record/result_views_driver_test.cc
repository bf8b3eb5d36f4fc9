// The views in the driver's run files (plugin/record/result_views.sql): ResultsDb creates them
// with its schema and stores each collision's anticipation from collision_anticipation when it
// records the collision. Written in the record stage's order (a step's collisions, then its
// warnings opening and closing), over many random steps, the view on the finished file still
// gives the stored value for every collision: what was recorded later (an episode that opened at
// the impact, one that closed after it) does not change an anticipation once taken.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "plugin/record/result_views.h"
#include "plugin/act/act_outcome.h"
#include "plugin/record/results_db.h"

namespace criticality::plugin {
namespace {

long long Count(sqlite3* db, const std::string& sql) {
  sqlite3_stmt* s = nullptr;
  long long n = -1;
  if (sqlite3_prepare_v2(db, sql.c_str(), -1, &s, nullptr) == SQLITE_OK &&
      sqlite3_step(s) == SQLITE_ROW) {
    n = sqlite3_column_int64(s, 0);
  }
  sqlite3_finalize(s);
  return n;
}

TEST(ResultViewsDriver, AnticipationIsTheDriversStoredValue) {
  const std::string path = ::testing::TempDir() + "result_views_driver.sqlite";
  for (const char* suffix : {"", "-wal", "-shm"}) std::remove((path + suffix).c_str());
  const std::vector<std::string> egos = {"a", "b", "c", "d"};
  {
    ResultsDb db(path);
    db.BeginRun("opts", "v", "a,b,c,d", 0.1);
    std::mt19937 random(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::map<std::string, long long> open;  // ego -> its open episode
    for (int k = 1; k <= 3000; ++k) {
      const double t = k * 100 / 1000.0;  // SUMO's milliseconds as seconds
      for (const std::string& ego : egos) {
        if (u(random) < 0.05) {
          SumoCollision c;
          c.collider = u(random) < 0.5 ? ego : "x";
          c.victim = c.collider == ego ? egos[k % egos.size()] : ego;
          db.AddCollision(t, c, true);
        }
      }
      // Each ego's estimate names one main object: another ego, the stranger x, or none.
      for (const std::string& ego : egos) {
        EgoStep s;
        s.ego = ego;
        const int pick = static_cast<int>(u(random) * 6);
        s.main_object = pick < 4 ? egos[pick] : pick == 4 ? "x" : "";
        if (s.main_object == ego) s.main_object = "x";
        db.AddStep(t, s);
      }
      for (const std::string& ego : egos) {
        const auto it = open.find(ego);
        if (it == open.end() && u(random) < 0.1) {
          open[ego] = db.OpenWarning(ego, t, 0.6, 0.0, 0.0, "e");
        } else if (it != open.end() && u(random) < 0.3) {
          db.CloseWarning(it->second, t);
          open.erase(it);
        }
      }
      db.Commit();
    }
    // An episode never closed (as in a killed run) and a collision while it is open.
    if (!open.count("a")) db.OpenWarning("a", 300.1, 0.6, 0.0, 0.0, "e");
    SumoCollision c;
    c.collider = "a";
    c.victim = "x";
    db.AddCollision(300.2, c, true);
    db.Commit();
    db.EndRun("interrupted", "signal", "", "{}");
  }
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  // The run file has the views (readers need not make them).
  EXPECT_EQ(Count(db, "SELECT count(*) FROM sqlite_master WHERE type = 'view' AND name IN "
                      "('warning_windows', 'warning_outcomes', 'critical_event_warnings', "
                      "'collision_anticipation')"),
            4);
  const long long collisions = Count(db, "SELECT count(*) FROM collisions");
  EXPECT_GT(collisions, 300);
  EXPECT_EQ(Count(db, "SELECT count(*) FROM collision_anticipation"), collisions);
  EXPECT_EQ(Count(db,
                  "SELECT count(*) FROM collisions c JOIN collision_anticipation a ON "
                  "a.collision_rowid = c.rowid WHERE a.anticipation_s IS NOT c.anticipation_s"),
            0);
  // The cases that tell rules apart occurred: warned and unwarned collisions, episodes that
  // opened at an impact of their ego, ended one step before one, or were never closed.
  EXPECT_GT(Count(db, "SELECT count(*) FROM collisions WHERE anticipation_s IS NOT NULL"), 50);
  EXPECT_GT(Count(db, "SELECT count(*) FROM collisions WHERE anticipation_s IS NULL"), 50);
  EXPECT_GT(Count(db,
                  "SELECT count(*) FROM collisions c JOIN warnings w ON w.ego IN (c.collider, "
                  "c.victim) AND w.start_s = c.time_s"),
            0);
  EXPECT_GT(Count(db,
                  "SELECT count(*) FROM collisions c JOIN warnings w ON w.ego IN (c.collider, "
                  "c.victim) AND abs(c.time_s - 0.1 - w.end_s) < 1e-9"),
            0);
  EXPECT_GT(Count(db, "SELECT count(*) FROM warnings WHERE end_s IS NULL"), 0);
  // Episodes open at a collision that never named its partner: no anticipation from them.
  EXPECT_GT(Count(db,
                  "SELECT count(*) FROM collision_warnings WHERE credited_s IS NULL"), 10);
  EXPECT_GT(Count(db,
                  "SELECT count(*) FROM collision_warnings WHERE credited_s > start_s"), 10);
  sqlite3_close(db);
  // Attached to another database under another name (criticality-campaign merge does so), the
  // file's views still read its own tables.
  sqlite3* other = nullptr;
  ASSERT_EQ(sqlite3_open(":memory:", &other), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(other, ("ATTACH DATABASE '" + path + "' AS r").c_str(), nullptr, nullptr,
                         nullptr),
            SQLITE_OK)
      << sqlite3_errmsg(other);
  EXPECT_EQ(Count(other, "SELECT count(*) FROM r.warning_outcomes"),
            Count(other, "SELECT count(*) FROM r.warnings"));
  EXPECT_EQ(Count(other, "SELECT count(*) FROM r.collision_anticipation"), collisions);
  sqlite3_close(other);
}

}  // namespace
}  // namespace criticality::plugin
