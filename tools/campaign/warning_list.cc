#include "tools/campaign/warning_list.h"

#include <algorithm>

namespace criticality::campaign {
namespace {

bool Has(SqliteDb& db, const std::string& table, std::initializer_list<const char*> cols,
         const std::string& schema = "main") {
  const std::vector<std::string> have = db.Columns(table, schema);
  if (have.empty()) return false;
  for (const char* c : cols) {
    if (std::find(have.begin(), have.end(), c) == have.end()) return false;
  }
  return true;
}

}  // namespace

Table WarningList(SqliteDb& db, const RunMetricsSet& metrics,
                  const std::map<std::size_t, std::string>& setting,
                  const std::map<std::size_t, std::set<std::string>>& twin_collided,
                  std::vector<std::string>& notes) {
  Table t;
  t.columns = {"run_index", "scenario",   "parameters", "ego",  "vehicle_class",
               "start_s",   "end_s",      "peak_p",     "edge", "object",
               "outcome",   "warning_id", "scene"};
  // The view exists when LoadRunMetrics could judge the warnings.
  if (!metrics.available.false_alarms || db.Columns("warning_outcomes", "temp").empty()) return t;
  std::map<std::size_t, const RunMetrics*> ok;
  for (const RunMetrics& m : metrics.runs) {
    if (m.ok) ok[m.run_index] = &m;
  }
  const bool id = Has(db, "warnings", {"id"});
  const bool scenes = id && Has(db, "warning_scenes", {"run_index", "warning_id"});
  const bool place = Has(db, "warnings", {"edge"});
  const bool object = Has(db, "warnings", {"object"});
  const bool peak = Has(db, "warnings", {"peak_p"});
  if (!scenes)
    notes.push_back(
        "warning scenes: the run files keep no warning_scenes (a driver older than it)");
  // warning_outcomes has no id: its rows join the warnings by run, ego and start.
  Statement s = db.Prepare(
      std::string("SELECT o.run_index, o.ego, o.start_s, o.end_s, o.outcome, ") +
      (peak ? "w.peak_p" : "NULL") + ", " + (place ? "w.edge" : "NULL") + ", " +
      (object ? "w.object" : "NULL") + ", " + (id ? "w.id" : "NULL") + ", " +
      (scenes ? "EXISTS (SELECT 1 FROM warning_scenes s WHERE s.run_index = o.run_index AND "
                "s.warning_id = w.id)"
              : "0") +
      " FROM temp.warning_outcomes o JOIN warnings w ON w.run_index = o.run_index AND w.ego = "
      "o.ego AND w.start_s = o.start_s ORDER BY o.run_index, o.start_s, o.ego");
  while (s.Step()) {
    const auto run = ok.find(static_cast<std::size_t>(s.Int(0)));
    if (run == ok.end()) continue;
    const RunMetrics& m = *run->second;
    const std::string ego = s.Text(1);
    std::string outcome = s.IsNull(4) ? "false alarm" : s.Text(4);
    const auto twin = twin_collided.find(m.run_index);
    if (outcome == "false alarm" && twin != twin_collided.end() && twin->second.count(ego))
      outcome = "avoided";
    const auto cls = m.ego_class.find(ego);
    const auto set = setting.find(m.run_index);
    t.rows.push_back({Cell(static_cast<long long>(m.run_index)), m.scenario,
                      set == setting.end() ? "-" : set->second, ego,
                      cls == m.ego_class.end() ? "" : cls->second, Cell(s.Real(2), 2),
                      s.IsNull(3) ? "" : Cell(s.Real(3), 2), s.IsNull(5) ? "" : Cell(s.Real(5), 3),
                      s.IsNull(6) ? "" : s.Text(6), s.IsNull(7) ? "" : s.Text(7), outcome,
                      s.IsNull(8) ? "" : Cell(s.Int(8)), s.Int(9) ? "yes" : "no"});
  }
  return t;
}

}  // namespace criticality::campaign
