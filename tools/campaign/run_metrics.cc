#include "tools/campaign/run_metrics.h"

#include <algorithm>
#include <set>

#include "plugin/record/result_views.h"

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

// The set being filled, with each run's position in it by run index.
struct Loader {
  SqliteDb& db;
  RunMetricsSet& set;
  std::map<std::size_t, std::size_t> at;

  // Calls fn(run, statement) for each row of `sql` whose first column is a known run index.
  template <typename Fn>
  void Each(const std::string& sql, Fn&& fn) {
    Statement s = db.Prepare(sql);
    while (s.Step()) {
      const auto it = at.find(static_cast<std::size_t>(s.Int(0)));
      if (it != at.end()) fn(set.runs[it->second], s);
    }
  }
};

void LoadRuns(Loader& l) {
  Statement s = l.db.Prepare(
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
    l.at[m.run_index] = l.set.runs.size();
    l.set.runs.push_back(std::move(m));
  }
  l.Each("SELECT run_index, name, value FROM plan_params",
         [](RunMetrics& m, Statement& p) { m.params[p.Text(1)] = p.Text(2); });
}

void LoadSteps(Loader& l) {
  MetricsAvailability& av = l.set.available;
  av.steps = Has(l.db, "steps", {"run_index"});
  av.estimator_ms = Has(l.db, "steps", {"run_index", "estimator_ms"});
  if (av.estimator_ms) {
    l.Each(
        "SELECT run_index, count(*), sum(estimator_ms), max(estimator_ms) FROM steps GROUP BY "
        "run_index",
        [](RunMetrics& m, Statement& s) {
          m.steps = s.Int(1);
          m.estimator_ms_sum = s.Real(2);
          m.estimator_ms_max = s.OptReal(3);
        });
  } else if (av.steps) {
    l.Each("SELECT run_index, count(*) FROM steps GROUP BY run_index",
           [](RunMetrics& m, Statement& s) { m.steps = s.Int(1); });
    l.set.notes.push_back("estimator time: the steps table has no estimator_ms column");
  } else {
    l.set.notes.push_back("steps and estimator time: no run has a steps table (no results?)");
  }
}

// Anticipation is the stored collisions.anticipation_s: the driver fills it when it records the
// collision, by the rule of the view collision_anticipation (plugin/record/result_views.sql),
// which gives the same value on the finished file. The column is also in run files whose runs
// table has no step_length_s, which the view needs.
void LoadEgoCollisions(Loader& l) {
  MetricsAvailability& av = l.set.available;
  const std::string ego = EgoCollisionCondition(l.db);
  av.anticipation = Has(l.db, "collisions", {"anticipation_s"});
  l.Each("SELECT c.run_index, count(*) FROM collisions c WHERE " + ego + " GROUP BY c.run_index",
         [](RunMetrics& m, Statement& s) { m.ego_collisions = s.Int(1); });
  if (MakeRunEgosTable(l.db)) {
    l.Each(
        "SELECT DISTINCT c.run_index, e.ego FROM collisions c JOIN _run_egos e ON "
        "e.run_index = c.run_index AND e.ego IN (c.collider, c.victim)",
        [](RunMetrics& m, Statement& s) { m.collided_egos.push_back(s.Text(1)); });
  }
  if (!av.anticipation) {
    l.set.notes.push_back("anticipation time: the collisions table has no anticipation_s column");
    return;
  }
  l.Each("SELECT c.run_index, c.anticipation_s FROM collisions c WHERE " + ego +
             " AND c.anticipation_s IS NOT NULL ORDER BY c.run_index, c.time_s",
         [](RunMetrics& m, Statement& s) {
           ++m.warned_collisions;
           m.anticipation_s.push_back(s.Real(1));
         });
}

void LoadCollisions(Loader& l) {
  MetricsAvailability& av = l.set.available;
  av.collisions = Has(l.db, "collisions", {"run_index"});
  if (!av.collisions) {
    l.set.notes.push_back("collisions: no run has a collisions table");
    return;
  }
  l.Each("SELECT run_index, count(*) FROM collisions GROUP BY run_index",
         [](RunMetrics& m, Statement& s) { m.collisions = s.Int(1); });
  const bool roles = Has(l.db, "collisions", {"collider", "victim"});
  const bool flagged = Has(l.db, "collisions", {"involves_ego"});
  av.ego_collisions = flagged || (roles && MakeRunEgosTable(l.db));
  if (av.ego_collisions) {
    LoadEgoCollisions(l);
  } else {
    l.set.notes.push_back(
        "ego collisions: the collisions table has neither involves_ego nor collider/victim with "
        "a steps table to tell egos");
  }
}

// The result views over this database as TEMP views, with the report's grace. A table the run
// files lack (no collisions at all, no critical_events from an older driver) is replaced by an
// empty one: nothing of it follows a warning. Steps without main_object (older drivers only)
// credit a collision's anticipation from the episode's start.
void CreateResultViews(SqliteDb& db, double grace_s, bool collisions_ok, bool events_ok) {
  plugin::ResultViewKeys keys = plugin::ResultViewKeys::Campaign(grace_s);
  keys.attributed = Has(db, "steps", {"run_index", "ego", "time_s", "main_object"});
  if (!Has(db, "steps", {"run_index", "ego", "time_s"})) {
    db.Exec("CREATE TEMP TABLE IF NOT EXISTS _no_steps(run_index, time_s, ego, main_object)");
    keys.steps = "temp._no_steps";
  }
  if (!collisions_ok) {
    db.Exec("CREATE TEMP TABLE IF NOT EXISTS _no_collisions(run_index, time_s, collider, victim)");
    keys.collisions = "temp._no_collisions";
  }
  if (!events_ok) {
    db.Exec("CREATE TEMP TABLE IF NOT EXISTS _no_critical_events(run_index, time_s, ego, kind)");
    keys.critical_events = "temp._no_critical_events";
  }
  db.Exec(plugin::DropResultViewsSql(keys) + plugin::ResultViewsSql(keys));
}

void LoadWarnings(Loader& l, double grace_s) {
  MetricsAvailability& av = l.set.available;
  av.warnings = Has(l.db, "warnings", {"run_index"});
  if (!av.warnings) {
    l.set.notes.push_back("warnings: no run has a warnings table");
    return;
  }
  l.Each("SELECT run_index, count(*) FROM warnings GROUP BY run_index",
         [](RunMetrics& m, Statement& s) { m.warnings = s.Int(1); });
  const bool warnings_ok = Has(l.db, "warnings", {"ego", "start_s", "end_s"});
  const bool collisions_ok = Has(l.db, "collisions", {"run_index", "time_s", "collider", "victim"});
  const bool events_ok = Has(l.db, "critical_events", {"run_index", "time_s", "ego", "kind"});
  av.false_alarms = warnings_ok && (collisions_ok || !av.collisions);
  if (!av.false_alarms) {
    l.set.notes.push_back(
        "false alarms: warnings need ego, start_s, end_s and collisions time_s, collider, "
        "victim");
    return;
  }
  // A false alarm: an episode that nothing followed (plugin/record/result_views.sql).
  CreateResultViews(l.db, grace_s, collisions_ok, events_ok);
  l.Each(
      "SELECT run_index, ego FROM temp.warning_outcomes WHERE outcome IS NULL "
      "ORDER BY run_index, start_s",
      [](RunMetrics& m, Statement& s) {
        ++m.false_alarms;
        m.false_alarm_egos.push_back(s.Text(1));
      });
}

// Exposure per run and ego: estimates x step length, speed x step length; each ego's class
// (egos table: the vClass of its first entry); the ego of each warning and ego collision, for
// rates per vehicle class.
void LoadExposure(Loader& l) {
  MetricsAvailability& av = l.set.available;
  av.vehicle_hours =
      Has(l.db, "runs", {"run_index", "step_length_s"}) && Has(l.db, "steps", {"run_index", "ego"});
  av.vehicle_km = av.vehicle_hours && Has(l.db, "steps", {"speed_mps"});
  av.vehicle_class = Has(l.db, "egos", {"run_index", "ego", "vehicle_class"});
  if (!av.vehicle_hours) {
    l.set.notes.push_back(
        "exposure (vehicle-hours, vehicle-km) and rates: the run files have no runs.step_length_s "
        "(a driver older than the exposure columns)");
  } else {
    const std::string km = av.vehicle_km ? "sum(s.speed_mps) * r.dt / 1000.0" : "0";
    l.Each("SELECT s.run_index, s.ego, count(*) * r.dt / 3600.0, " + km +
               " FROM steps s JOIN (SELECT run_index, max(step_length_s) AS dt FROM runs GROUP "
               "BY run_index) r USING(run_index) GROUP BY s.run_index, s.ego",
           [](RunMetrics& m, Statement& s) {
             RunMetrics::EgoExposure& e = m.ego_exposure[s.Text(1)];
             e.hours = s.Real(2);
             e.km = s.Real(3);
             m.vehicle_hours += e.hours;
             m.vehicle_km += e.km;
           });
    if (!av.vehicle_km) l.set.notes.push_back("vehicle-km: the steps table has no speed_mps");
  }
  if (av.vehicle_class) {
    l.Each("SELECT run_index, ego, vehicle_class FROM egos ORDER BY run_index, first_s DESC",
           [](RunMetrics& m, Statement& s) { m.ego_class[s.Text(1)] = s.Text(2); });
  } else {
    l.set.notes.push_back(
        "rates per vehicle class: the run files have no egos table (a driver older than it)");
  }
  if (l.set.available.warnings && Has(l.db, "warnings", {"ego"})) {
    l.Each("SELECT run_index, ego FROM warnings ORDER BY run_index, start_s",
           [](RunMetrics& m, Statement& s) { m.warning_egos.push_back(s.Text(1)); });
  }
  if (l.set.available.ego_collisions && MakeRunEgosTable(l.db)) {
    l.Each(
        "SELECT c.run_index, e.ego FROM collisions c JOIN _run_egos e ON e.run_index = "
        "c.run_index AND e.ego IN (c.collider, c.victim) ORDER BY c.run_index, c.time_s",
        [](RunMetrics& m, Statement& s) { m.collision_egos.push_back(s.Text(1)); });
  }
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
  Loader l{db, set, {}};
  LoadRuns(l);
  LoadSteps(l);
  LoadCollisions(l);
  LoadWarnings(l, grace_s);
  LoadExposure(l);
  return set;
}

}  // namespace criticality::campaign
