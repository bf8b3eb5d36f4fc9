#include "tools/campaign/run_metrics.h"

#include <algorithm>
#include <set>

namespace criticality::campaign {
namespace {

bool Has(SqliteDb& db, const std::string& table, std::initializer_list<const char*> cols) {
  const std::vector<std::string> have = db.Columns(table);
  if (have.empty()) return false;
  for (const char* c : cols) {
    if (std::find(have.begin(), have.end(), c) == have.end()) return false;
  }
  return true;
}

}  // namespace

bool MakeRunEgosTable(SqliteDb& db) {
  if (!Has(db, "steps", {"run_index", "ego"})) return false;
  if (db.HasTable("_run_egos", "temp")) return true;
  db.Exec(
      "CREATE TEMP TABLE _run_egos AS SELECT DISTINCT run_index, ego FROM steps;"
      "CREATE INDEX temp._run_egos_idx ON _run_egos(run_index, ego);");
  return true;
}

std::string EgoCollisionCondition(SqliteDb& db) {
  if (Has(db, "collisions", {"involves_ego"})) return "c.involves_ego = 1";
  return "EXISTS (SELECT 1 FROM _run_egos e WHERE e.run_index = c.run_index AND "
         "e.ego IN (c.collider, c.victim))";
}

RunMetricsSet LoadRunMetrics(SqliteDb& db, double grace_s) {
  RunMetricsSet set;
  MetricsAvailability& av = set.available;
  std::map<std::size_t, std::size_t> at;  // run index -> position in set.runs
  {
    Statement s = db.Prepare(
        "SELECT run_index, scenario, label, status, COALESCE(wall_s, 0) FROM campaign_runs "
        "ORDER BY run_index");
    while (s.Step()) {
      RunMetrics m;
      m.run_index = static_cast<std::size_t>(s.Int(0));
      m.scenario = s.Text(1);
      m.label = s.Text(2);
      m.status = s.Text(3);
      m.ok = m.status == "ok";
      m.wall_s = s.Real(4);
      at[m.run_index] = set.runs.size();
      set.runs.push_back(std::move(m));
    }
  }
  {
    Statement s = db.Prepare("SELECT run_index, name, value FROM plan_params");
    while (s.Step()) {
      const auto it = at.find(static_cast<std::size_t>(s.Int(0)));
      if (it != at.end()) set.runs[it->second].params[s.Text(1)] = s.Text(2);
    }
  }
  auto each = [&](const std::string& sql, auto&& fn) {
    Statement s = db.Prepare(sql);
    while (s.Step()) {
      const auto it = at.find(static_cast<std::size_t>(s.Int(0)));
      if (it != at.end()) fn(set.runs[it->second], s);
    }
  };

  av.steps = Has(db, "steps", {"run_index"});
  av.estimator_ms = Has(db, "steps", {"run_index", "estimator_ms"});
  if (av.estimator_ms) {
    each(
        "SELECT run_index, count(*), sum(estimator_ms), max(estimator_ms) FROM steps GROUP BY "
        "run_index",
        [](RunMetrics& m, Statement& s) {
          m.steps = s.Int(1);
          m.estimator_ms_sum = s.Real(2);
          m.estimator_ms_max = s.OptReal(3);
        });
  } else if (av.steps) {
    each("SELECT run_index, count(*) FROM steps GROUP BY run_index",
         [](RunMetrics& m, Statement& s) { m.steps = s.Int(1); });
    set.notes.push_back("estimator time: the steps table has no estimator_ms column");
  } else {
    set.notes.push_back("steps and estimator time: no run has a steps table (no results?)");
  }

  av.collisions = Has(db, "collisions", {"run_index"});
  if (av.collisions) {
    each("SELECT run_index, count(*) FROM collisions GROUP BY run_index",
         [](RunMetrics& m, Statement& s) { m.collisions = s.Int(1); });
    const bool roles = Has(db, "collisions", {"collider", "victim"});
    const bool flagged = Has(db, "collisions", {"involves_ego"});
    av.ego_collisions = flagged || (roles && MakeRunEgosTable(db));
    if (av.ego_collisions) {
      const std::string ego = EgoCollisionCondition(db);
      av.anticipation = Has(db, "collisions", {"anticipation_s"});
      each("SELECT c.run_index, count(*) FROM collisions c WHERE " + ego + " GROUP BY c.run_index",
           [](RunMetrics& m, Statement& s) { m.ego_collisions = s.Int(1); });
      if (MakeRunEgosTable(db)) {
        each(
            "SELECT DISTINCT c.run_index, e.ego FROM collisions c JOIN _run_egos e ON "
            "e.run_index = c.run_index AND e.ego IN (c.collider, c.victim)",
            [](RunMetrics& m, Statement& s) { m.collided_egos.push_back(s.Text(1)); });
      }
      if (av.anticipation) {
        each("SELECT c.run_index, c.anticipation_s FROM collisions c WHERE " + ego +
                 " AND c.anticipation_s IS NOT NULL ORDER BY c.run_index, c.time_s",
             [](RunMetrics& m, Statement& s) {
               ++m.warned_collisions;
               m.anticipation_s.push_back(s.Real(1));
             });
      } else {
        set.notes.push_back("anticipation time: the collisions table has no anticipation_s column");
      }
    } else {
      set.notes.push_back(
          "ego collisions: the collisions table has neither involves_ego nor collider/victim with "
          "a steps table to tell egos");
    }
  } else {
    set.notes.push_back("collisions: no run has a collisions table");
  }

  av.warnings = Has(db, "warnings", {"run_index"});
  if (av.warnings) {
    each("SELECT run_index, count(*) FROM warnings GROUP BY run_index",
         [](RunMetrics& m, Statement& s) { m.warnings = s.Int(1); });
    // A warning is a false alarm unless its ego collided, or (driver run files with a
    // critical_events table) its body overlapped another or it braked hard, from the warning's
    // start until grace_s after its end.
    const bool warnings_ok = Has(db, "warnings", {"ego", "start_s", "end_s"});
    const bool collisions_ok = Has(db, "collisions", {"run_index", "time_s", "collider", "victim"});
    const bool events_ok = Has(db, "critical_events", {"run_index", "time_s", "ego"});
    av.false_alarms = warnings_ok && (collisions_ok || !av.collisions);
    if (av.false_alarms) {
      std::string sql = "SELECT w.run_index, w.ego FROM warnings w WHERE 1";
      auto window = [](const std::string& a) {
        return a + ".time_s >= w.start_s AND " + a + ".time_s <= COALESCE(w.end_s, 1e300) + ?";
      };
      int binds = 0;
      if (collisions_ok) {
        sql += " AND NOT EXISTS (SELECT 1 FROM collisions c WHERE c.run_index = w.run_index AND "
               "w.ego IN (c.collider, c.victim) AND " + window("c") + ")";
        ++binds;
      }
      if (events_ok) {
        sql += " AND NOT EXISTS (SELECT 1 FROM critical_events e WHERE e.run_index = w.run_index "
               "AND e.ego = w.ego AND " + window("e") + ")";
        ++binds;
      }
      Statement s = db.Prepare(sql + " ORDER BY w.run_index, w.start_s");
      for (int b = 1; b <= binds; ++b) s.Bind(b, grace_s);
      while (s.Step()) {
        const auto it = at.find(static_cast<std::size_t>(s.Int(0)));
        if (it == at.end()) continue;
        ++set.runs[it->second].false_alarms;
        set.runs[it->second].false_alarm_egos.push_back(s.Text(1));
      }
    } else {
      set.notes.push_back(
          "false alarms: warnings need ego, start_s, end_s and collisions time_s, collider, "
          "victim");
    }
  } else {
    set.notes.push_back("warnings: no run has a warnings table");
  }
  return set;
}

}  // namespace criticality::campaign
