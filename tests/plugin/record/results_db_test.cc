// The results database: schema, episodes, anticipation times, commits, readers during a run,
// refusing to overwrite, leaving nothing behind when discarded.
#include "plugin/record/results_db.h"

#include <gtest/gtest.h>
#include <sqlite3.h>
#include <sys/stat.h>

#include <chrono>
#include <cstdio>
#include <string>

#include "../results_query.h"

namespace criticality::plugin {
namespace {

using testing::Query;

std::string TempFile(const char* name) {
  const std::string path = ::testing::TempDir() + name;
  for (const char* suffix : {"", "-wal", "-shm", "-journal"}) std::remove((path + suffix).c_str());
  return path;
}

bool Exists(const std::string& path) {
  struct stat st {};
  return stat(path.c_str(), &st) == 0;
}

EgoStep Row(double p = 0.0) {
  EgoStep r;
  r.ego = "ego";
  r.p_collision = p;
  r.objects = 2;
  r.objects_in_reach = 1;
  return r;
}

// ego's step with `main` as the object with the largest share of p.
EgoStep Named(const char* ego, const char* main) {
  EgoStep r = Row(0.6);
  r.ego = ego;
  r.main_object = main;
  return r;
}

SumoCollision Collision(const char* collider, const char* victim) {
  SumoCollision c;
  c.collider = collider;
  c.victim = victim;
  c.type = "collision";
  c.lane = "WE_1";
  c.x_m = 10.0;
  c.y_m = -5.0;
  return c;
}

TEST(ResultsDb, AnticipationCountsOnlyAnEpisodeActiveAtTheImpact) {
  const std::string path = TempFile("anticipation.sqlite");
  {
    ResultsDb db(path);
    db.BeginRun("opts", "SUMO 1.15.0", "a,b,c,d", 0.1);
    db.SetScenario("collision", "x", 2.5, "");
    db.AddStep(1.0, Row(0.2));
    // Each episode's first step names the object each collision below is with (x, or c's y).
    for (const char* ego : {"a", "b", "c", "d"}) db.AddStep(ego[0] == 'a' ? 1.5 : 2.0, Named(ego, "x"));
    db.AddStep(2.0, Named("c", "y"));
    // a: warned from 1.5 s, still warning at its collision at 3.0 s -> 1.5 s.
    db.UpdateWarningPeak(db.OpenWarning("a", 1.5, 0.6, 1.0, 2.0, "WE"), 0.9);
    db.AddCollision(3.0, Collision("a", "x"), true);
    // b: an episode that ended exactly one step before the impact counts...
    db.CloseWarning(db.OpenWarning("b", 2.0, 0.6, 0, 0, "WE"), 2.9);
    db.AddCollision(3.0, Collision("b", "x"), true);
    // c: ...one that ended two steps before does not.
    db.CloseWarning(db.OpenWarning("c", 2.0, 0.6, 0, 0, "WE"), 2.8);
    db.AddCollision(3.0, Collision("y", "c"), true);
    // d: an episode starting after the impact does not either.
    db.OpenWarning("d", 3.5, 0.6, 0, 0, "WE");
    db.AddCollision(3.0, Collision("d", "x"), true);
    // e: an episode open at the impact that only warned of another object does not.
    db.AddStep(2.0, Named("e", "ped"));
    db.OpenWarning("e", 2.0, 0.6, 0, 0, "WE");
    db.AddCollision(3.0, Collision("e", "x"), true);
    db.Commit();
    db.EndRun("completed", "sumo-end", "", "{}");
  }
  EXPECT_EQ(Query(path, "select anticipation_s from collisions where collider='a'"), "1.5");
  EXPECT_EQ(Query(path, "select round(anticipation_s, 9) from collisions where collider='b'"),
            "1.0");
  EXPECT_EQ(Query(path, "select anticipation_s from collisions where victim='c'"), "NULL");
  EXPECT_EQ(Query(path, "select anticipation_s from collisions where collider='d'"), "NULL");
  EXPECT_EQ(Query(path, "select anticipation_s from collisions where collider='e'"), "NULL");
  EXPECT_EQ(Query(path, "select main_object from steps where ego='e'"), "ped");
  EXPECT_EQ(Query(path, "select count(*) from steps where ego='ego' and main_object is null"), "1");
  EXPECT_EQ(Query(path, "select peak_p || ' ' || x_m || ' ' || edge from warnings where ego='a'"),
            "0.9 1.0 WE");
  EXPECT_EQ(Query(path, "select status || ' ' || end_reason from runs"), "completed sumo-end");
  EXPECT_EQ(Query(path, "select error from runs"), "NULL");
  EXPECT_EQ(Query(path, "select expect || ' ' || expect_partner || ' ' || quiet_until_s from runs"),
            "collision x 2.5");
  EXPECT_EQ(Query(path, "select category from runs"), "NULL");
  EXPECT_EQ(Query(path, "select objects || ' ' || objects_in_reach from steps where ego='ego'"),
            "2 1");
}

TEST(ResultsDb, WarningsNameTheirObjectAndCriticalEventsAreKept) {
  const std::string path = TempFile("critical.sqlite");
  {
    ResultsDb db(path);
    db.BeginRun("opts", "SUMO 1.15.0", "a", 0.1);
    db.OpenWarning("a", 1.5, 0.95, 1.0, 2.0, "WE", "ped7");
    db.OpenWarning("b", 2.5, 0.95, 1.0, 2.0, "WE");
    db.AddCriticalEvent(2.0, "a", "overlap", "ped7", 6.5);
    db.AddCriticalEvent(2.4, "a", "hard-braking", "", 9.0);
    db.Commit();
  }
  EXPECT_EQ(Query(path, "SELECT object FROM warnings WHERE ego='a'"), "ped7");
  EXPECT_EQ(Query(path, "SELECT object FROM warnings WHERE ego='b'"), "NULL");
  EXPECT_EQ(Query(path, "SELECT group_concat(kind || ':' || ifnull(other, '-') || ':' || value, "
                        "' ') FROM critical_events WHERE ego='a' ORDER BY time_s"),
            "overlap:ped7:6.5 hard-braking:-:9.0");
}

TEST(ResultsDb, OnlyCommittedStepsSurvive) {
  const std::string path = TempFile("killed.sqlite");
  {
    ResultsDb db(path);
    db.BeginRun("opts", "v", "ego", 0.1);
    db.AddStep(0.1, Row());
    db.AddEgoEvent(0.1, "ego", "depart", "");
    db.Commit();
    db.AddStep(0.2, Row());  // never committed: the run dies before the step ends
  }                        // closing rolls the open transaction back, as a killed process loses it
  EXPECT_EQ(Query(path, "select status from runs"), "running");
  EXPECT_EQ(Query(path, "select count(*) from steps"), "1");
  EXPECT_EQ(Query(path, "select time_s from steps"), "0.1");
  EXPECT_EQ(Query(path, "select event from ego_events"), "depart");
  EXPECT_NE(Query(path, "select heartbeat_unix from runs"), "NULL");
}

TEST(ResultsDb, AReaderHoldingTheFileNeitherBlocksNorSlowsTheRun) {
  const std::string path = TempFile("reader.sqlite");
  ResultsDb db(path);
  db.BeginRun("opts", "v", "ego", 0.1);
  db.AddStep(0.1, Row());
  db.Commit();
  // A reader in the middle of a read transaction (as `sqlite3 run.sqlite "select ..."` is).
  sqlite3* reader = nullptr;
  ASSERT_EQ(sqlite3_open_v2(path.c_str(), &reader, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(reader, "BEGIN; SELECT count(*) FROM steps;", nullptr, nullptr, nullptr),
            SQLITE_OK);
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 2; k <= 20; ++k) {
    db.AddStep(0.1 * k, Row());
    db.Commit();  // in rollback-journal mode this waits for the reader, then fails
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_LT(seconds, 1.0);  // not the 5 s busy timeout
  // The reader keeps its snapshot until it ends its transaction, then sees everything.
  sqlite3_stmt* s = nullptr;
  sqlite3_prepare_v2(reader, "SELECT count(*) FROM steps", -1, &s, nullptr);
  ASSERT_EQ(sqlite3_step(s), SQLITE_ROW);
  EXPECT_EQ(sqlite3_column_int(s, 0), 1);
  sqlite3_finalize(s);
  sqlite3_exec(reader, "COMMIT", nullptr, nullptr, nullptr);
  sqlite3_close(reader);
  EXPECT_EQ(Query(path, "select count(*) from steps"), "20");
  EXPECT_EQ(Query(path, "pragma journal_mode"), "wal");
}

TEST(ResultsDb, EndRunRecordsTheFailureAndClosingLeavesOneFile) {
  const std::string path = TempFile("failed.sqlite");
  {
    ResultsDb db(path);
    db.BeginRun("opts", "v", "ego", 0.1);
    db.AddStep(0.1, Row());
    db.Commit();
    db.EndRun("failed", "error", "SUMO error: connection closed", "{\"status\":\"failed\"}");
  }
  EXPECT_FALSE(Exists(path + "-wal"));  // closing folded the WAL into the file
  EXPECT_EQ(Query(path, "select status || '|' || end_reason || '|' || error from runs"),
            "failed|error|SUMO error: connection closed");
  EXPECT_EQ(Query(path, "select summary from runs"), "{\"status\":\"failed\"}");
}

TEST(ResultsDb, DiscardLeavesNoFile) {
  const std::string path = TempFile("discard.sqlite");
  ResultsDb db(path);
  db.BeginRun("opts", "v", "ego", 0.1);
  ASSERT_TRUE(Exists(path));
  db.Discard();
  EXPECT_FALSE(Exists(path));
  EXPECT_FALSE(Exists(path + "-wal"));
  EXPECT_FALSE(Exists(path + "-shm"));
}

TEST(ResultsDb, RefusesToOverwriteAndNamesTheProblem) {
  const std::string path = TempFile("exists.sqlite");
  { ResultsDb db(path); }
  try {
    ResultsDb again(path);
    FAIL();
  } catch (const ResultsError& e) {
    EXPECT_NE(std::string(e.what()).find("already exists"), std::string::npos);
  }
  EXPECT_THROW(ResultsDb("/nonexistent-dir/x.sqlite"), ResultsError);
}

}  // namespace
}  // namespace criticality::plugin
