#pragma once
// The SQL views that define what followed a warning episode (a false alarm when nothing did)
// and a collision's anticipation, once (result_views.sql, embedded at build time), with their
// placeholders filled in: for the driver's run files, a merged campaign.sqlite, or episodes put
// into a table of their own. Only text: no SQLite, no SUMO.
#include <string>

namespace criticality::plugin {

/** What the views read and how they are stored (result_views.sql lists the placeholders). */
struct ResultViewKeys {
  /** The evaluation's grace: what follows within 2 s of an episode's end still counts. */
  static constexpr double kDefaultGraceS = 2.0;

  std::string schema{"main"};        ///< "main": views kept in the file; "temp": this connection's
  std::string run_key{"run_id"};     ///< the run column of warnings, collisions, critical_events
  std::string runs_key{"id"};        ///< the column of `runs` that run_key refers to
  std::string warnings{"warnings"};  ///< the episodes judged (a table or view)
  std::string collisions{"collisions"};
  std::string critical_events{"critical_events"};
  std::string runs{"runs"};
  std::string steps{"steps"};
  /** The steps name each step's main object (column main_object): a collision's anticipation
   *  counts from the first step at which its partner was it. false: from the episode's start
   *  (run files of drivers before the column). */
  bool attributed{true};
  double grace_s{kDefaultGraceS};

  /** A driver run file: run_id, views stored in the file, the default grace. */
  static ResultViewKeys RunFile();
  /** A merged campaign.sqlite (run_index), views of this connection only. */
  static ResultViewKeys Campaign(double grace_s);
};

/** The views' definitions as they are written (with placeholders). */
const std::string& ResultViewsTemplate();

/** CREATE VIEW statements for warning_windows, warning_outcomes, critical_event_warnings,
 *  collision_warnings and collision_anticipation. Throws std::invalid_argument for a name that is not a plain SQL
 *  identifier (letters, digits, '_', '.') or a grace that is not finite. */
std::string ResultViewsSql(const ResultViewKeys& keys);

/** DROP VIEW IF EXISTS statements for the same views (in keys.schema). */
std::string DropResultViewsSql(const ResultViewKeys& keys);

/** `value` as an SQL literal that SQLite reads back as exactly the same double: the shortest
 *  decimal (with a decimal point) when it has at most 15 significant digits, else an exact
 *  quotient of two integers. Throws std::invalid_argument when not finite. */
std::string SqlRealLiteral(double value);

}  // namespace criticality::plugin
