// The result views (plugin/record/result_views.sql) on small hand-made databases: what followed
// a warning (collision, overlap, hard braking, else a false alarm) on the boundaries of its
// window, the anticipation of a collision with its one-step tolerance, and the placeholders
// (run key, episodes table, grace) for run files, merged campaigns and replayed episodes.
#include "plugin/record/result_views.h"

#include <gtest/gtest.h>
#include <sqlite3.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

namespace criticality::plugin {
namespace {

class Db {
 public:
  Db() { sqlite3_open(":memory:", &db_); }
  ~Db() { sqlite3_close(db_); }
  Db(const Db&) = delete;
  Db& operator=(const Db&) = delete;

  void Exec(const std::string& sql) {
    char* err = nullptr;
    if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &err) != SQLITE_OK) {
      const std::string msg = err ? err : "?";
      sqlite3_free(err);
      throw std::runtime_error(msg + " in: " + sql);
    }
  }

  // The first column of each row of `sql` with `bound` bound to ?1, ?2, ... (NULL: nullopt).
  std::vector<std::optional<std::string>> Texts(const std::string& sql,
                                                const std::vector<double>& bound = {}) {
    sqlite3_stmt* s = Prepare(sql);
    for (std::size_t k = 0; k < bound.size(); ++k) {
      sqlite3_bind_double(s, static_cast<int>(k + 1), bound[k]);
    }
    std::vector<std::optional<std::string>> out;
    while (sqlite3_step(s) == SQLITE_ROW) {
      const unsigned char* t = sqlite3_column_text(s, 0);
      out.push_back(t ? std::optional<std::string>(reinterpret_cast<const char*>(t))
                      : std::nullopt);
    }
    sqlite3_finalize(s);
    return out;
  }

  std::vector<std::optional<double>> Reals(const std::string& sql) {
    sqlite3_stmt* s = Prepare(sql);
    std::vector<std::optional<double>> out;
    while (sqlite3_step(s) == SQLITE_ROW) {
      out.push_back(sqlite3_column_type(s, 0) == SQLITE_NULL
                        ? std::nullopt
                        : std::optional<double>(sqlite3_column_double(s, 0)));
    }
    sqlite3_finalize(s);
    return out;
  }

  // Inserts one row, the values bound as doubles or text.
  void Insert(const std::string& table, const std::vector<std::optional<double>>& numbers,
              const std::vector<std::string>& texts, const std::string& columns) {
    std::string marks;
    const std::size_t n = numbers.size() + texts.size();
    for (std::size_t k = 0; k < n; ++k) marks += k ? ",?" : "?";
    sqlite3_stmt* s = Prepare("INSERT INTO " + table + "(" + columns + ") VALUES(" + marks + ")");
    int k = 1;
    for (const auto& v : numbers) {
      if (v) {
        sqlite3_bind_double(s, k++, *v);
      } else {
        sqlite3_bind_null(s, k++);
      }
    }
    for (const std::string& t : texts) sqlite3_bind_text(s, k++, t.c_str(), -1, SQLITE_TRANSIENT);
    if (sqlite3_step(s) != SQLITE_DONE) throw std::runtime_error(sqlite3_errmsg(db_));
    sqlite3_finalize(s);
  }

 private:
  sqlite3_stmt* Prepare(const std::string& sql) {
    sqlite3_stmt* s = nullptr;
    if (sqlite3_prepare_v2(db_, sql.c_str(), -1, &s, nullptr) != SQLITE_OK) {
      throw std::runtime_error(std::string(sqlite3_errmsg(db_)) + " in: " + sql);
    }
    return s;
  }

  sqlite3* db_{nullptr};
};

// The tables the views read, as in a driver's run file (only the columns they need).
void RunFileTables(Db& db, double step_s = 0.1) {
  db.Exec(
      "CREATE TABLE runs(id INTEGER PRIMARY KEY, step_length_s REAL);"
      "CREATE TABLE warnings(id INTEGER PRIMARY KEY, run_id INTEGER, ego TEXT, start_s REAL, "
      "end_s REAL);"
      "CREATE TABLE collisions(run_id INTEGER, time_s REAL, collider TEXT, victim TEXT);"
      "CREATE TABLE critical_events(run_id INTEGER, time_s REAL, ego TEXT, kind TEXT);"
      "CREATE TABLE steps(run_id INTEGER, time_s REAL, ego TEXT, main_object TEXT);");
  db.Insert("runs", {1.0, step_s}, {}, "id, step_length_s");
}

// The rules that pick the episode, whatever it warned of: episodes credited from their start
// (as for run files without steps.main_object).
ResultViewKeys Unattributed() {
  ResultViewKeys keys = ResultViewKeys::RunFile();
  keys.attributed = false;
  return keys;
}

// The ego's step at t with `object` as the main object of its estimate.
void MainObject(Db& db, const std::string& ego, double t, const std::string& object,
                double run = 1.0) {
  db.Insert("steps", {run, t}, {ego, object}, "run_id, time_s, ego, main_object");
}

void Warning(Db& db, const std::string& ego, double start, std::optional<double> end,
             double run = 1.0) {
  db.Insert("warnings", {run, start, end}, {ego}, "run_id, start_s, end_s, ego");
}
void Collision(Db& db, double t, const std::string& collider, const std::string& victim,
               double run = 1.0) {
  db.Insert("collisions", {run, t}, {collider, victim}, "run_id, time_s, collider, victim");
}
void Event(Db& db, double t, const std::string& ego, const std::string& kind, double run = 1.0) {
  db.Insert("critical_events", {run, t}, {ego, kind}, "run_id, time_s, ego, kind");
}

// Outcomes in warning order ("-": a false alarm).
std::vector<std::string> Outcomes(Db& db) {
  std::vector<std::string> out;
  for (const auto& o : db.Texts("SELECT outcome FROM warning_outcomes ORDER BY start_s, ego")) {
    out.push_back(o.value_or("-"));
  }
  return out;
}

TEST(ResultViews, CollisionBeatsOverlapBeatsHardBraking) {
  Db db;
  RunFileTables(db);
  db.Exec(ResultViewsSql(ResultViewKeys::RunFile()));
  Warning(db, "a", 1.0, 2.0);  // all three follow
  Collision(db, 3.0, "x", "a");
  Event(db, 1.5, "a", "overlap");
  Event(db, 1.6, "a", "hard-braking");
  Warning(db, "b", 2.0, 3.0);  // overlap and hard braking
  Event(db, 3.5, "b", "hard-braking");
  Event(db, 4.0, "b", "overlap");
  Warning(db, "c", 3.0, 4.0);  // hard braking only
  Event(db, 5.0, "c", "hard-braking");
  Warning(db, "d", 4.0, 5.0);  // what follows is another ego's or of another kind
  Event(db, 4.5, "a", "overlap");
  Event(db, 4.5, "d", "something-else");
  Collision(db, 4.5, "a", "x");
  Warning(db, "e", 5.0, 6.0);  // a pass-through (after an overlap, before hard braking)
  Event(db, 5.5, "e", "hard-braking");
  Event(db, 6.0, "e", "pass-through");
  EXPECT_EQ(Outcomes(db), (std::vector<std::string>{"collision", "overlap", "hard-braking", "-",
                                                    "pass-through"}));
}

TEST(ResultViews, TheWindowRunsFromTheStartToTheEndPlusTheGraceAsTheEvaluationAddsIt) {
  const double grace = 0.2;
  // 0.1 + 0.2 = 0.30000000000000004 and (0.30000000000000004 - 0.1) > 0.2: an event exactly
  // at end + grace counts, although t - end <= grace would say it does not.
  const double end = 0.1, at_edge = end + grace;
  ASSERT_GT(at_edge - end, grace);
  const double past = std::nextafter(at_edge, std::numeric_limits<double>::infinity());
  const double start = 0.05, before = std::nextafter(start, 0.0);
  Db db;
  RunFileTables(db);
  ResultViewKeys keys = ResultViewKeys::RunFile();
  keys.grace_s = grace;
  db.Exec(ResultViewsSql(keys));
  std::vector<std::optional<std::string>> expected;
  // Each kind on its own, at each boundary: ego "<kind> <where>".
  for (const std::string kind : {"collision", "hard-braking", "overlap", "pass-through"}) {
    for (const auto& [where, t, counts] :
         {std::tuple<std::string, double, bool>{"at end + grace", at_edge, true},
          {"at start", start, true},
          {"just after end + grace", past, false},
          {"just before start", before, false}}) {
      const std::string ego = kind + " " + where;
      Warning(db, ego, start, end);
      if (kind == "collision") {
        Collision(db, t, "x", ego);
      } else {
        Event(db, t, ego, kind);
      }
      expected.push_back(ego + ": " + (counts ? kind : "-"));
    }
  }
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(db.Texts("SELECT ego || ': ' || COALESCE(outcome, '-') FROM warning_outcomes "
                     "ORDER BY 1"),
            expected);
}

TEST(ResultViews, AnOpenEpisodeIsJudgedAsIfItEndedAtItsStart) {
  Db db;
  RunFileTables(db);
  db.Exec(ResultViewsSql(ResultViewKeys::RunFile()));
  Warning(db, "a", 10.0, std::nullopt);
  Event(db, 12.0, "a", "hard-braking");  // start + grace: counts
  Warning(db, "b", 10.0, std::nullopt);
  Event(db, 12.5, "b", "hard-braking");  // later: does not
  EXPECT_EQ(Outcomes(db), (std::vector<std::string>{"hard-braking", "-"}));
  EXPECT_EQ(db.Reals("SELECT window_end_s FROM warning_outcomes ORDER BY ego"),
            (std::vector<std::optional<double>>{12.0, 12.0}));
}

TEST(ResultViews, TheGraceIsTheOneGiven) {
  Db db;
  RunFileTables(db);
  Warning(db, "a", 1.0, 2.0);
  Event(db, 3.5, "a", "overlap");
  db.Exec(ResultViewsSql(ResultViewKeys::RunFile()));  // 2 s: followed
  EXPECT_EQ(Outcomes(db), (std::vector<std::string>{"overlap"}));
  ResultViewKeys one = ResultViewKeys::RunFile();
  one.grace_s = 1.0;
  db.Exec(DropResultViewsSql(one) + ResultViewsSql(one));  // replaced: 1 s, a false alarm
  EXPECT_EQ(Outcomes(db), (std::vector<std::string>{"-"}));
}

TEST(ResultViews, CriticalEventsAreWarnedOfWithinTheSameWindow) {
  Db db;
  RunFileTables(db);
  db.Exec(ResultViewsSql(ResultViewKeys::RunFile()));
  Warning(db, "a", 10.0, 11.0);
  Event(db, 9.9, "a", "overlap");        // before the start
  Event(db, 13.0, "a", "overlap");       // end + grace
  Event(db, 13.1, "a", "hard-braking");  // later
  Event(db, 10.5, "b", "overlap");       // another ego's
  EXPECT_EQ(
      db.Texts("SELECT ego || '@' || time_s || '=' || warned FROM critical_event_warnings "
               "ORDER BY time_s, ego"),
      (std::vector<std::optional<std::string>>{"a@9.9=0", "b@10.5=0", "a@13.0=1", "a@13.1=0"}));
}

TEST(ResultViews, AnticipationCountsAnEpisodeEndedOneStepBeforeTheImpactNotTwo) {
  Db db;
  RunFileTables(db, 0.1);
  db.Exec(ResultViewsSql(Unattributed()));
  Warning(db, "a", 1.0, 1.5);  // one step before 1.6, two before 1.7
  Collision(db, 1.6, "a", "x");
  Collision(db, 1.7, "a", "x");
  Warning(db, "b", 2.0, std::nullopt);  // opens at the impact: does not anticipate it
  Collision(db, 2.0, "b", "x");
  Warning(db, "c", 3.0, 3.8);  // open at the impact, as collider and as victim
  Collision(db, 3.4, "c", "x");
  Collision(db, 3.5, "y", "c");
  Warning(db, "d", 4.0, std::nullopt);  // never closed (a killed run): open
  Warning(db, "d", 4.2, 4.3);           // the latest that began before the impact counts
  Collision(db, 4.4, "d", "x");
  Collision(db, 4.5, "z", "w");  // no episode of its vehicles
  const auto got = db.Reals("SELECT anticipation_s FROM collision_anticipation ORDER BY time_s");
  ASSERT_EQ(got.size(), 7u);
  // Rounded to 1e-6 s: 0.6, not the subtraction's 0.6000000000000001 (1.6 - 1.0).
  EXPECT_EQ(got[0], std::optional<double>(0.6));
  EXPECT_EQ(got[1], std::nullopt);
  EXPECT_EQ(got[2], std::nullopt);
  EXPECT_EQ(got[3], std::optional<double>(0.4));
  EXPECT_EQ(got[4], std::optional<double>(0.5));
  EXPECT_EQ(got[5], std::optional<double>(0.2));
  EXPECT_EQ(got[6], std::nullopt);
}

TEST(ResultViews, AnticipationCountsFromTheFirstStepThatNamedThePartner) {
  Db db;
  RunFileTables(db, 0.1);
  db.Exec(ResultViewsSql(ResultViewKeys::RunFile()));
  // The collider's episode first warned of a pedestrian, then of the car it hit.
  Warning(db, "a", 1.0, std::nullopt);
  MainObject(db, "a", 1.0, "ped");
  MainObject(db, "a", 1.1, "ped");
  MainObject(db, "a", 1.2, "car");
  MainObject(db, "a", 1.3, "ped");
  Collision(db, 1.5, "a", "car");
  // An episode that only ever warned of someone else anticipates nothing.
  Warning(db, "b", 2.0, std::nullopt);
  MainObject(db, "b", 2.0, "ped");
  MainObject(db, "b", 2.1, "ped");
  Collision(db, 2.3, "b", "car");
  // The victim's episode names the collider; the collider's own episode, later, names someone
  // else: the victim's counts.
  Warning(db, "v", 3.0, std::nullopt);
  MainObject(db, "v", 3.0, "c");
  Warning(db, "c", 3.2, std::nullopt);
  MainObject(db, "c", 3.2, "other");
  Collision(db, 3.6, "c", "v");
  // A step that named the partner at the impact's own stamp (written before that step) or
  // before the episode does not count.
  Warning(db, "d", 4.0, std::nullopt);
  MainObject(db, "d", 3.9, "car");
  MainObject(db, "d", 4.0, "ped");
  MainObject(db, "d", 4.4, "car");
  Collision(db, 4.4, "d", "car");
  EXPECT_EQ(db.Reals("SELECT anticipation_s FROM collision_anticipation ORDER BY time_s"),
            (std::vector<std::optional<double>>{0.3, std::nullopt, 0.6,
                                                std::nullopt}));
}

TEST(ResultViews, TheOneStepToleranceIsTheRunsStepLength) {
  Db db;
  RunFileTables(db, 0.5);
  db.Insert("runs", {2.0, 0.1}, {}, "id, step_length_s");
  db.Exec(ResultViewsSql(Unattributed()));
  Warning(db, "a", 1.0, 1.5, 1.0);  // run 1, step 0.5: 0.5 s before the impact counts
  Collision(db, 2.0, "a", "x", 1.0);
  Warning(db, "a", 1.0, 1.5, 2.0);  // run 2, step 0.1: it does not
  Collision(db, 2.0, "a", "x", 2.0);
  EXPECT_EQ(db.Reals("SELECT anticipation_s FROM collision_anticipation ORDER BY run_id"),
            (std::vector<std::optional<double>>{1.0, std::nullopt}));
}

// A merged campaign.sqlite: every run keeps run_id = 1; run_index tells them apart.
TEST(ResultViews, CampaignKeysJudgeEachRunByItsRunIndex) {
  Db db;
  db.Exec(
      "CREATE TABLE runs(run_index INTEGER, id INTEGER, step_length_s REAL);"
      "CREATE TABLE warnings(run_index INTEGER, run_id INTEGER, ego TEXT, start_s REAL, "
      "end_s REAL);"
      "CREATE TABLE collisions(run_index INTEGER, run_id INTEGER, time_s REAL, collider TEXT, "
      "victim TEXT);"
      "CREATE TABLE critical_events(run_index INTEGER, run_id INTEGER, time_s REAL, ego TEXT, "
      "kind TEXT);"
      "INSERT INTO runs VALUES(0, 1, 0.1), (1, 1, 0.1);"
      "INSERT INTO warnings VALUES(0, 1, 'ego', 1.0, 1.5), (1, 1, 'ego', 1.0, 1.5);"
      "INSERT INTO collisions VALUES(1, 1, 1.2, 'ego', 'x');"
      "INSERT INTO critical_events VALUES(1, 1, 1.3, 'ego', 'overlap');");
  ResultViewKeys keys = ResultViewKeys::Campaign(1.0);
  keys.attributed = false;  // these runs' steps name no main object: from the episode's start
  db.Exec("CREATE TABLE steps(run_index INTEGER, run_id INTEGER, time_s REAL, ego TEXT)");
  db.Exec(ResultViewsSql(keys));
  EXPECT_EQ(db.Texts("SELECT run_index || ':' || COALESCE(outcome, '-') FROM "
                     "temp.warning_outcomes ORDER BY run_index"),
            (std::vector<std::optional<std::string>>{"0:-", "1:collision"}));
  EXPECT_EQ(db.Reals("SELECT anticipation_s FROM temp.collision_anticipation"),
            (std::vector<std::optional<double>>{0.2}));
}

// The evaluation's replayed (or SSM's) episodes in a table of their own, judged by the same rule.
TEST(ResultViews, AnotherEpisodesTableIsJudgedByTheSameRule) {
  Db db;
  RunFileTables(db);
  db.Exec("CREATE TEMP TABLE replayed(run_id, ego, start_s, end_s)");
  db.Exec("INSERT INTO temp.replayed VALUES(1, 'a', 1.0, 2.0), (1, 'b', 1.0, 2.0)");
  Warning(db, "a", 50.0, 51.0);  // the driver's own: not judged here
  Collision(db, 3.0, "a", "x");
  ResultViewKeys keys = ResultViewKeys::RunFile();
  keys.schema = "temp";
  keys.warnings = "temp.replayed";
  db.Exec(ResultViewsSql(keys));
  EXPECT_EQ(Outcomes(db), (std::vector<std::string>{"collision", "-"}));
}

TEST(ResultViews, NamesMustBeIdentifiersAndTheGraceFinite) {
  ResultViewKeys keys = ResultViewKeys::RunFile();
  keys.warnings = "warnings; DROP TABLE runs";
  EXPECT_THROW(ResultViewsSql(keys), std::invalid_argument);
  keys = ResultViewKeys::RunFile();
  keys.grace_s = std::numeric_limits<double>::infinity();
  EXPECT_THROW(ResultViewsSql(keys), std::invalid_argument);
  const std::string sql = ResultViewsSql(ResultViewKeys::RunFile());
  EXPECT_EQ(sql.find("{{"), std::string::npos);
  EXPECT_NE(sql.find("+ 2.0"), std::string::npos);  // the default grace, as a literal
  EXPECT_NE(DropResultViewsSql(ResultViewKeys::RunFile())
                .find("DROP VIEW IF EXISTS main.collision_anticipation;"),
            std::string::npos);
}

TEST(ResultViews, LiteralsReadBackAsTheSameDouble) {
  EXPECT_EQ(SqlRealLiteral(2.0), "2.0");
  EXPECT_EQ(SqlRealLiteral(0.3), "0.3");
  EXPECT_EQ(SqlRealLiteral(-1.5), "-1.5");
  Db db;
  // 2.024585207138345: SQLite 3.40 reads its shortest decimal one ulp off.
  for (const double v :
       {2.0, 1.0, 0.1, 0.3, 1e-6, 0.1 + 0.2, 2.024585207138345, 1.0 / 3.0, 123456.789, -0.75}) {
    const std::string lit = SqlRealLiteral(v);
    EXPECT_EQ(db.Texts("SELECT " + lit + " = ?1 AND typeof(" + lit + ") = 'real'", {v}),
              (std::vector<std::optional<std::string>>{"1"}))
        << lit;
  }
}

}  // namespace
}  // namespace criticality::plugin
