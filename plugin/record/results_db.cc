#include "plugin/record/results_db.h"

#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <ctime>

#include "plugin/record/result_views.h"

namespace criticality::plugin {
namespace {

constexpr const char* kSchema = R"sql(
CREATE TABLE runs(
  id INTEGER PRIMARY KEY, started_utc TEXT NOT NULL, ended_utc TEXT, status TEXT NOT NULL,
  end_reason TEXT, error TEXT, heartbeat_unix REAL, step_length_s REAL, sumo_version TEXT,
  egos TEXT, options TEXT, expect TEXT, expect_partner TEXT, quiet_until_s REAL,
  category TEXT, summary TEXT);
CREATE TABLE steps(
  run_id INTEGER NOT NULL REFERENCES runs(id), time_s REAL NOT NULL, ego TEXT NOT NULL,
  p_collision REAL NOT NULL, estimator_ms REAL NOT NULL, objects INTEGER NOT NULL,
  objects_in_reach INTEGER NOT NULL, speed_mps REAL NOT NULL, acting INTEGER NOT NULL,
  p_reference REAL NOT NULL, unavoidability REAL NOT NULL, main_object TEXT);
CREATE TABLE warnings(
  id INTEGER PRIMARY KEY, run_id INTEGER NOT NULL REFERENCES runs(id), ego TEXT NOT NULL,
  start_s REAL NOT NULL, end_s REAL, peak_p REAL NOT NULL, x_m REAL, y_m REAL, edge TEXT,
  object TEXT);
CREATE TABLE actions(
  run_id INTEGER NOT NULL REFERENCES runs(id), time_s REAL NOT NULL, ego TEXT NOT NULL,
  kind TEXT NOT NULL, accel_mps2 REAL, speed_mps REAL, p_collision REAL, speed_after_mps REAL,
  lane_before TEXT, lane_after TEXT, route INTEGER, route_collision_probability REAL,
  route_probability REAL, detail TEXT);
CREATE TABLE collisions(
  run_id INTEGER NOT NULL REFERENCES runs(id), time_s REAL NOT NULL, collider TEXT NOT NULL,
  victim TEXT NOT NULL, collider_type TEXT, victim_type TEXT, type TEXT, lane TEXT, pos_m REAL,
  x_m REAL, y_m REAL, collider_speed_mps REAL, victim_speed_mps REAL,
  involves_ego INTEGER NOT NULL, anticipation_s REAL);
CREATE TABLE ego_events(
  run_id INTEGER NOT NULL REFERENCES runs(id), time_s REAL NOT NULL, ego TEXT NOT NULL,
  event TEXT NOT NULL, detail TEXT);
CREATE TABLE critical_events(
  run_id INTEGER NOT NULL REFERENCES runs(id), time_s REAL NOT NULL, ego TEXT NOT NULL,
  kind TEXT NOT NULL, other TEXT, value REAL);
CREATE TABLE step_times(
  run_id INTEGER NOT NULL REFERENCES runs(id), time_s REAL NOT NULL, estimates INTEGER NOT NULL,
  shortcut_estimates INTEGER NOT NULL, sumo_ms REAL, observe_ms REAL, scenes_ms REAL,
  estimate_ms REAL, act_ms REAL, record_ms REAL, rss_mb REAL);
CREATE TABLE egos(
  run_id INTEGER NOT NULL REFERENCES runs(id), ego TEXT NOT NULL, vehicle_class TEXT,
  vehicle_type TEXT, length_m REAL, width_m REAL, first_s REAL NOT NULL);
CREATE TABLE warning_scenes(
  warning_id INTEGER NOT NULL REFERENCES warnings(id), run_id INTEGER NOT NULL REFERENCES runs(id),
  ego TEXT NOT NULL, time_s REAL NOT NULL, scene TEXT NOT NULL);
CREATE INDEX steps_by_ego ON steps(run_id, ego, time_s);
)sql";

std::string UtcNow() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

double UnixNow() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

void BindOptionalDouble(sqlite3_stmt* s, int k, double v) {
  if (std::isfinite(v)) {
    sqlite3_bind_double(s, k, v);
  } else {
    sqlite3_bind_null(s, k);
  }
}

// An empty text is stored as NULL.
void BindOptionalText(sqlite3_stmt* s, int k, const std::string& text) {
  if (text.empty()) {
    sqlite3_bind_null(s, k);
  } else {
    sqlite3_bind_text(s, k, text.c_str(), -1, SQLITE_TRANSIENT);
  }
}

}  // namespace

void CheckOutputCreatable(const std::string& path) {
  struct stat st {};
  if (stat(path.c_str(), &st) == 0) {
    throw ResultsError("output '" + path + "' already exists" +
                       (S_ISDIR(st.st_mode) ? " (a folder); name a file in it" : "; remove it") +
                       " or choose another --output");
  }
  const size_t slash = path.find_last_of('/');
  const std::string folder =
      slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
  if (stat(folder.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) {
    throw ResultsError("cannot create output '" + path + "': no folder '" + folder +
                       "'; create it first or choose another --output");
  }
  if (access(folder.c_str(), W_OK) != 0) {
    throw ResultsError("cannot create output '" + path + "': folder '" + folder +
                       "' is not writable; choose another --output");
  }
}

ResultsDb::ResultsDb(const std::string& path) : path_(path) {
  CheckOutputCreatable(path);
  if (sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) !=
      SQLITE_OK) {
    const std::string msg = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    db_ = nullptr;
    throw ResultsError("cannot create output '" + path + "': " + msg);
  }
  try {
    // Readers wait up to 5 s for the rare moments they need a lock; so does the run.
    sqlite3_busy_timeout(db_, 5000);
    Exec("PRAGMA journal_mode=WAL");
    Exec("PRAGMA synchronous=NORMAL");
    Exec(kSchema);
    step_ = Prepare("INSERT INTO steps VALUES(?,?,?,?,?,?,?,?,?,?,?,?)");
    open_warning_ = Prepare(
        "INSERT INTO warnings(run_id,ego,start_s,end_s,peak_p,x_m,y_m,edge,object) "
        "VALUES(?,?,?,NULL,?,?,?,?,?)");
    peak_warning_ = Prepare("UPDATE warnings SET peak_p=? WHERE id=?");
    close_warning_ = Prepare("UPDATE warnings SET end_s=? WHERE id=?");
    action_ = Prepare("INSERT INTO actions VALUES(?,?,?,?,?,?,?,?,?,?,?,?,?,?)");
    // The views that define a warning's outcome and a collision's anticipation
    // (result_views.sql): readers of the file query them; the anticipation stored with each
    // collision is the view's, taken when the collision is recorded.
    Exec(ResultViewsSql(ResultViewKeys::RunFile()));
    collision_ = Prepare(
        "INSERT INTO collisions VALUES(?1,?2,?3,?4,?5,?6,?7,?8,?9,?10,?11,?12,?13,?14,NULL)");
    anticipation_ = Prepare(
        "UPDATE collisions SET anticipation_s = (SELECT anticipation_s FROM collision_anticipation "
        "WHERE collision_rowid = ?1) WHERE rowid = ?1");
    ego_event_ = Prepare("INSERT INTO ego_events VALUES(?,?,?,?,?)");
    ego_ = Prepare("INSERT INTO egos VALUES(?,?,?,?,?,?,?)");
    warning_scene_ = Prepare("INSERT INTO warning_scenes VALUES(?,?,?,?,?)");
    critical_event_ = Prepare("INSERT INTO critical_events VALUES(?,?,?,?,?,?)");
    step_time_ = Prepare("INSERT INTO step_times VALUES(?,?,?,?,?,?,?,?,?,?,?)");
    heartbeat_ = Prepare("UPDATE runs SET heartbeat_unix=? WHERE id=?");
  } catch (...) {
    Discard();  // a half-made file is no result
    throw;
  }
}

ResultsDb::~ResultsDb() { Close(); }

void ResultsDb::Close() {
  for (sqlite3_stmt* s : {step_, open_warning_, peak_warning_, close_warning_, action_, collision_,
                          anticipation_, ego_event_, ego_, warning_scene_, critical_event_,
                          step_time_, heartbeat_}) {
    sqlite3_finalize(s);
  }
  step_ = open_warning_ = peak_warning_ = close_warning_ = action_ = collision_ = anticipation_ =
      ego_event_ = ego_ = warning_scene_ = critical_event_ = step_time_ = heartbeat_ = nullptr;
  // An open transaction is rolled back: only what Commit() or EndRun() committed stays.
  if (db_) sqlite3_close(db_);
  db_ = nullptr;
}

void ResultsDb::Discard() {
  Close();
  for (const char* suffix : {"", "-wal", "-shm", "-journal"}) unlink((path_ + suffix).c_str());
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
                         const std::string& egos, double step_length_s) {
  sqlite3_stmt* s = Prepare(
      "INSERT INTO runs(started_utc,status,heartbeat_unix,step_length_s,sumo_version,egos,options)"
      " VALUES(?,'running',?,?,?,?,?)");
  const std::string now = UtcNow();
  last_heartbeat_ = UnixNow();
  sqlite3_bind_text(s, 1, now.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_double(s, 2, last_heartbeat_);
  sqlite3_bind_double(s, 3, step_length_s);
  sqlite3_bind_text(s, 4, sumo_version.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(s, 5, egos.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(s, 6, options.c_str(), -1, SQLITE_TRANSIENT);
  const int rc = sqlite3_step(s);
  sqlite3_finalize(s);
  if (rc != SQLITE_DONE) Fail("run");
  run_id_ = sqlite3_last_insert_rowid(db_);
  Exec("BEGIN");
}

void ResultsDb::SetScenario(const std::string& expect, const std::string& expect_partner,
                            double quiet_until_s, const std::string& category) {
  sqlite3_stmt* s = Prepare(
      "UPDATE runs SET expect=NULLIF(?,''), expect_partner=NULLIF(?,''), quiet_until_s=?, "
      "category=NULLIF(?,'') WHERE id=?");
  sqlite3_bind_text(s, 1, expect.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(s, 2, expect_partner.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_double(s, 3, quiet_until_s);
  sqlite3_bind_text(s, 4, category.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_int64(s, 5, run_id_);
  const int rc = sqlite3_step(s);
  sqlite3_finalize(s);
  if (rc != SQLITE_DONE) Fail("scenario");
}

void ResultsDb::AddStep(double time_s, const EgoStep& r) {
  sqlite3_bind_int64(step_, 1, run_id_);
  sqlite3_bind_double(step_, 2, time_s);
  sqlite3_bind_text(step_, 3, r.ego.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_double(step_, 4, r.p_collision);
  sqlite3_bind_double(step_, 5, r.estimator_ms);
  sqlite3_bind_int(step_, 6, r.objects);
  sqlite3_bind_int(step_, 7, r.objects_in_reach);
  sqlite3_bind_double(step_, 8, r.speed_mps);
  sqlite3_bind_int(step_, 9, r.acting ? 1 : 0);
  sqlite3_bind_double(step_, 10, r.p_reference);
  sqlite3_bind_double(step_, 11, r.unavoidability);
  BindOptionalText(step_, 12, r.main_object);
  Step(step_, "step");
}

long long ResultsDb::OpenWarning(const std::string& ego, double start_s, double p, double x_m,
                                 double y_m, const std::string& edge,
                                 const std::string& object) {
  sqlite3_bind_int64(open_warning_, 1, run_id_);
  sqlite3_bind_text(open_warning_, 2, ego.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_double(open_warning_, 3, start_s);
  sqlite3_bind_double(open_warning_, 4, p);
  BindOptionalDouble(open_warning_, 5, x_m);
  BindOptionalDouble(open_warning_, 6, y_m);
  sqlite3_bind_text(open_warning_, 7, edge.c_str(), -1, SQLITE_TRANSIENT);
  BindOptionalText(open_warning_, 8, object);
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

void ResultsDb::AddAction(double time_s, const ActionEvent& a) {
  sqlite3_stmt* s = action_;
  sqlite3_bind_int64(s, 1, run_id_);
  sqlite3_bind_double(s, 2, time_s);
  sqlite3_bind_text(s, 3, a.ego.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(s, 4, a.kind.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_double(s, 5, a.accel_mps2);
  sqlite3_bind_double(s, 6, a.speed_mps);
  sqlite3_bind_double(s, 7, a.p_collision);
  sqlite3_bind_double(s, 8, a.speed_after_mps);
  sqlite3_bind_text(s, 9, a.lane_before.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(s, 10, a.lane_after.c_str(), -1, SQLITE_TRANSIENT);
  if (a.route >= 0) {
    sqlite3_bind_int(s, 11, a.route);
    sqlite3_bind_double(s, 12, a.route_collision_probability);
    sqlite3_bind_double(s, 13, a.route_probability);
  } else {
    sqlite3_bind_null(s, 11);
    sqlite3_bind_null(s, 12);
    sqlite3_bind_null(s, 13);
  }
  sqlite3_bind_text(s, 14, a.detail.c_str(), -1, SQLITE_TRANSIENT);
  Step(s, "action");
}

void ResultsDb::AddCollision(double time_s, const SumoCollision& c, bool involves_ego) {
  sqlite3_stmt* s = collision_;
  sqlite3_bind_int64(s, 1, run_id_);
  sqlite3_bind_double(s, 2, time_s);
  sqlite3_bind_text(s, 3, c.collider.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(s, 4, c.victim.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(s, 5, c.collider_type.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(s, 6, c.victim_type.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(s, 7, c.type.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(s, 8, c.lane.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_double(s, 9, c.pos_m);
  BindOptionalDouble(s, 10, c.x_m);
  BindOptionalDouble(s, 11, c.y_m);
  sqlite3_bind_double(s, 12, c.collider_speed_mps);
  sqlite3_bind_double(s, 13, c.victim_speed_mps);
  sqlite3_bind_int(s, 14, involves_ego ? 1 : 0);
  Step(s, "collision");
  sqlite3_bind_int64(anticipation_, 1, sqlite3_last_insert_rowid(db_));
  Step(anticipation_, "collision anticipation");
}

void ResultsDb::AddEgoEvent(double time_s, const std::string& ego, const std::string& event,
                            const std::string& detail) {
  sqlite3_bind_int64(ego_event_, 1, run_id_);
  sqlite3_bind_double(ego_event_, 2, time_s);
  sqlite3_bind_text(ego_event_, 3, ego.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(ego_event_, 4, event.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(ego_event_, 5, detail.c_str(), -1, SQLITE_TRANSIENT);
  Step(ego_event_, "ego event");
}

void ResultsDb::AddEgo(double first_s, const std::string& ego, const std::string& vehicle_class,
                       const std::string& vehicle_type, double length_m, double width_m) {
  sqlite3_bind_int64(ego_, 1, run_id_);
  sqlite3_bind_text(ego_, 2, ego.c_str(), -1, SQLITE_TRANSIENT);
  BindOptionalText(ego_, 3, vehicle_class);
  BindOptionalText(ego_, 4, vehicle_type);
  BindOptionalDouble(ego_, 5, length_m);
  BindOptionalDouble(ego_, 6, width_m);
  sqlite3_bind_double(ego_, 7, first_s);
  Step(ego_, "ego");
}

void ResultsDb::AddWarningScene(long long warning, const std::string& ego, double time_s,
                                const std::string& scene) {
  sqlite3_bind_int64(warning_scene_, 1, warning);
  sqlite3_bind_int64(warning_scene_, 2, run_id_);
  sqlite3_bind_text(warning_scene_, 3, ego.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_double(warning_scene_, 4, time_s);
  sqlite3_bind_text(warning_scene_, 5, scene.c_str(), -1, SQLITE_TRANSIENT);
  Step(warning_scene_, "warning scene");
}

void ResultsDb::AddCriticalEvent(double time_s, const std::string& ego, const std::string& kind,
                                 const std::string& other, double value) {
  sqlite3_bind_int64(critical_event_, 1, run_id_);
  sqlite3_bind_double(critical_event_, 2, time_s);
  sqlite3_bind_text(critical_event_, 3, ego.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(critical_event_, 4, kind.c_str(), -1, SQLITE_TRANSIENT);
  BindOptionalText(critical_event_, 5, other);
  BindOptionalDouble(critical_event_, 6, value);
  Step(critical_event_, "critical event");
}

void ResultsDb::AddStepTime(const StepTimeRow& t) {
  sqlite3_stmt* s = step_time_;
  sqlite3_bind_int64(s, 1, run_id_);
  sqlite3_bind_double(s, 2, t.time_s);
  sqlite3_bind_int(s, 3, t.estimates);
  sqlite3_bind_int(s, 4, t.shortcut_estimates);
  sqlite3_bind_double(s, 5, t.sumo_ms);
  sqlite3_bind_double(s, 6, t.observe_ms);
  sqlite3_bind_double(s, 7, t.scenes_ms);
  sqlite3_bind_double(s, 8, t.estimate_ms);
  sqlite3_bind_double(s, 9, t.act_ms);
  sqlite3_bind_double(s, 10, t.record_ms);
  sqlite3_bind_double(s, 11, t.rss_mb);
  Step(s, "step time");
}

void ResultsDb::Commit() {
  const double now = UnixNow();
  if (now - last_heartbeat_ >= 1.0) {
    sqlite3_bind_double(heartbeat_, 1, now);
    sqlite3_bind_int64(heartbeat_, 2, run_id_);
    Step(heartbeat_, "heartbeat");
    last_heartbeat_ = now;
  }
  Exec("COMMIT");
  Exec("BEGIN");
}

void ResultsDb::EndRun(const std::string& status, const std::string& end_reason,
                       const std::string& error, const std::string& summary_json) {
  sqlite3_stmt* s = Prepare(
      "UPDATE runs SET ended_utc=?, status=?, end_reason=?, error=?, heartbeat_unix=?, summary=? "
      "WHERE id=?");
  const std::string now = UtcNow();
  sqlite3_bind_text(s, 1, now.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(s, 2, status.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(s, 3, end_reason.c_str(), -1, SQLITE_TRANSIENT);
  BindOptionalText(s, 4, error);
  sqlite3_bind_double(s, 5, UnixNow());
  sqlite3_bind_text(s, 6, summary_json.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_int64(s, 7, run_id_);
  const int rc = sqlite3_step(s);
  sqlite3_finalize(s);
  if (rc != SQLITE_DONE) Fail("run end");
  Exec("COMMIT");
  Exec("BEGIN");
}

}  // namespace criticality::plugin
