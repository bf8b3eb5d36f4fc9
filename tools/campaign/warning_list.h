#pragma once
// Every warning episode of the successful runs, with what followed it (the view
// warning_outcomes of plugin/record/result_views.sql, made by LoadRunMetrics) and whether the
// run file kept its scene (table warning_scenes): the report's warning table, and the list the
// figure script draws the warning scenes from.
#include <map>
#include <set>
#include <string>
#include <vector>

#include "tools/campaign/run_metrics.h"
#include "tools/campaign/sqlite_db.h"
#include "tools/campaign/table_writer.h"

namespace criticality::campaign {

/** warnings.csv: run_index, scenario, parameters, ego, vehicle_class, start_s, end_s, peak_p,
 *  edge, object, outcome (false alarm, collision, overlap, pass-through, hard-braking,
 *  avoided: an act=brake run's warning of an ego that collided in its act=warn twin),
 *  warning_id, scene (yes/no).
 *  `setting`: each run's grouping parameters; `twin_collided`: per act=brake run, those egos.
 *  Needs the TEMP view warning_outcomes on `db`; empty with a note when it is missing. */
Table WarningList(SqliteDb& db, const RunMetricsSet& metrics,
                  const std::map<std::size_t, std::string>& setting,
                  const std::map<std::size_t, std::set<std::string>>& twin_collided,
                  std::vector<std::string>& notes);

}  // namespace criticality::campaign
