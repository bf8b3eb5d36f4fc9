#pragma once
// The run's SQLite file (schema in plugin/README.md). WAL journal and a busy timeout: readers
// (sqlite3, pandas, a dashboard polling while the run goes on) never block the run and the run
// never blocks them. Everything is written inside a transaction that Commit() closes after each
// simulation step, so a killed run leaves a readable file holding every completed step; its
// heartbeat (runs.heartbeat_unix) then stops.
#include <sqlite3.h>

#include <stdexcept>
#include <string>

#include "plugin/act/act_outcome.h"
#include "plugin/sumo/sumo_reports.h"

namespace criticality::plugin {

/** Any failure to write results (disk full, unwritable path, existing file). */
class ResultsError : public std::runtime_error {
 public:
  explicit ResultsError(const std::string& what) : std::runtime_error(what) {}
};

/** Throws ResultsError unless a run could create `path`: it must not exist, and its folder
 *  must exist and be writable (what ResultsDb checks first; --check-options checks it too). */
void CheckOutputCreatable(const std::string& path);

/** Where the time of one step went (milliseconds of wall time). */
struct StepTimeRow {
  double time_s{0.0};
  int estimates{0};
  int shortcut_estimates{0};
  double sumo_ms{0.0}, observe_ms{0.0}, scenes_ms{0.0}, estimate_ms{0.0}, act_ms{0.0},
      record_ms{0.0};
  double rss_mb{0.0};  ///< the process's resident memory (sampled every few seconds)
};

class ResultsDb {
 public:
  /** Creates `path`; refuses an existing file so that no earlier results are lost. */
  explicit ResultsDb(const std::string& path);
  ~ResultsDb();
  ResultsDb(const ResultsDb&) = delete;
  ResultsDb& operator=(const ResultsDb&) = delete;

  void BeginRun(const std::string& options, const std::string& sumo_version,
                const std::string& egos, double step_length_s);
  /** The scenario's metadata (--expect, --expect-partner, --quiet-until, --category), recorded
   *  for evaluations; empty strings are stored as NULL. */
  void SetScenario(const std::string& expect, const std::string& expect_partner,
                   double quiet_until_s, const std::string& category);
  /** The ego's row of the step at time_s. */
  void AddStep(double time_s, const EgoStep& s);
  /** Opens a warning episode where the ego is; `object`: the object with the largest share of
   *  p_collision at the opening ("" stored as NULL). Returns its row id. */
  long long OpenWarning(const std::string& ego, double start_s, double p_collision, double x_m,
                        double y_m, const std::string& edge, const std::string& object = "");
  void UpdateWarningPeak(long long id, double peak);
  void CloseWarning(long long id, double end_s);
  void AddAction(double time_s, const ActionEvent& a);
  /** Records a collision and its anticipation time as the view collision_anticipation
   *  defines it (result_views.sql): collision time minus the start of the latest warning
   *  episode of the collider or victim that began before it and was still open at it, or ended
   *  at most one step before it; NULL when there is none. Record a step's collisions before its
   *  warnings (an episode that opens at the impact does not anticipate it). */
  void AddCollision(double time_s, const SumoCollision& c, bool involves_ego);
  void AddEgoEvent(double time_s, const std::string& ego, const std::string& event,
                   const std::string& detail);
  /** An ego, once, when it is first estimated: its SUMO vClass and vType ("" stored as NULL)
   *  and size, for breakdowns by class. */
  void AddEgo(double first_s, const std::string& ego, const std::string& vehicle_class,
              const std::string& vehicle_type, double length_m, double width_m);
  /** The scene (a scene file's text, criticality/scene_io.h) of warning row `warning` at its
   *  start, to show and replay the situation behind it. */
  void AddWarningScene(long long warning, const std::string& ego, double time_s,
                       const std::string& scene);
  /** An overlap or a hard braking of an ego (plugin/observe/critical_events.h); `other` "" is NULL. */
  void AddCriticalEvent(double time_s, const std::string& ego, const std::string& kind,
                        const std::string& other, double value);
  void AddStepTime(const StepTimeRow& t);
  /** Commits what was written since the last commit, refreshes the heartbeat (at most once a
   *  second) and opens the next transaction. */
  void Commit();
  /** Final status (completed, interrupted, failed), why the run ended, the error (empty: none)
   *  and the JSON summary; commits. The file stays in WAL mode (switching back would lock out
   *  the readers of that moment); closing it folds the WAL into the file. */
  void EndRun(const std::string& status, const std::string& end_reason, const std::string& error,
              const std::string& summary_json);
  /** Closes and deletes the file: a run that failed before its first step leaves nothing. */
  void Discard();
  const std::string& path() const { return path_; }

 private:
  void Exec(const std::string& sql);
  sqlite3_stmt* Prepare(const char* sql);
  void Step(sqlite3_stmt* s, const char* what);
  [[noreturn]] void Fail(const std::string& what);
  void Close();

  std::string path_;
  sqlite3* db_{nullptr};
  long long run_id_{0};
  double last_heartbeat_{0.0};
  sqlite3_stmt* step_{nullptr};
  sqlite3_stmt* open_warning_{nullptr};
  sqlite3_stmt* critical_event_{nullptr};
  sqlite3_stmt* peak_warning_{nullptr};
  sqlite3_stmt* close_warning_{nullptr};
  sqlite3_stmt* action_{nullptr};
  sqlite3_stmt* collision_{nullptr};
  sqlite3_stmt* anticipation_{nullptr};
  sqlite3_stmt* ego_event_{nullptr};
  sqlite3_stmt* ego_{nullptr};
  sqlite3_stmt* warning_scene_{nullptr};
  sqlite3_stmt* step_time_{nullptr};
  sqlite3_stmt* heartbeat_{nullptr};
};

}  // namespace criticality::plugin
