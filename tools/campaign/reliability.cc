#include "tools/campaign/reliability.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "tools/campaign/run_metrics.h"

namespace criticality::campaign {
namespace {

bool HasAll(SqliteDb& db, const std::string& table, std::initializer_list<const char*> cols) {
  const std::vector<std::string> have = db.Columns(table);
  for (const char* c : cols) {
    if (std::find(have.begin(), have.end(), c) == have.end()) return false;
  }
  return !have.empty();
}

}  // namespace

Reliability ComputeReliability(SqliteDb& db, double default_horizon_s, int min_collisions,
                               int bins) {
  Reliability r;
  r.bins.columns = {"p_low", "p_high", "steps", "mean_p", "observed_frequency"};
  if (!HasAll(db, "steps", {"run_index", "ego", "time_s", "p_collision"}) ||
      !HasAll(db, "collisions", {"run_index", "time_s", "collider", "victim"})) {
    r.reason = "needs steps (ego, time_s, p_collision) and collisions (time_s, collider, victim)";
    return r;
  }
  MakeRunEgosTable(db);
  // First collision of each ego of each successful run.
  std::map<std::pair<long long, std::string>, double> first;
  {
    Statement s = db.Prepare(
        "SELECT c.run_index, e.ego, min(c.time_s) FROM collisions c JOIN _run_egos e ON "
        "e.run_index = c.run_index AND e.ego IN (c.collider, c.victim) JOIN campaign_runs r ON "
        "r.run_index = c.run_index AND r.status = 'ok' GROUP BY c.run_index, e.ego");
    while (s.Step()) first[{s.Int(0), s.Text(1)}] = s.Real(2);
  }
  r.ego_collisions = static_cast<long long>(first.size());
  if (r.ego_collisions < min_collisions) {
    r.reason = std::to_string(r.ego_collisions) + (r.ego_collisions == 1 ? " ego" : " egos") +
               " collided in successful runs; at least " + std::to_string(min_collisions) +
               " needed (--min-collisions)";
    return r;
  }
  // Horizon per run: the grid's `horizon`, else --horizon on its command line, else default.
  std::map<long long, double> horizon;
  {
    const bool options = HasAll(db, "runs", {"run_index", "options"});
    Statement s = db.Prepare(
        "SELECT r.run_index, (SELECT value FROM plan_params p WHERE p.run_index = r.run_index "
        "AND p.name = 'horizon'), " +
        std::string(options ? "(SELECT options FROM runs o WHERE o.run_index = r.run_index "
                              "LIMIT 1)"
                            : "NULL") +
        " FROM campaign_runs r WHERE r.status = 'ok'");
    while (s.Step()) {
      double h = default_horizon_s;
      const std::string opts = s.IsNull(2) ? "" : s.Text(2);
      const std::size_t at = opts.rfind("--horizon");  // the last one wins, as on a command line
      if (!s.IsNull(1)) {
        h = std::atof(s.Text(1).c_str());
      } else if (at != std::string::npos && at + 9 < opts.size() &&
                 (opts[at + 9] == ' ' || opts[at + 9] == '=')) {
        h = std::atof(opts.c_str() + at + 10);
      }
      horizon[s.Int(0)] = h > 0 ? h : default_horizon_s;
    }
  }
  std::vector<long long> count(bins, 0), hits(bins, 0);
  std::vector<double> p_sum(bins, 0.0);
  double brier = 0.0;
  Statement s = db.Prepare(
      "SELECT s.run_index, s.ego, s.time_s, s.p_collision FROM steps s JOIN campaign_runs r ON "
      "r.run_index = s.run_index AND r.status = 'ok'");
  while (s.Step()) {
    const long long run = s.Int(0);
    const double t = s.Real(2), p = s.Real(3);
    const auto it = first.find({run, s.Text(1)});
    const double crash = it == first.end() ? INFINITY : it->second;
    if (t >= crash - 1e-9) continue;
    const auto h = horizon.find(run);
    const bool followed = crash - t <= (h == horizon.end() ? default_horizon_s : h->second) + 1e-9;
    const int b = std::clamp(static_cast<int>(std::floor(p * bins)), 0, bins - 1);
    ++count[b];
    p_sum[b] += p;
    hits[b] += followed ? 1 : 0;
    brier += (p - (followed ? 1.0 : 0.0)) * (p - (followed ? 1.0 : 0.0));
    ++r.steps;
    r.followed += followed ? 1 : 0;
  }
  if (r.steps == 0) {
    r.reason = "no estimate before the collisions of successful runs";
    return r;
  }
  r.brier = brier / static_cast<double>(r.steps);
  for (int b = 0; b < bins; ++b) {
    const double lo = static_cast<double>(b) / bins, hi = static_cast<double>(b + 1) / bins;
    r.bins.rows.push_back(
        {Cell(lo, 2), Cell(hi, 2), Cell(count[b]),
         count[b] ? Cell(p_sum[b] / static_cast<double>(count[b]), 4) : "",
         count[b] ? Cell(static_cast<double>(hits[b]) / static_cast<double>(count[b]), 4) : ""});
  }
  r.available = true;
  return r;
}

}  // namespace criticality::campaign
