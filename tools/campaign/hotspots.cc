#include "tools/campaign/hotspots.h"

#include <algorithm>
#include <map>
#include <tuple>

namespace criticality::campaign {
namespace {

bool HasAll(const std::vector<std::string>& have, std::initializer_list<const char*> cols) {
  for (const char* c : cols) {
    if (std::find(have.begin(), have.end(), c) == have.end()) return false;
  }
  return true;
}

std::string StripIndex(const std::string& id) {
  const auto u = id.find_last_of('_');
  return u == std::string::npos || u == 0 ? id : id.substr(0, u);
}

}  // namespace

std::pair<std::string, std::string> NetworkElement(const std::string& id, bool is_lane) {
  const std::string edge = is_lane ? StripIndex(id) : id;
  if (!edge.empty() && edge[0] == ':') return {"junction", StripIndex(edge.substr(1))};
  return {"edge", edge};
}

Hotspots ComputeHotspots(SqliteDb& db, const std::map<std::size_t, std::string>& setting) {
  Hotspots h;
  h.counts.columns = {"scenario", "parameters", "kind", "id", "warnings", "collisions"};
  h.points.columns = {"scenario", "parameters", "event", "run_index", "time_s",
                      "x_m",      "y_m",        "lane",  "pos_m"};
  auto setting_of = [&](long long run) {
    const auto it = setting.find(static_cast<std::size_t>(run));
    return it == setting.end() ? std::string("-") : it->second;
  };
  // (scenario, setting, kind, id) -> (warnings, collisions); settings in order of first run.
  std::map<std::tuple<std::string, std::string, std::string, std::string>,
           std::pair<long long, long long>>
      n;
  std::map<std::string, std::size_t> setting_order;
  const std::string ok_runs =
      " JOIN campaign_runs r ON r.run_index = t.run_index AND r.status = 'ok' ";

  const std::vector<std::string> w = db.Columns("warnings");
  if (!w.empty()) {
    const bool edge = HasAll(w, {"edge"});
    const bool xy = HasAll(w, {"x_m", "y_m"});
    if (edge || xy) {
      Statement s =
          db.Prepare("SELECT r.scenario, t.run_index, " + std::string(edge ? "t.edge" : "NULL") +
                     ", " + (xy ? "t.x_m, t.y_m" : "NULL, NULL") + ", t.start_s FROM warnings t" +
                     ok_runs + "ORDER BY t.run_index, t.rowid");
      while (s.Step()) {
        const std::string set = setting_of(s.Int(1));
        setting_order.emplace(set, setting_order.size());
        if (!s.IsNull(2)) {
          const auto [kind, id] = NetworkElement(s.Text(2), false);
          ++n[{s.Text(0), set, kind, id}].first;
        }
        if (!s.IsNull(3) && !s.IsNull(4)) {
          h.points.rows.push_back({s.Text(0), set, "warning", Cell(s.Int(1)),
                                   s.IsNull(5) ? "" : Cell(s.Real(5), 2), Cell(s.Real(3), 2),
                                   Cell(s.Real(4), 2), "", ""});
        }
      }
      if (!edge)
        h.notes.push_back("warning hotspots per edge: the warnings table has no edge column");
    } else {
      h.notes.push_back(
          "warning locations: the warnings table has no edge or x_m/y_m columns (run files from "
          "a driver that does not record where a warning starts)");
    }
  }

  const std::vector<std::string> c = db.Columns("collisions");
  if (!c.empty()) {
    const bool edge = HasAll(c, {"edge"});
    const bool lane = HasAll(c, {"lane"});
    const bool xy = HasAll(c, {"x_m", "y_m"});
    const bool pos = HasAll(c, {"pos_m"});
    if (edge || lane || xy) {
      Statement s =
          db.Prepare("SELECT r.scenario, t.run_index, " + std::string(edge ? "t.edge" : "NULL") +
                     ", " + (lane ? "t.lane" : "NULL") + ", " +
                     (xy ? "t.x_m, t.y_m" : "NULL, NULL") + ", " + (pos ? "t.pos_m" : "NULL") +
                     ", t.time_s FROM collisions t" + ok_runs + "ORDER BY t.run_index, t.rowid");
      while (s.Step()) {
        const std::string scenario = s.Text(0);
        const std::string set = setting_of(s.Int(1));
        setting_order.emplace(set, setting_order.size());
        if (!s.IsNull(2) && !s.Text(2).empty()) {
          const auto [kind, id] = NetworkElement(s.Text(2), false);
          ++n[{scenario, set, kind, id}].second;
        } else if (!s.IsNull(3) && !s.Text(3).empty()) {
          const auto [kind, id] = NetworkElement(s.Text(3), true);
          ++n[{scenario, set, kind, id}].second;
        }
        const bool has_xy = !s.IsNull(4) && !s.IsNull(5);
        const bool has_lane_pos = !s.IsNull(3) && !s.Text(3).empty() && !s.IsNull(6);
        if (has_xy || has_lane_pos) {
          h.points.rows.push_back(
              {scenario, set, "collision", Cell(s.Int(1)), s.IsNull(7) ? "" : Cell(s.Real(7), 2),
               has_xy ? Cell(s.Real(4), 2) : "", has_xy ? Cell(s.Real(5), 2) : "",
               s.IsNull(3) ? "" : s.Text(3), s.IsNull(6) ? "" : Cell(s.Real(6), 2)});
        }
      }
    } else {
      h.notes.push_back("collision locations: the collisions table has no edge, lane or x_m/y_m");
    }
  }

  std::vector<std::pair<decltype(n)::key_type, std::pair<long long, long long>>> sorted(n.begin(),
                                                                                        n.end());
  // Per scenario and setting (in run order), the most collisions first, then warnings.
  std::stable_sort(sorted.begin(), sorted.end(), [&](const auto& a, const auto& b) {
    if (std::get<0>(a.first) != std::get<0>(b.first))
      return std::get<0>(a.first) < std::get<0>(b.first);
    const std::size_t sa = setting_order[std::get<1>(a.first)];
    const std::size_t sb = setting_order[std::get<1>(b.first)];
    if (sa != sb) return sa < sb;
    if (a.second.second != b.second.second) return a.second.second > b.second.second;
    return a.second.first > b.second.first;
  });
  for (const auto& [key, v] : sorted) {
    h.counts.rows.push_back({std::get<0>(key), std::get<1>(key), std::get<2>(key), std::get<3>(key),
                             Cell(v.first), Cell(v.second)});
  }
  return h;
}

}  // namespace criticality::campaign
