#include "plugin/results_db.h"

#include <sys/stat.h>

#include <ctime>

namespace criticality::plugin {
namespace {

constexpr const char* kSchema = R"sql(
CREATE TABLE runs(
  id INTEGER PRIMARY KEY, started_utc TEXT NOT NULL, ended_utc TEXT, status TEXT NOT NULL,
  sumo_version TEXT, egos TEXT, options TEXT);
CREATE TABLE steps(
  run_id INTEGER NOT NULL REFERENCES runs(id), time_s REAL NOT NULL, ego TEXT NOT NULL,
  p_collision REAL NOT NULL, estimator_ms REAL NOT NULL, objects INTEGER NOT NULL,
  speed_mps REAL NOT NULL, acting INTEGER NOT NULL);
CREATE TABLE warnings(
  id INTEGER PRIMARY KEY, run_id INTEGER NOT NULL REFERENCES runs(id), ego TEXT NOT NULL,
  start_s REAL NOT NULL, end_s REAL, peak_p REAL NOT NULL);
CREATE TABLE actions(
  run_id INTEGER NOT NULL REFERENCES runs(id), time_s REAL NOT NULL, ego TEXT NOT NULL,
  kind TEXT NOT NULL, accel_mps2 REAL, speed_mps REAL, p_collision REAL);
CREATE TABLE collisions(
  run_id INTEGER NOT NULL REFERENCES runs(id), time_s REAL NOT NULL, collider TEXT NOT NULL,
  victim TEXT NOT NULL, collider_type TEXT, victim_type TEXT, type TEXT, lane TEXT, pos_m REAL,
  collider_speed_mps REAL, victim_speed_mps REAL, anticipation_s REAL);
CREATE INDEX steps_by_ego ON steps(run_id, ego, time_s);
)sql";

std::string UtcNow() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

}  // namespace

ResultsDb::ResultsDb(const std::string& path) : path_(path) {
  struct stat st {};
  if (stat(path.c_str(), &st) == 0) {
    throw ResultsError("output '" + path +
                       "' already exists; remove it or choose another --output");
  }
  if (sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) !=
      SQLITE_OK) {
    const std::string msg = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    db_ = nullptr;
    throw ResultsError("cannot create output '" + path + "': " + msg);
  }
  Exec("PRAGMA synchronous=NORMAL");
  Exec(kSchema);
  step_ = Prepare("INSERT INTO steps VALUES(?,?,?,?,?,?,?,?)");
  open_warning_ =
      Prepare("INSERT INTO warnings(run_id,ego,start_s,end_s,peak_p) VALUES(?,?,?,NULL,?)");
  peak_warning_ = Prepare("UPDATE warnings SET peak_p=? WHERE id=?");
  close_warning_ = Prepare("UPDATE warnings SET end_s=? WHERE id=?");
  action_ = Prepare("INSERT INTO actions VALUES(?,?,?,?,?,?,?)");
  collision_ = Prepare(
      "INSERT INTO collisions VALUES(?,?,?,?,?,?,?,?,?,?,?,"
      "(SELECT ?2 - start_s FROM warnings WHERE run_id=?1 AND ego IN (?3, ?4) AND start_s <= ?2 "
      "ORDER BY start_s DESC LIMIT 1))");
}

ResultsDb::~ResultsDb() {
  for (sqlite3_stmt* s :
       {step_, open_warning_, peak_warning_, close_warning_, action_, collision_}) {
    sqlite3_finalize(s);
  }
  if (db_) {
    sqlite3_exec(db_, "COMMIT", nullptr, nullptr, nullptr);  // no-op when none is open
    sqlite3_close(db_);
  }
}

void ResultsDb::Fail(const std::string& what) {
  throw ResultsError("cannot write results to '" + path_ + "' (" + what +
                     "): " + sqlite3_errmsg(db_));
}

void ResultsDb::Exec(const std::string& sql) {
  char* err = nullptr;
  if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &err) != SQLITE_OK) {
    const std::string msg = err ? err : "unknown error";
    sqlite3_free(err);
    throw ResultsError("cannot write results to '" + path_ + "': " + msg);
  }
}

sqlite3_stmt* ResultsDb::Prepare(const char* sql) {
  sqlite3_stmt* s = nullptr;
  if (sqlite3_prepare_v2(db_, sql, -1, &s, nullptr) != SQLITE_OK) Fail("prepare");
  return s;
}

void ResultsDb::Step(sqlite3_stmt* s, const char* what) {
  const int rc = sqlite3_step(s);
  sqlite3_reset(s);
  sqlite3_clear_bindings(s);
  if (rc != SQLITE_DONE) Fail(what);
}

void ResultsDb::BeginRun(const std::string& options, const std::string& sumo_version,
                         const std::string& egos) {
  sqlite3_stmt* s = Prepare(
      "INSERT INTO runs(started_utc,status,sumo_version,egos,options) VALUES(?,'running',?,?,?)");
  const std::string now = UtcNow();
  sqlite3_bind_text(s, 1, now.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(s, 2, sumo_version.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(s, 3, egos.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(s, 4, options.c_str(), -1, SQLITE_TRANSIENT);
  const int rc = sqlite3_step(s);
  sqlite3_finalize(s);
  if (rc != SQLITE_DONE) Fail("run");
  run_id_ = sqlite3_last_insert_rowid(db_);
  Exec("BEGIN");
}

void ResultsDb::AddStep(double time_s, const std::string& ego, double p, double ms, int objects,
                        double speed, bool acting) {
  sqlite3_bind_int64(step_, 1, run_id_);
  sqlite3_bind_double(step_, 2, time_s);
  sqlite3_bind_text(step_, 3, ego.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_double(step_, 4, p);
  sqlite3_bind_double(step_, 5, ms);
  sqlite3_bind_int(step_, 6, objects);
  sqlite3_bind_double(step_, 7, speed);
  sqlite3_bind_int(step_, 8, acting ? 1 : 0);
  Step(step_, "step");
}

long long ResultsDb::OpenWarning(const std::string& ego, double start_s, double p) {
  sqlite3_bind_int64(open_warning_, 1, run_id_);
  sqlite3_bind_text(open_warning_, 2, ego.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_double(open_warning_, 3, start_s);
  sqlite3_bind_double(open_warning_, 4, p);
  Step(open_warning_, "warning");
  return sqlite3_last_insert_rowid(db_);
}

void ResultsDb::UpdateWarningPeak(long long id, double peak) {
  sqlite3_bind_double(peak_warning_, 1, peak);
  sqlite3_bind_int64(peak_warning_, 2, id);
  Step(peak_warning_, "warning peak");
}

void ResultsDb::CloseWarning(long long id, double end_s) {
  sqlite3_bind_double(close_warning_, 1, end_s);
  sqlite3_bind_int64(close_warning_, 2, id);
  Step(close_warning_, "warning end");
}

void ResultsDb::AddAction(double time_s, const std::string& ego, const std::string& kind,
                          double accel, double speed, double p) {
  sqlite3_bind_int64(action_, 1, run_id_);
  sqlite3_bind_double(action_, 2, time_s);
  sqlite3_bind_text(action_, 3, ego.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(action_, 4, kind.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_double(action_, 5, accel);
  sqlite3_bind_double(action_, 6, speed);
  sqlite3_bind_double(action_, 7, p);
  Step(action_, "action");
}

void ResultsDb::AddCollision(const CollisionRow& c) {
  sqlite3_stmt* s = collision_;
  sqlite3_bind_int64(s, 1, run_id_);
  sqlite3_bind_double(s, 2, c.time_s);
  sqlite3_bind_text(s, 3, c.collider.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(s, 4, c.victim.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(s, 5, c.collider_type.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(s, 6, c.victim_type.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(s, 7, c.type.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(s, 8, c.lane.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_double(s, 9, c.pos_m);
  sqlite3_bind_double(s, 10, c.collider_speed_mps);
  sqlite3_bind_double(s, 11, c.victim_speed_mps);
  Step(s, "collision");
}

void ResultsDb::Commit() {
  Exec("COMMIT");
  Exec("BEGIN");
}

void ResultsDb::EndRun(const std::string& status) {
  sqlite3_stmt* s = Prepare("UPDATE runs SET ended_utc=?, status=? WHERE id=?");
  const std::string now = UtcNow();
  sqlite3_bind_text(s, 1, now.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(s, 2, status.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_int64(s, 3, run_id_);
  const int rc = sqlite3_step(s);
  sqlite3_finalize(s);
  if (rc != SQLITE_DONE) Fail("run end");
  Exec("COMMIT");
  Exec("BEGIN");
}

}  // namespace criticality::plugin
