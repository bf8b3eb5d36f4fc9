#include "tools/campaign/rate_tables.h"

#include <algorithm>

#include "tools/campaign/rates.h"

namespace criticality::campaign {
namespace {

const std::set<std::string> kNone;

const std::set<std::string>& NotFalse(const RateInputs& in, std::size_t run) {
  const auto it = in.twin_collided.find(run);
  return it == in.twin_collided.end() ? kNone : it->second;
}

// A run's totals: false alarms as the braking comparison counts them.
RunEvents Totals(const RateInputs& in, const RunMetrics& m) {
  RunEvents e;
  e.hours = m.vehicle_hours;
  e.km = m.vehicle_km;
  e.warnings = static_cast<double>(m.warnings);
  const auto fa = in.false_alarms.find(m.run_index);
  e.false_alarms = static_cast<double>(fa == in.false_alarms.end() ? m.false_alarms : fa->second);
  e.ego_collisions = static_cast<double>(m.ego_collisions);
  e.egos = static_cast<long long>(m.ego_exposure.size());
  return e;
}

struct Measure {
  const char* name;
  double RunEvents::*count;
  bool MetricsAvailability::*available;
};
const Measure kMeasures[] = {
    {"warnings", &RunEvents::warnings, &MetricsAvailability::warnings},
    {"false alarms", &RunEvents::false_alarms, &MetricsAvailability::false_alarms},
    {"ego collisions", &RunEvents::ego_collisions, &MetricsAvailability::ego_collisions}};

// The rows of one group: one per measure, each with both rates and their intervals.
void AddRateRows(const RateInputs& in, const std::vector<std::string>& group,
                 const std::vector<RunEvents>& runs, Table& t) {
  const MetricsAvailability& av = in.metrics.available;
  double hours = 0.0, km = 0.0;
  for (const RunEvents& r : runs) {
    hours += r.hours;
    km += r.km;
  }
  for (const Measure& m : kMeasures) {
    if (!(av.*m.available)) continue;
    std::vector<RateSample> per_h, per_km;
    for (const RunEvents& r : runs) {
      per_h.push_back({r.*m.count, r.hours});
      per_km.push_back({r.*m.count, r.km / 1e6});  // per million km: exposure in 10^6 km
    }
    const Rate h = RateOf(per_h);
    const Rate k = av.vehicle_km ? RateOf(per_km) : Rate{};
    std::vector<std::string> row = group;
    row.insert(
        row.end(),
        {m.name, Cell(static_cast<long long>(h.events)), Cell(static_cast<long long>(runs.size())),
         SigCell(hours, 4), av.vehicle_km ? SigCell(km, 4) : "", SigCell(h.value), SigCell(h.low),
         SigCell(h.high), SigCell(k.value), SigCell(k.low), SigCell(k.high), h.interval});
    t.rows.push_back(std::move(row));
  }
}

std::string Param(const RunMetrics& m, const std::string& name) {
  const auto it = m.params.find(name);
  return it == m.params.end() ? "" : it->second;
}

// Per scenario and setting (the grouping parameters), in plan order.
void ScenarioRows(const RateInputs& in, Table& t) {
  std::map<std::vector<std::size_t>, std::pair<std::vector<std::string>, std::vector<RunEvents>>>
      groups;
  for (const RunMetrics& m : in.metrics.runs) {
    if (!m.ok) continue;
    const auto pos = in.scenario_order.find(m.scenario);
    std::vector<std::size_t> key{pos == in.scenario_order.end() ? 9999 : pos->second};
    std::string label;
    for (const RateAxis& a : in.axes) {
      const std::string v = Param(m, a.name);
      key.push_back(static_cast<std::size_t>(std::find(a.values.begin(), a.values.end(), v) -
                                             a.values.begin()));
      label += (label.empty() ? "" : " ") + a.name + "=" + v;
    }
    auto& g = groups[key];
    if (g.first.empty()) g.first = {"scenario", m.scenario, label.empty() ? "-" : label, "(all)"};
    g.second.push_back(Totals(in, m));
  }
  for (const auto& [key, g] : groups) AddRateRows(in, g.first, g.second, t);
}

// Per value of each grouping parameter: over every scenario, then per scenario (plan order).
void ParameterRows(const RateInputs& in, Table& t) {
  for (const RateAxis& a : in.axes) {
    for (const std::string& v : a.values) {
      std::vector<RunEvents> runs;
      std::map<std::size_t, std::pair<std::string, std::vector<RunEvents>>> per;
      for (const RunMetrics& m : in.metrics.runs) {
        if (!m.ok || Param(m, a.name) != v) continue;
        runs.push_back(Totals(in, m));
        const auto pos = in.scenario_order.find(m.scenario);
        auto& p = per[pos == in.scenario_order.end() ? 9999 : pos->second];
        p.first = m.scenario;
        p.second.push_back(runs.back());
      }
      if (runs.empty()) continue;
      AddRateRows(in, {"parameter", "(all)", a.name + "=" + v, "(all)"}, runs, t);
      for (const auto& [pos, p] : per)
        AddRateRows(in, {"parameter", p.first, a.name + "=" + v, "(all)"}, p.second, t);
    }
  }
}

// Per vehicle class: over every run, and per value of each grouping parameter. A run without
// egos of a class is no sample of it.
void ClassRows(const RateInputs& in, Table& t) {
  std::map<std::string, std::vector<RunEvents>> all;
  std::map<std::tuple<std::string, std::string, std::string>, std::vector<RunEvents>> per_value;
  for (const RunMetrics& m : in.metrics.runs) {
    if (!m.ok) continue;
    for (const auto& [cls, e] : EventsByClass(m, NotFalse(in, m.run_index))) {
      all[cls].push_back(e);
      for (const RateAxis& a : in.axes) per_value[{cls, a.name, Param(m, a.name)}].push_back(e);
    }
  }
  for (const auto& [cls, runs] : all)
    AddRateRows(in, {"vehicle class", "(all)", "-", cls}, runs, t);
  for (const RateAxis& a : in.axes) {
    for (const auto& [cls, runs_all] : all) {
      for (const std::string& v : a.values) {
        const auto it = per_value.find({cls, a.name, v});
        if (it != per_value.end())
          AddRateRows(in, {"vehicle class", "(all)", a.name + "=" + v, cls}, it->second, t);
      }
    }
  }
}

Table PerRunTable(const RateInputs& in) {
  Table t;
  t.columns = {"run_index",     "scenario",   "parameters", "status",       "egos",
               "vehicle_hours", "vehicle_km", "warnings",   "false_alarms", "ego_collisions"};
  for (const RunMetrics& m : in.metrics.runs) {
    const RunEvents e = Totals(in, m);
    t.rows.push_back({Cell(static_cast<long long>(m.run_index)), m.scenario, m.label, m.status,
                      m.ok ? Cell(e.egos) : "", m.ok ? SigCell(e.hours, 4) : "",
                      m.ok && in.metrics.available.vehicle_km ? SigCell(e.km, 4) : "",
                      m.ok ? Cell(static_cast<long long>(e.warnings)) : "",
                      m.ok ? Cell(static_cast<long long>(e.false_alarms)) : "",
                      m.ok ? Cell(static_cast<long long>(e.ego_collisions)) : ""});
  }
  return t;
}

Table ClassTable(const RateInputs& in) {
  Table t;
  t.columns = {"vehicle_class", "runs",     "egos",         "vehicle_hours",
               "vehicle_km",    "warnings", "false_alarms", "ego_collisions"};
  std::map<std::string, std::pair<long long, RunEvents>> sum;
  for (const RunMetrics& m : in.metrics.runs) {
    if (!m.ok) continue;
    for (const auto& [cls, e] : EventsByClass(m, NotFalse(in, m.run_index))) {
      auto& s = sum[cls];
      ++s.first;
      s.second.egos += e.egos;
      s.second.hours += e.hours;
      s.second.km += e.km;
      s.second.warnings += e.warnings;
      s.second.false_alarms += e.false_alarms;
      s.second.ego_collisions += e.ego_collisions;
    }
  }
  for (const auto& [cls, s] : sum) {
    const RunEvents& e = s.second;
    t.rows.push_back({cls, Cell(s.first), Cell(e.egos), SigCell(e.hours, 4),
                      in.metrics.available.vehicle_km ? SigCell(e.km, 4) : "",
                      Cell(static_cast<long long>(e.warnings)),
                      Cell(static_cast<long long>(e.false_alarms)),
                      Cell(static_cast<long long>(e.ego_collisions))});
  }
  return t;
}

}  // namespace

std::map<std::string, RunEvents> EventsByClass(const RunMetrics& m,
                                               const std::set<std::string>& not_false_alarms) {
  auto class_of = [&](const std::string& ego) {
    const auto it = m.ego_class.find(ego);
    return it == m.ego_class.end() || it->second.empty() ? std::string("(unknown)") : it->second;
  };
  std::map<std::string, RunEvents> out;
  for (const auto& [ego, x] : m.ego_exposure) {
    RunEvents& e = out[class_of(ego)];
    e.hours += x.hours;
    e.km += x.km;
    ++e.egos;
  }
  for (const std::string& ego : m.warning_egos) out[class_of(ego)].warnings += 1.0;
  for (const std::string& ego : m.false_alarm_egos) {
    if (!not_false_alarms.count(ego)) out[class_of(ego)].false_alarms += 1.0;
  }
  for (const std::string& ego : m.collision_egos) out[class_of(ego)].ego_collisions += 1.0;
  return out;
}

RateTables MakeRateTables(const RateInputs& in) {
  RateTables out;
  out.per_run = PerRunTable(in);
  out.by_class = ClassTable(in);
  out.rates.columns = {"breakdown",
                       "scenario",
                       "parameters",
                       "vehicle_class",
                       "measure",
                       "events",
                       "runs",
                       "vehicle_hours",
                       "vehicle_km",
                       "per_vehicle_hour",
                       "per_vehicle_hour_low",
                       "per_vehicle_hour_high",
                       "per_million_vehicle_km",
                       "per_million_vehicle_km_low",
                       "per_million_vehicle_km_high",
                       "interval"};
  if (!in.metrics.available.vehicle_hours) return out;  // the metrics' notes say why
  std::vector<RunEvents> all;
  for (const RunMetrics& m : in.metrics.runs) {
    if (m.ok) all.push_back(Totals(in, m));
  }
  if (!all.empty()) AddRateRows(in, {"all runs", "(all)", "-", "(all)"}, all, out.rates);
  ScenarioRows(in, out.rates);
  ParameterRows(in, out.rates);
  if (in.metrics.available.vehicle_class) ClassRows(in, out.rates);
  return out;
}

void WriteExposureTable(SqliteDb& db, const RateInputs& in) {
  db.Exec(
      "DROP TABLE IF EXISTS report_exposure;"
      "CREATE TABLE report_exposure(run_index INTEGER, vehicle_class TEXT, egos INTEGER, "
      "vehicle_hours REAL, vehicle_km REAL, warnings INTEGER, false_alarms INTEGER, "
      "ego_collisions INTEGER, PRIMARY KEY(run_index, vehicle_class));");
  if (!in.metrics.available.vehicle_hours) return;
  db.Exec("BEGIN");
  Statement s = db.Prepare("INSERT INTO report_exposure VALUES(?,?,?,?,?,?,?,?)");
  for (const RunMetrics& m : in.metrics.runs) {
    if (!m.ok) continue;
    for (const auto& [cls, e] : EventsByClass(m, NotFalse(in, m.run_index))) {
      s.Bind(1, static_cast<long long>(m.run_index)).Bind(2, cls).Bind(3, e.egos).Bind(4, e.hours);
      if (in.metrics.available.vehicle_km)
        s.Bind(5, e.km);
      else
        s.BindNull(5);
      s.Bind(6, static_cast<long long>(e.warnings))
          .Bind(7, static_cast<long long>(e.false_alarms))
          .Bind(8, static_cast<long long>(e.ego_collisions));
      s.Run();
    }
  }
  db.Exec("COMMIT");
}

}  // namespace criticality::campaign
