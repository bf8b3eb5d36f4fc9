#include "tools/campaign/report.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <numeric>
#include <set>
#include <sstream>

#include "tools/campaign/campaign_error.h"
#include "tools/campaign/hotspots.h"
#include "tools/campaign/rate_tables.h"
#include "tools/campaign/reliability.h"
#include "tools/campaign/run_metrics.h"
#include "tools/campaign/scenario_files.h"
#include "tools/campaign/sqlite_db.h"
#include "tools/campaign/table_writer.h"
#include "tools/campaign/warning_list.h"

#ifndef CRIT_CAMPAIGN_REPORT_SCRIPT
#define CRIT_CAMPAIGN_REPORT_SCRIPT ""
#endif

namespace fs = std::filesystem;
using nlohmann::json;

namespace criticality::campaign {
namespace {

struct AxisInfo {
  std::string name;
  std::string target;
  std::vector<std::string> values;
  bool grouping{true};  ///< false for replication axes (SUMO's seed): aggregated over
};

const std::vector<std::string> kMetricColumns = {"runs",
                                                 "ok",
                                                 "failed",
                                                 "collisions",
                                                 "ego_collisions",
                                                 "warned_collisions",
                                                 "anticipation_mean_s",
                                                 "anticipation_median_s",
                                                 "anticipation_min_s",
                                                 "warnings",
                                                 "false_alarms",
                                                 "collisions_avoided",
                                                 "estimator_ms_mean",
                                                 "estimator_ms_max",
                                                 "steps",
                                                 "vehicle_hours",
                                                 "vehicle_km",
                                                 "wall_s_mean"};

struct Aggregate {
  long long runs{0}, ok{0}, failed{0}, steps{0}, collisions{0}, ego_collisions{0}, warned{0},
      warnings{0}, false_alarms{0};
  std::vector<double> anticipation;
  double est_sum{0.0};
  std::optional<double> est_max;
  double wall_sum{0.0};
  double vehicle_hours{0.0}, vehicle_km{0.0};
  long long avoided{0};
  bool has_avoided{false};

  void Add(const RunMetrics& m, const std::optional<long long>& avoided_here,
           const std::optional<long long>& false_alarms_here) {
    ++runs;
    if (!m.ok) {
      ++failed;
      return;
    }
    ++ok;
    steps += m.steps;
    collisions += m.collisions;
    ego_collisions += m.ego_collisions;
    warned += m.warned_collisions;
    warnings += m.warnings;
    false_alarms += false_alarms_here.value_or(m.false_alarms);
    anticipation.insert(anticipation.end(), m.anticipation_s.begin(), m.anticipation_s.end());
    est_sum += m.estimator_ms_sum;
    if (m.estimator_ms_max) est_max = std::max(est_max.value_or(0.0), *m.estimator_ms_max);
    wall_sum += m.wall_s;
    vehicle_hours += m.vehicle_hours;
    vehicle_km += m.vehicle_km;
    if (avoided_here) {
      avoided += *avoided_here;
      has_avoided = true;
    }
  }

  std::vector<std::string> Cells(const MetricsAvailability& av) const {
    std::optional<double> mean, median, min;
    if (!anticipation.empty()) {
      std::vector<double> a = anticipation;
      std::sort(a.begin(), a.end());
      mean = std::accumulate(a.begin(), a.end(), 0.0) / static_cast<double>(a.size());
      median = a.size() % 2 ? a[a.size() / 2] : 0.5 * (a[a.size() / 2 - 1] + a[a.size() / 2]);
      min = a.front();
    }
    auto count = [&](bool available, long long v) { return available && ok ? Cell(v) : ""; };
    return {Cell(runs),
            Cell(ok),
            Cell(failed),
            count(av.collisions, collisions),
            count(av.ego_collisions, ego_collisions),
            count(av.anticipation, warned),
            Cell(mean),
            Cell(median),
            Cell(min),
            count(av.warnings, warnings),
            count(av.false_alarms, false_alarms),
            has_avoided ? Cell(avoided) : "",
            av.estimator_ms && steps ? Cell(est_sum / static_cast<double>(steps)) : "",
            av.estimator_ms ? Cell(est_max) : "",
            count(av.steps, steps),
            av.vehicle_hours && ok ? SigCell(vehicle_hours, 4) : "",
            av.vehicle_km && ok ? SigCell(vehicle_km, 4) : "",
            ok ? Cell(wall_sum / static_cast<double>(ok), 2) : ""};
  }
};

std::vector<AxisInfo> ReadAxes(const json& info) {
  std::vector<AxisInfo> axes;
  if (!info.contains("axes")) return axes;
  for (const json& a : info["axes"]) {
    AxisInfo x;
    x.name = a.value("name", "");
    x.target = a.value("target", "driver");
    for (const json& v : a.value("values", json::array())) x.values.push_back(v.get<std::string>());
    x.grouping = !(x.target == "sumo" && x.name == "seed");
    axes.push_back(std::move(x));
  }
  return axes;
}

// What braking changed: each run with act=brake against the same run (scenario, other
// parameters, repetition) with act=warn, else act=none. Collisions avoided: the baseline's ego
// collisions minus its own. False alarms: a warning of an ego that collided in the baseline was
// a true alarm whose braking worked, so it is not counted.
struct BrakingEffect {
  std::map<std::size_t, long long> avoided;
  std::map<std::size_t, long long> false_alarms;
  std::map<std::size_t, std::set<std::string>> twin_collided;  ///< egos that collided in the twin
};

BrakingEffect CompareBraking(const std::vector<RunMetrics>& runs, const std::vector<AxisInfo>& axes,
                             bool available, std::vector<std::string>& notes) {
  BrakingEffect out;
  const auto act = std::find_if(axes.begin(), axes.end(), [](const AxisInfo& a) {
    return a.name == "act" && a.target == "driver";
  });
  const bool has_brake =
      act != axes.end() && std::count(act->values.begin(), act->values.end(), "brake");
  const bool has_base =
      act != axes.end() && (std::count(act->values.begin(), act->values.end(), "warn") ||
                            std::count(act->values.begin(), act->values.end(), "none"));
  if (!has_brake || !has_base) {
    notes.push_back(
        "collisions avoided: needs `act` on the grid with brake and warn (or none); each braking "
        "run is compared with the same run that only warns");
    return out;
  }
  if (!available) {
    notes.push_back("collisions avoided: ego collisions are not computable");
    return out;
  }
  auto key = [](const RunMetrics& m) {
    std::string k = m.scenario + "\n";
    for (const auto& [name, value] : m.params) {
      if (name != "act") k += name + "=" + value + "\n";
    }
    return k;
  };
  // Repetitions: runs of one key in index order pair up in order.
  std::map<std::string, std::map<std::string, std::vector<const RunMetrics*>>> by_key;
  for (const RunMetrics& m : runs) {
    const auto it = m.params.find("act");
    if (it != m.params.end()) by_key[key(m)][it->second].push_back(&m);
  }
  for (auto& [k, by_act] : by_key) {
    const auto& brake = by_act["brake"];
    const auto& base = by_act.count("warn") ? by_act["warn"] : by_act["none"];
    for (std::size_t i = 0; i < brake.size() && i < base.size(); ++i) {
      if (!brake[i]->ok || !base[i]->ok) continue;
      const RunMetrics& b = *brake[i];
      out.avoided[b.run_index] = base[i]->ego_collisions - b.ego_collisions;
      const std::set<std::string> collided(base[i]->collided_egos.begin(),
                                           base[i]->collided_egos.end());
      long long false_alarms = 0;
      for (const std::string& ego : b.false_alarm_egos) false_alarms += collided.count(ego) ? 0 : 1;
      out.false_alarms[b.run_index] = false_alarms;
      out.twin_collided[b.run_index] = collided;
    }
  }
  return out;
}

std::string Quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string FindPython(const std::string& option, std::string& why) {
  // An interpreter named by the user is the only one tried; otherwise Debian's, then PATH's.
  std::string chosen = option;
  if (chosen.empty()) {
    if (const char* env = std::getenv("CRIT_PYTHON"); env && *env) chosen = env;
  }
  const std::vector<std::string> candidates =
      chosen.empty() ? std::vector<std::string>{"/usr/bin/python3", "python3"}
                     : std::vector<std::string>{chosen};
  bool any = false;
  for (const std::string& py : candidates) {
    if (std::system(("command -v " + Quote(py) + " >/dev/null 2>&1").c_str()) != 0) continue;
    any = true;
    if (std::system((Quote(py) + " -c 'import matplotlib' >/dev/null 2>&1").c_str()) == 0)
      return py;
  }
  why = !any ? "no python3 found (" + candidates.front() +
                   "; install python3-matplotlib: tools/setup.sh)"
        : candidates.size() == 1
            ? candidates.front() + " cannot import matplotlib (install python3-matplotlib)"
            : "python3 has no matplotlib (install python3-matplotlib: tools/setup.sh)";
  return "";
}

// criticality-bench replays a warning's scene for its picture (its hypotheses' paths).
std::string FindBench(const std::string& option) {
  auto executable = [](const fs::path& p) {
    std::error_code ec;
    return fs::is_regular_file(p, ec) && access(p.c_str(), X_OK) == 0;
  };
  if (!option.empty()) return executable(option) ? fs::absolute(option).string() : "";
  if (const char* env = std::getenv("CRIT_BENCH"); env && *env) return executable(env) ? env : "";
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec).parent_path();
  for (const fs::path& p :
       {self / "../../estimator/bench/criticality-bench", self / "criticality-bench"}) {
    if (!ec && executable(p)) return p.lexically_normal().string();
  }
  if (const char* path = std::getenv("PATH")) {
    std::stringstream dirs(path);
    for (std::string d; std::getline(dirs, d, ':');) {
      if (!d.empty() && executable(fs::path(d) / "criticality-bench"))
        return (fs::path(d) / "criticality-bench").string();
    }
  }
  return "";
}

fs::path FindScript(const fs::path& option) {
  if (!option.empty()) return option;
  if (const char* env = std::getenv("CRIT_CAMPAIGN_REPORT_SCRIPT"); env && *env) return env;
  return CRIT_CAMPAIGN_REPORT_SCRIPT;
}

// Runs a command; returns its exit status and the last line of its output.
std::pair<int, std::string> RunCaptured(const std::string& cmd) {
  FILE* pipe = popen((cmd + " 2>&1").c_str(), "r");
  if (!pipe) return {-1, "cannot start"};
  std::string text;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) text.append(buf.data(), n);
  const int status = pclose(pipe);
  while (!text.empty() && text.back() == '\n') text.pop_back();
  const auto nl = text.find_last_of('\n');
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1,
          nl == std::string::npos ? text : text.substr(nl + 1)};
}

// What every table is computed from: the runs' metrics, the grid, and braking's effect.
struct ReportInputs {
  const json& info;
  std::vector<AxisInfo> axes;
  RunMetricsSet metrics;
  BrakingEffect braking;
  std::map<std::string, std::size_t> scenario_order;  ///< as in the plan
};

std::map<std::string, std::size_t> ScenarioOrder(const json& info) {
  std::map<std::string, std::size_t> order;
  if (info.contains("scenarios")) {
    for (const json& s : info["scenarios"]) order.emplace(s.value("name", ""), order.size());
  }
  return order;
}

// The plan position of a scenario; `unknown` for one the plan does not list.
std::size_t ScenarioPos(const ReportInputs& in, const std::string& scenario, std::size_t unknown) {
  const auto it = in.scenario_order.find(scenario);
  return it == in.scenario_order.end() ? unknown : it->second;
}

std::size_t ValuePos(const AxisInfo& a, const std::string& v) {
  const auto it = std::find(a.values.begin(), a.values.end(), v);
  return static_cast<std::size_t>(it - a.values.begin());
}

std::optional<long long> Lookup(const std::map<std::size_t, long long>& m, std::size_t run) {
  const auto it = m.find(run);
  return it == m.end() ? std::nullopt : std::optional<long long>(it->second);
}

void AddRun(const ReportInputs& in, Aggregate& g, const RunMetrics& m) {
  g.Add(m, Lookup(in.braking.avoided, m.run_index), Lookup(in.braking.false_alarms, m.run_index));
}

// Per scenario and grouping parameters.
Table SummaryTable(const ReportInputs& in) {
  Table summary;
  summary.columns = {"scenario"};
  for (const AxisInfo& a : in.axes) {
    if (a.grouping) summary.columns.push_back(a.name);
  }
  summary.columns.insert(summary.columns.end(), kMetricColumns.begin(), kMetricColumns.end());
  std::map<std::vector<std::size_t>, std::pair<std::vector<std::string>, Aggregate>> groups;
  for (const RunMetrics& m : in.metrics.runs) {
    std::vector<std::size_t> key{ScenarioPos(in, m.scenario, in.scenario_order.size())};
    std::vector<std::string> cells{m.scenario};
    for (const AxisInfo& a : in.axes) {
      if (!a.grouping) continue;
      const auto it = m.params.find(a.name);
      const std::string v = it == m.params.end() ? "" : it->second;
      key.push_back(ValuePos(a, v));
      cells.push_back(v);
    }
    auto& g = groups[key];
    if (g.first.empty()) g.first = cells;
    AddRun(in, g.second, m);
  }
  for (const auto& [key, g] : groups) {
    std::vector<std::string> row = g.first;
    const auto cells = g.second.Cells(in.metrics.available);
    row.insert(row.end(), cells.begin(), cells.end());
    summary.rows.push_back(std::move(row));
  }
  return summary;
}

// The rows of one value of one axis: over all scenarios, then per scenario in plan order.
void AddParameterRows(const ReportInputs& in, const AxisInfo& a, const std::string& v,
                      Table& by_param) {
  std::map<std::size_t, std::pair<std::string, Aggregate>> per;
  Aggregate all;
  for (const RunMetrics& m : in.metrics.runs) {
    const auto it = m.params.find(a.name);
    if (it == m.params.end() || it->second != v) continue;
    auto& p = per[ScenarioPos(in, m.scenario, 9999)];
    p.first = m.scenario;
    AddRun(in, p.second, m);
    AddRun(in, all, m);
  }
  auto add_row = [&](const std::string& scenario, const Aggregate& g) {
    std::vector<std::string> row{a.name, v, scenario};
    const auto cells = g.Cells(in.metrics.available);
    row.insert(row.end(), cells.begin(), cells.end());
    by_param.rows.push_back(std::move(row));
  };
  add_row("(all)", all);
  for (const auto& [pos, p] : per) add_row(p.first, p.second);
}

// Per parameter value, per scenario and over all scenarios.
Table ByParameterTable(const ReportInputs& in) {
  Table by_param;
  by_param.columns = {"parameter", "value", "scenario"};
  by_param.columns.insert(by_param.columns.end(), kMetricColumns.begin(), kMetricColumns.end());
  for (const AxisInfo& a : in.axes) {
    if (!a.grouping) continue;
    for (const std::string& v : a.values) AddParameterRows(in, a, v, by_param);
  }
  return by_param;
}

Table FailuresTable(SqliteDb& db) {
  Table failures;
  failures.columns = {"run_index", "scenario", "parameters", "status", "exit_code", "error"};
  Statement s = db.Prepare(
      "SELECT run_index, scenario, label, status, exit_code, signal, error FROM campaign_runs "
      "WHERE status != 'ok' ORDER BY run_index");
  while (s.Step()) {
    failures.rows.push_back({Cell(s.Int(0)), s.Text(1), s.Text(2), s.Text(3),
                             s.IsNull(4) ? (s.IsNull(5) ? "" : "signal " + s.Text(5)) : s.Text(4),
                             s.Text(6)});
  }
  return failures;
}

// Each run's grouping parameters, as the hotspots are split: "act=warn" ("-" without).
std::map<std::size_t, std::string> Settings(const ReportInputs& in) {
  std::map<std::size_t, std::string> out;
  for (const RunMetrics& m : in.metrics.runs) {
    std::string label;
    for (const AxisInfo& a : in.axes) {
      if (!a.grouping) continue;
      const auto it = m.params.find(a.name);
      label += (label.empty() ? "" : " ") + a.name + "=" + (it == m.params.end() ? "" : it->second);
    }
    out[m.run_index] = label.empty() ? "-" : label;
  }
  return out;
}

RateInputs RatesOf(const ReportInputs& in) {
  RateInputs r{
      in.metrics, {}, in.scenario_order, in.braking.false_alarms, in.braking.twin_collided};
  for (const AxisInfo& a : in.axes) {
    if (a.grouping) r.axes.push_back({a.name, a.values});
  }
  return r;
}

// Every table of the report, as written.
struct ReportTables {
  Table summary, by_param, failures;
  Hotspots hot;
  Reliability rel;
  RateTables rates;
  Table warnings;
};

void WriteTables(const ReportTables& t, ReportResult& result) {
  WriteCsv(t.summary, result.dir / "summary.csv");
  WriteCsv(t.by_param, result.dir / "by_parameter.csv");
  WriteCsv(t.failures, result.dir / "failures.csv");
  WriteCsv(t.hot.counts, result.dir / "hotspots.csv");
  WriteCsv(t.hot.points, result.dir / "events.csv");
  WriteCsv(t.rates.per_run, result.dir / "exposure.csv");
  WriteCsv(t.rates.rates, result.dir / "rates.csv");
  WriteCsv(t.rates.by_class, result.dir / "by_vehicle_class.csv");
  WriteCsv(t.warnings, result.dir / "warnings.csv");
  result.files = {"summary.csv",  "by_parameter.csv",     "failures.csv",
                  "hotspots.csv", "events.csv",           "exposure.csv",
                  "rates.csv",    "by_vehicle_class.csv", "warnings.csv"};
  if (t.rel.available) {
    WriteCsv(t.rel.bins, result.dir / "reliability.csv");
    result.files.push_back("reliability.csv");
  }
}

// The network file of a scenario, for its map; "" when it cannot be found.
std::string NetFileOf(const Scenario& sc) {
  try {
    const fs::path cfg = SumoConfigOf(sc);
    if (!cfg.empty() && fs::exists(cfg)) {
      const auto nets = SumoConfigFiles(cfg, "net-file");
      if (!nets.empty() && fs::exists(nets.front())) return nets.front().string();
    }
  } catch (const CampaignError&) {
  }
  return "";
}

json ScenariosManifest(const json& info) {
  json out = json::array();
  if (!info.contains("scenarios")) return out;
  for (const json& s : info["scenarios"]) {
    Scenario sc;
    sc.name = s.value("name", "");
    sc.path = s.value("path", "");
    sc.kind =
        s.value("kind", "") == "cfg" ? ScenarioKind::kDriverConfig : ScenarioKind::kSumoConfig;
    out.push_back({{"name", sc.name}, {"path", sc.path.string()}, {"net_file", NetFileOf(sc)}});
  }
  return out;
}

// Run counts for the headline.
struct RunCounts {
  std::size_t planned{0}, complete{0};
  long long ok{0}, failed{0};
};

RunCounts CountRuns(const CampaignFolder& folder, const RunMetricsSet& metrics) {
  RunCounts c;
  c.planned = folder.runs();
  c.complete = metrics.runs.size();
  for (const RunMetrics& m : metrics.runs) (m.ok ? c.ok : c.failed) += 1;
  return c;
}

// The manifest for the figure script (its notes are added once they are complete).
json Manifest(const ReportInputs& in, const ReportTables& t, const RunCounts& c,
              const ReportOptions& o, const std::vector<std::string>& files) {
  json manifest;
  manifest["name"] = in.info.value("name", "campaign");
  manifest["runs"] = c.planned;
  manifest["complete"] = c.complete;
  manifest["ok"] = c.ok;
  manifest["failed"] = c.failed;
  manifest["grace_s"] = o.grace_s;
  manifest["scene_pictures"] = o.scene_pictures;
  manifest["bench"] = FindBench(o.bench);
  manifest["available"] = {{"vehicle_hours", in.metrics.available.vehicle_hours},
                           {"vehicle_km", in.metrics.available.vehicle_km},
                           {"vehicle_class", in.metrics.available.vehicle_class},
                           {"collisions", in.metrics.available.collisions},
                           {"false_alarms", in.metrics.available.false_alarms}};
  manifest["axes"] = json::array();
  for (const AxisInfo& a : in.axes) {
    manifest["axes"].push_back(
        {{"name", a.name}, {"target", a.target}, {"values", a.values}, {"grouping", a.grouping}});
  }
  manifest["scenarios"] = ScenariosManifest(in.info);
  const Reliability& rel = t.rel;
  manifest["reliability"] = {{"available", rel.available},
                             {"reason", rel.reason},
                             {"steps", rel.steps},
                             {"followed", rel.followed},
                             {"ego_collisions", rel.ego_collisions},
                             {"brier", rel.available ? json(rel.brier) : json()}};
  manifest["tables"] = files;
  return manifest;
}

// A section of tables: the table, or `empty` when it has no rows.
void TableSection(std::ostream& md, const std::string& title, const Table& t,
                  const std::string& empty, std::size_t max_rows = 0) {
  md << "## " << title << "\n\n";
  if (t.rows.empty())
    md << empty << "\n\n";
  else
    md << MarkdownTable(t, max_rows) << "\n";
}

void ReliabilitySection(std::ostream& md, const Reliability& rel) {
  md << "## Reliability (is p calibrated?)\n\n";
  if (!rel.available) {
    md << "Not computed: " << rel.reason << ".\n\n";
    return;
  }
  md << rel.steps << " estimates of egos in successful runs (up to each ego's first "
     << "collision), " << rel.ego_collisions << " egos collided; " << rel.followed
     << " estimates were followed by their ego's collision within the horizon. Brier "
     << "score " << Cell(rel.brier, 4)
     << ". Consecutive steps are correlated: read counts as estimates, not independent "
        "trials.\n\n"
     << MarkdownTable(rel.bins) << "\n";
}

void ColumnsSection(std::ostream& md, double grace_s) {
  md << "\n## Columns\n\n"
     << "- `collisions`: every collision SUMO reported; `ego_collisions`: those involving an "
        "ego; `warned_collisions`: ego collisions with a warning before them (anticipation "
        "known).\n"
     << "- `anticipation_*_s`: collision time minus the start of the warning before it "
        "(the driver's anticipation_s), over warned ego collisions.\n"
     << "- `false_alarms`: warning episodes with no collision of their ego, and no critical "
        "event of it (its body overlapping another's, braking harder than its vehicle type's "
        "decel: the driver's critical_events table), from their start until "
     << Cell(grace_s, 2)
     << " s after their end; in an act=brake run, a warning of an ego that collided in the "
        "same run with act=warn (or none) is not counted (its braking avoided the "
        "collision).\n"
     << "- `collisions_avoided`: for act=brake runs, ego collisions of the same run with "
        "act=warn (or none) minus its own.\n"
     << "- `estimator_ms_*`: estimator time per estimate (steps table); `wall_s_mean`: wall "
        "time per run.\n"
     << "- `vehicle_hours`: ego estimates x the run's step length; `vehicle_km`: the egos' "
        "speed x step length, summed: how long and how far vehicles were watched.\n"
     << "- Rates: events over exposure, pooled over the group's runs; the interval is 95 % "
        "across those runs (t interval of the ratio, each run a cluster: how much the rate "
        "moves from seed to seed) when there are two runs or more and at least one event, "
        "else the exact Poisson interval of the pooled count (`interval`: runs or poisson; 0 "
        "events: 0 to 3.69 / exposure). A collision of two egos counts for each of their "
        "vehicle classes.\n";
}

void WriteSummaryMarkdown(const fs::path& file, const std::string& name, const RunCounts& c,
                          const ReportTables& t, const std::vector<std::string>& notes,
                          double grace_s) {
  std::ofstream md(file);
  md << "# Campaign " << name << ": report\n\n"
     << c.planned << " runs planned, " << c.complete << " complete (" << c.ok << " ok, " << c.failed
     << " failed), " << (c.planned - c.complete)
     << " not complete. Merged database: `campaign.sqlite`. Metrics count successful runs "
        "only; seeds (SUMO `seed`) are aggregated over.\n\n"
     << "## Per scenario and parameters\n\n"
     << MarkdownTable(t.summary) << "\n";
  TableSection(md, "Per parameter value", t.by_param, "(no grid parameters)");
  TableSection(md,
               "Rates per exposure (95 % interval across the runs of a group: seeds, "
               "repetitions)",
               t.rates.rates, "Not computable (see Not computed).");
  TableSection(md, "Per vehicle class of the egos", t.rates.by_class,
               "Not computable (see Not computed).");
  TableSection(md, "Failed runs", t.failures, "None.", 50);
  TableSection(md, "Hotspots (where collisions and warnings happened)", t.hot.counts,
               "No located collisions or warnings.", 30);
  ReliabilitySection(md, t.rel);
  md << "## Not computed\n\n";
  if (notes.empty()) md << "Everything was computable.\n";
  for (const std::string& n : notes) md << "- " << n << "\n";
  ColumnsSection(md, grace_s);
  if (!md) throw CampaignError("cannot write '" + file.string() + "'");
}

// The figures and index.html, by campaign_report.py; says in the result why not when not.
void MakeFigures(const ReportOptions& o, ReportResult& result) {
  if (!o.plots) {
    result.figures_missing = "--no-plots";
    return;
  }
  std::string why;
  const std::string python = FindPython(o.python, why);
  const fs::path script = FindScript(o.script);
  if (python.empty()) {
    result.figures_missing = why + "; tables are in " + (result.dir / "summary.md").string();
    return;
  }
  if (script.empty() || !fs::exists(script)) {
    result.figures_missing = "figure script not found (" +
                             (script.empty() ? std::string("none built in") : script.string()) +
                             "; give --script or CRIT_CAMPAIGN_REPORT_SCRIPT)";
    return;
  }
  const auto [rc, last] =
      RunCaptured(Quote(python) + " " + Quote(script.string()) + " " + Quote(result.dir.string()));
  if (rc != 0) {
    result.figures_missing = script.filename().string() + " failed: " + last;
    return;
  }
  result.figures = true;
  for (const auto& e : fs::directory_iterator(result.dir)) {
    const std::string ext = e.path().extension().string();
    if (ext == ".png" || ext == ".svg" || ext == ".html")
      result.files.push_back(e.path().filename().string());
  }
  std::sort(result.files.begin() + 1, result.files.end());
}

}  // namespace

ReportResult MakeReport(const CampaignFolder& folder, const ReportOptions& o) {
  ReportResult result;
  result.dir = folder.dir() / "report";
  fs::create_directories(result.dir);
  const fs::path db_path = folder.dir() / "campaign.sqlite";
  if (!fs::exists(db_path))
    throw CampaignError("no " + db_path.string() + ": run `criticality-campaign merge` first");
  // The grace is written into the result views as a number.
  if (!std::isfinite(o.grace_s)) throw CampaignError("--grace: not a finite number of seconds");
  SqliteDb db(db_path.string(), false);

  ReportInputs in{folder.info(),
                  ReadAxes(folder.info()),
                  LoadRunMetrics(db, o.grace_s),
                  {},
                  ScenarioOrder(folder.info())};
  std::vector<std::string>& notes = result.notes;
  notes = in.metrics.notes;
  in.braking = CompareBraking(in.metrics.runs, in.axes, in.metrics.available.ego_collisions, notes);

  ReportTables t{SummaryTable(in),
                 ByParameterTable(in),
                 FailuresTable(db),
                 ComputeHotspots(db, Settings(in)),
                 {},
                 {},
                 WarningList(db, in.metrics, Settings(in), in.braking.twin_collided, notes)};
  const RateInputs rate_in = RatesOf(in);
  t.rates = MakeRateTables(rate_in);
  WriteExposureTable(db, rate_in);
  notes.insert(notes.end(), t.hot.notes.begin(), t.hot.notes.end());
  t.rel = ComputeReliability(db, o.default_horizon_s, o.reliability_min_collisions);
  if (!t.rel.available) notes.push_back("reliability diagram: " + t.rel.reason);
  WriteTables(t, result);

  const RunCounts counts = CountRuns(folder, in.metrics);
  json manifest = Manifest(in, t, counts, o, result.files);
  manifest["database"] = db_path.string();  // the figure script reads scenes and p series there
  WriteSummaryMarkdown(result.dir / "summary.md", manifest["name"].get<std::string>(), counts, t,
                       notes, o.grace_s);
  result.files.insert(result.files.begin(), "summary.md");
  manifest["notes"] = notes;
  {
    std::ofstream mf(result.dir / "report.json");
    mf << manifest.dump(2, ' ', false, json::error_handler_t::replace) << "\n";
  }
  MakeFigures(o, result);
  return result;
}

}  // namespace criticality::campaign
