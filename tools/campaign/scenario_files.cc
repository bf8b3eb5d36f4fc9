#include "tools/campaign/scenario_files.h"

#include <glob.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "tools/campaign/campaign_error.h"
#include "tools/campaign/xml_scan.h"

namespace fs = std::filesystem;

namespace criticality::campaign {
namespace {

std::string ReadText(const fs::path& p) {
  std::ifstream in(p);
  if (!in) throw CampaignError(p.string() + ": cannot read the file");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string Where(const CampaignSpec& spec, int line, const std::string& key) {
  return spec.file.string() + ":" + std::to_string(line) + ": " + key + ": ";
}

std::vector<fs::path> Glob(const fs::path& pattern) {
  glob_t g{};
  const int rc = glob(pattern.c_str(), 0, nullptr, &g);
  std::vector<fs::path> out;
  if (rc == 0) {
    for (std::size_t k = 0; k < g.gl_pathc; ++k) out.emplace_back(g.gl_pathv[k]);
  }
  globfree(&g);
  // Byte order, whatever the locale: the plan must not depend on LC_COLLATE.
  std::sort(out.begin(), out.end(),
            [](const fs::path& a, const fs::path& b) { return a.string() < b.string(); });
  return out;
}

std::string Trim(std::string s) {
  const auto b = s.find_first_not_of(" \t\r");
  const auto e = s.find_last_not_of(" \t\r");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

}  // namespace

std::vector<fs::path> SumoConfigFiles(const fs::path& sumocfg, const std::string& key) {
  std::vector<fs::path> out;
  ScanXmlTags(ReadText(sumocfg), [&](const std::string& tag, const XmlAttributes& a) {
    if (tag != key) return;
    const auto v = a.find("value");
    if (v == a.end()) return;
    std::stringstream list(v->second);
    std::string item;
    while (std::getline(list, item, ',')) {
      item = Trim(item);
      if (!item.empty()) out.push_back((sumocfg.parent_path() / item).lexically_normal());
    }
  });
  return out;
}

fs::path SumoConfigOf(const Scenario& s) {
  if (s.kind == ScenarioKind::kSumoConfig) return s.path;
  std::ifstream in(s.path);
  std::string line;
  while (std::getline(in, line)) {
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    const auto eq = line.find('=');
    if (eq == std::string::npos) continue;
    const std::string key = Trim(line.substr(0, eq));
    if (key == "sumo-config" || key == "c") {
      const fs::path p = Trim(line.substr(eq + 1));
      return p.is_absolute() ? p : (s.path.parent_path() / p).lexically_normal();
    }
  }
  return {};
}

std::vector<std::string> VehiclesOfType(const std::vector<fs::path>& route_files,
                                        const std::string& type) {
  std::vector<std::string> ids;
  for (const fs::path& f : route_files) {
    ScanXmlTags(ReadText(f), [&](const std::string& tag, const XmlAttributes& a) {
      if (tag != "vehicle" && tag != "trip" && tag != "flow") return;
      const auto t = a.find("type");
      const std::string vtype = t == a.end() ? "DEFAULT_VEHTYPE" : t->second;
      const auto id = a.find("id");
      if (vtype != type || id == a.end()) return;
      if (tag != "flow") {
        ids.push_back(id->second);
        return;
      }
      const auto number = a.find("number");
      if (number == a.end()) return;
      const long n = std::strtol(number->second.c_str(), nullptr, 10);
      for (long k = 0; k < n; ++k) ids.push_back(id->second + "." + std::to_string(k));
    });
  }
  return ids;
}

std::vector<Scenario> ResolveScenarios(const CampaignSpec& spec) {
  std::vector<Scenario> out;
  std::map<std::string, std::size_t> by_path;
  for (std::size_t k = 0; k < spec.scenarios.size(); ++k) {
    const ScenarioEntry& e = spec.scenarios[k];
    const std::string key = "scenarios[" + std::to_string(k) + "]";
    const fs::path pattern =
        fs::path(e.pattern).is_absolute() ? fs::path(e.pattern) : spec.base_dir / e.pattern;
    const std::vector<fs::path> files = Glob(pattern.lexically_normal());
    if (files.empty()) {
      throw CampaignError(Where(spec, e.line, key) + "'" + e.pattern + "' matches no file (" +
                          pattern.lexically_normal().string() + ")");
    }
    if (!e.name.empty() && files.size() > 1) {
      throw CampaignError(Where(spec, e.line, key + ".name") + "'" + e.pattern + "' matches " +
                          std::to_string(files.size()) + " files; a name fits only one");
    }
    for (const fs::path& f : files) {
      Scenario s;
      s.entry = k;
      s.line = e.line;
      s.path = fs::absolute(f).lexically_normal();
      s.rel_path = s.path.lexically_relative(spec.base_dir).string();
      if (by_path.count(s.path.string())) {
        throw CampaignError(Where(spec, e.line, key) + s.rel_path +
                            " is already in the campaign (an earlier entry matches it too)");
      }
      if (!fs::is_regular_file(s.path)) {
        throw CampaignError(Where(spec, e.line, key) + s.rel_path + " is not a file");
      }
      const std::string ext = s.path.extension().string();
      if (ext == ".sumocfg") {
        s.kind = ScenarioKind::kSumoConfig;
      } else if (ext == ".cfg") {
        s.kind = ScenarioKind::kDriverConfig;
      } else {
        throw CampaignError(Where(spec, e.line, key) + s.rel_path +
                            ": expected a driver scenario.cfg (--config) or a SUMO .sumocfg");
      }
      s.name = !e.name.empty()                         ? e.name
               : s.kind == ScenarioKind::kDriverConfig ? s.path.parent_path().filename().string()
                                                       : s.path.stem().string();
      const std::optional<EgoSelection>& egos = e.egos ? e.egos : spec.egos;
      // The campaign-wide `egos` is for plain .sumocfg files; a scenario.cfg names its own
      // (an entry's own `egos` adds to them).
      const bool use = e.egos || (egos && s.kind == ScenarioKind::kSumoConfig);
      // Egos may also come as driver options (`ego`, `all-vehicles: true`, fixed or on the grid).
      const bool driver_egos =
          std::any_of(spec.driver_options.begin(), spec.driver_options.end(),
                      [](const FixedOption& o) {
                        return o.name == "ego" || (o.name == "all-vehicles" &&
                                                   o.values == std::vector<std::string>{"true"});
                      }) ||
          std::any_of(spec.axes.begin(), spec.axes.end(), [](const Axis& a) {
            return a.target == Target::kDriver && (a.name == "ego" || a.name == "all-vehicles");
          });
      if (use && driver_egos) {
        throw CampaignError(Where(spec, egos->line, e.egos ? key + ".egos" : "egos") +
                            "the driver options choose the egos too (`ego` or `all-vehicles`); "
                            "keep one of the two");
      }
      if (s.kind == ScenarioKind::kSumoConfig && !use && !driver_egos) {
        throw CampaignError(Where(spec, e.line, key) + s.rel_path +
                            " is a plain .sumocfg: say which vehicles are egos with `egos:` (all, "
                            "a list of IDs, or {type: VTYPE}) for the campaign or this entry");
      }
      if (use) {
        s.has_egos = true;
        s.egos = *egos;
        if (egos->kind == EgoSelection::Kind::kType) {
          const fs::path cfg = SumoConfigOf(s);
          std::vector<fs::path> routes;
          if (!cfg.empty() && fs::exists(cfg)) {
            routes = SumoConfigFiles(cfg, "route-files");
            for (const fs::path& a : SumoConfigFiles(cfg, "additional-files")) {
              if (fs::exists(a)) routes.push_back(a);
            }
          }
          s.egos.kind = EgoSelection::Kind::kIds;
          s.egos.ids = VehiclesOfType(routes, egos->type);
          if (s.egos.ids.empty()) {
            throw CampaignError(Where(spec, egos->line, "egos.type") + "no vehicle of type '" +
                                egos->type + "' in the route files of " + s.rel_path +
                                " (<vehicle>, <trip>, <flow number=...>; flows without a number "
                                "are not counted)");
          }
        }
      }
      by_path[s.path.string()] = out.size();
      out.push_back(std::move(s));
    }
  }
  // Names label tables and figures. A name given (`name:`) must be the only one of its kind;
  // clashing names derived from paths are made unique with their paths.
  std::map<std::string, int> count;
  for (const Scenario& s : out) ++count[s.name];
  for (const Scenario& s : out) {
    const ScenarioEntry& e = spec.scenarios[s.entry];
    if (e.name.empty() || count[s.name] == 1) continue;
    const auto other = std::find_if(out.begin(), out.end(), [&](const Scenario& o) {
      return o.name == s.name && o.path != s.path;
    });
    throw CampaignError(Where(spec, e.line, "scenarios[" + std::to_string(s.entry) + "].name") +
                        "'" + s.name + "' is also the name of " + other->rel_path +
                        "; give each scenario its own name");
  }
  for (Scenario& s : out) {
    if (count[s.name] > 1) s.name = fs::path(s.rel_path).replace_extension().string();
  }
  return out;
}

}  // namespace criticality::campaign
