// The results database: schema, episodes, anticipation times, refusing to overwrite.
#include "plugin/results_db.h"

#include <gtest/gtest.h>
#include <sqlite3.h>

#include <cstdio>
#include <string>

namespace criticality::plugin {
namespace {

std::string Query(const std::string& path, const std::string& sql) {
  sqlite3* db = nullptr;
  sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr);
  sqlite3_stmt* s = nullptr;
  std::string out;
  if (sqlite3_prepare_v2(db, sql.c_str(), -1, &s, nullptr) == SQLITE_OK &&
      sqlite3_step(s) == SQLITE_ROW) {
    const unsigned char* t = sqlite3_column_text(s, 0);
    out = t ? reinterpret_cast<const char*>(t) : "NULL";
  }
  sqlite3_finalize(s);
  sqlite3_close(db);
  return out;
}

std::string TempFile(const char* name) {
  const std::string path = ::testing::TempDir() + name;
  std::remove(path.c_str());
  return path;
}

TEST(ResultsDb, AnticipationIsCollisionTimeMinusTheWarningStart) {
  const std::string path = TempFile("anticipation.sqlite");
  {
    ResultsDb db(path);
    db.BeginRun("opts", "SUMO 1.15.0", "ego");
    db.AddStep(1.0, "ego", 0.2, 3.0, 2, 20.0, false);
    const long long w = db.OpenWarning("ego", 1.5, 0.6);
    db.UpdateWarningPeak(w, 0.9);
    db.AddCollision(CollisionRow{3.0, "ego", "lead", "car", "car", "collision", "WE_1", 20, 5, 99});
    db.AddCollision(
        CollisionRow{4.0, "other", "third", "car", "car", "collision", "WE_0", 9, 8, 12});
    db.CloseWarning(w, 3.2);
    db.EndRun("completed");
  }
  EXPECT_EQ(Query(path, "select anticipation_s from collisions where collider='ego'"), "1.5");
  EXPECT_EQ(Query(path, "select anticipation_s from collisions where collider='other'"), "NULL");
  EXPECT_EQ(Query(path, "select peak_p from warnings"), "0.9");
  EXPECT_EQ(Query(path, "select status from runs"), "completed");
  EXPECT_EQ(Query(path, "select count(*) from steps"), "1");
}

TEST(ResultsDb, CommittedStepsSurviveWithoutEndRun) {
  const std::string path = TempFile("killed.sqlite");
  {
    ResultsDb db(path);
    db.BeginRun("opts", "v", "ego");
    db.AddStep(0.1, "ego", 0.0, 1.0, 0, 10.0, false);
    db.Commit();
    db.AddStep(0.2, "ego", 0.0, 1.0, 0, 10.0, false);  // never committed
  }  // as if killed after the first step (the destructor's COMMIT is the only difference)
  EXPECT_EQ(Query(path, "select status from runs"), "running");
  EXPECT_GE(std::stoi(Query(path, "select count(*) from steps")), 1);
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
