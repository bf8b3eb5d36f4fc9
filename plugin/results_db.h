#pragma once
// The run's SQLite file (schema in plugin/README.md). Everything is written inside a
// transaction that Commit() closes after each simulation step, so a killed run leaves a
// readable file holding every completed step.
#include <sqlite3.h>

#include <stdexcept>
#include <string>

namespace criticality::plugin {

/** Any failure to write results (disk full, unwritable path, existing file). */
class ResultsError : public std::runtime_error {
 public:
  explicit ResultsError(const std::string& what) : std::runtime_error(what) {}
};

struct CollisionRow {
  double time_s{0.0};
  std::string collider, victim, collider_type, victim_type, type, lane;
  double collider_speed_mps{0.0}, victim_speed_mps{0.0}, pos_m{0.0};
};

class ResultsDb {
 public:
  /** Creates `path`; refuses an existing file so that no earlier results are lost. */
  explicit ResultsDb(const std::string& path);
  ~ResultsDb();
  ResultsDb(const ResultsDb&) = delete;
  ResultsDb& operator=(const ResultsDb&) = delete;

  void BeginRun(const std::string& options, const std::string& sumo_version,
                const std::string& egos);
  void AddStep(double time_s, const std::string& ego, double p_collision, double estimator_ms,
               int objects, double speed_mps, bool acting);
  /** Opens a warning episode; returns its row id. */
  long long OpenWarning(const std::string& ego, double start_s, double p_collision);
  void UpdateWarningPeak(long long id, double peak);
  void CloseWarning(long long id, double end_s);
  void AddAction(double time_s, const std::string& ego, const std::string& kind, double accel_mps2,
                 double speed_mps, double p_collision);
  /** Records a collision and its anticipation time (collision time minus the start of the
   *  latest warning episode of the collider or victim that began at or before it). */
  void AddCollision(const CollisionRow& c);
  /** Commits what was written since the last commit and opens the next transaction. */
  void Commit();
  /** Final status ("completed", "failed: ...") and end time; commits. */
  void EndRun(const std::string& status);
  const std::string& path() const { return path_; }

 private:
  void Exec(const std::string& sql);
  sqlite3_stmt* Prepare(const char* sql);
  void Step(sqlite3_stmt* s, const char* what);
  [[noreturn]] void Fail(const std::string& what);

  std::string path_;
  sqlite3* db_{nullptr};
  long long run_id_{0};
  sqlite3_stmt* step_{nullptr};
  sqlite3_stmt* open_warning_{nullptr};
  sqlite3_stmt* peak_warning_{nullptr};
  sqlite3_stmt* close_warning_{nullptr};
  sqlite3_stmt* action_{nullptr};
  sqlite3_stmt* collision_{nullptr};
};

}  // namespace criticality::plugin
