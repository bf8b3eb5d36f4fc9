#include "tools/campaign/campaign_file.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "tools/campaign/campaign_error.h"

namespace fs = std::filesystem;

namespace criticality::campaign {
namespace {

// Driver options the campaign sets itself for every run.
const std::set<std::string> kReservedDriverOptions = {
    "output", "no-progress", "config", "sumo-config", "c", "connect", "help", "h", "version"};

class Reader {
 public:
  explicit Reader(fs::path file) : file_(std::move(file)) {}

  [[noreturn]] void Fail(const YAML::Node& at, const std::string& key,
                         const std::string& what) const {
    Fail(Line(at), key, what);
  }
  [[noreturn]] void Fail(int line, const std::string& key, const std::string& what) const {
    std::ostringstream s;
    s << file_.string();
    if (line > 0) s << ":" << line;
    s << ": " << (key.empty() ? "" : key + ": ") << what;
    throw CampaignError(s.str());
  }
  static int Line(const YAML::Node& n) { return n.Mark().line + 1; }

  static std::string Kind(const YAML::Node& n) {
    switch (n.Type()) {
      case YAML::NodeType::Map:
        return "a mapping";
      case YAML::NodeType::Sequence:
        return "a list";
      case YAML::NodeType::Null:
        return "nothing";
      default:
        return "'" + n.Scalar() + "'";
    }
  }

  void RequireMap(const YAML::Node& n, const std::string& key) const {
    if (!n.IsMap()) Fail(n, key, "expected a mapping (name: value lines), got " + Kind(n));
  }

  /** A key given twice in one mapping, anywhere in the document, is an error naming the key
   *  and both lines (YAML parsers keep the first and drop the other without a word). */
  void CheckNoDuplicateKeys(const YAML::Node& n, const std::string& prefix) const {
    if (n.IsSequence()) {
      for (std::size_t k = 0; k < n.size(); ++k)
        CheckNoDuplicateKeys(n[k], prefix + "[" + std::to_string(k) + "]");
      return;
    }
    if (!n.IsMap()) return;
    std::map<std::string, int> first_line;
    for (auto it = n.begin(); it != n.end(); ++it) {
      const std::string k = it->first.IsScalar() ? it->first.Scalar() : "";
      const std::string key = prefix.empty() ? k : prefix + "." + k;
      const auto [at, fresh] = first_line.emplace(k, Line(it->first));
      if (!fresh) {
        Fail(it->first, key,
             "given twice (first at line " + std::to_string(at->second) + "); keep one");
      }
      CheckNoDuplicateKeys(it->second, key);
    }
  }

  /** Keys of `map` not in `allowed` are errors naming the key and its line. */
  void CheckKeys(const YAML::Node& map, const std::string& prefix,
                 const std::set<std::string>& allowed) const {
    for (auto it = map.begin(); it != map.end(); ++it) {
      const std::string k = it->first.Scalar();
      if (!allowed.count(k)) {
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        Fail(it->first, prefix + k, "unknown key (expected one of: " + list + ")");
      }
    }
  }

  std::string String(const YAML::Node& n, const std::string& key) const {
    if (!n.IsScalar()) Fail(n, key, "expected a text value, got " + Kind(n));
    return n.Scalar();
  }

  long long Integer(const YAML::Node& n, const std::string& key, long long min) const {
    if (!n.IsScalar()) Fail(n, key, "expected a whole number, got " + Kind(n));
    const std::string& s = n.Scalar();
    std::size_t used = 0;
    long long v = 0;
    try {
      v = std::stoll(s, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != s.size()) Fail(n, key, "expected a whole number, got '" + s + "'");
    if (v < min) Fail(n, key, "must be at least " + std::to_string(min) + ", got " + s);
    return v;
  }

  double Number(const YAML::Node& n, const std::string& key, double min) const {
    if (!n.IsScalar()) Fail(n, key, "expected a number, got " + Kind(n));
    const std::string& s = n.Scalar();
    std::size_t used = 0;
    double v = 0;
    try {
      v = std::stod(s, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != s.size() || !std::isfinite(v))
      Fail(n, key, "expected a number, got '" + s + "'");
    if (v < min) Fail(n, key, "must be at least " + std::to_string(min) + ", got " + s);
    return v;
  }

  // A plain (unquoted) true/false is a boolean; quoted "true" stays text.
  static bool IsBoolean(const YAML::Node& n) {
    if (!n.IsScalar() || n.Tag() != "?") return false;
    std::string s = n.Scalar();
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s == "true" || s == "false";
  }
  static std::string BooleanText(const YAML::Node& n) {
    std::string s = n.Scalar();
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
  }

  void CheckOptionName(const YAML::Node& key_node, const std::string& key, Target target) const {
    const std::string name = key_node.Scalar();
    if (name.empty() || name[0] == '-')
      Fail(key_node, key, "write option names without leading dashes (profiles, not --profiles)");
    for (char c : name) {
      if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '.' || c == '_'))
        Fail(key_node, key, "not an option name (letters, digits, '-', '.', '_')");
    }
    if (target == Target::kDriver && kReservedDriverOptions.count(name)) {
      Fail(key_node, key,
           "set by the campaign for every run (scenarios give the configuration, the campaign "
           "folder the output); remove it");
    }
  }

  std::vector<FixedOption> Options(const YAML::Node& map, const std::string& prefix,
                                   Target target) const {
    std::vector<FixedOption> out;
    if (!map) return out;
    if (map.IsNull()) return out;
    RequireMap(map, prefix);
    for (auto it = map.begin(); it != map.end(); ++it) {
      const std::string key = prefix + "." + it->first.Scalar();
      CheckOptionName(it->first, key, target);
      FixedOption o;
      o.name = it->first.Scalar();
      o.line = Line(it->first);
      const YAML::Node v = it->second;  // a copy: it-> is a temporary proxy
      if (IsBoolean(v)) {
        o.boolean = true;
        o.values.push_back(BooleanText(v));
      } else if (v.IsScalar()) {
        o.values.push_back(v.Scalar());
      } else if (v.IsSequence()) {
        if (v.size() == 0) Fail(v, key, "empty list (give at least one value or remove the key)");
        for (std::size_t k = 0; k < v.size(); ++k) {
          if (!v[k].IsScalar() || IsBoolean(v[k]))
            Fail(v[k], key, "a repeated option takes text or number values, got " + Kind(v[k]));
          o.values.push_back(v[k].Scalar());
        }
      } else {
        Fail(v, key, "expected a value (or a list for a repeatable option), got " + Kind(v));
      }
      out.push_back(std::move(o));
    }
    return out;
  }

  // `range: [first, last]` or `[first, last, step]`: whole numbers, inclusive.
  std::vector<std::string> Range(const YAML::Node& m, const std::string& key) const {
    CheckKeys(m, key + ".", {"range"});
    const YAML::Node r = m["range"];
    if (!r || !r.IsSequence() || (r.size() != 2 && r.size() != 3))
      Fail(m, key + ".range", "expected [first, last] or [first, last, step] (whole numbers)");
    const long long first = Integer(r[0], key + ".range", std::numeric_limits<long long>::min());
    const long long last = Integer(r[1], key + ".range", std::numeric_limits<long long>::min());
    const long long step = r.size() == 3 ? Integer(r[2], key + ".range", 1) : 1;
    if (last < first) Fail(r, key + ".range", "last is smaller than first: the range is empty");
    const long long n = (last - first) / step + 1;
    if (n > 10'000'000) Fail(r, key + ".range", "more than 10,000,000 values");
    std::vector<std::string> out;
    out.reserve(static_cast<std::size_t>(n));
    for (long long v = first; v <= last; v += step) out.push_back(std::to_string(v));
    return out;
  }

  std::vector<Axis> Axes(const YAML::Node& map, const std::string& prefix, Target target) const {
    std::vector<Axis> out;
    if (!map || map.IsNull()) return out;
    RequireMap(map, prefix);
    for (auto it = map.begin(); it != map.end(); ++it) {
      const std::string key = prefix + "." + it->first.Scalar();
      CheckOptionName(it->first, key, target);
      Axis a;
      a.target = target;
      a.name = it->first.Scalar();
      a.line = Line(it->first);
      const YAML::Node v = it->second;  // a copy: it-> is a temporary proxy
      if (v.IsMap()) {
        a.values = Range(v, key);
      } else if (v.IsSequence()) {
        if (v.size() == 0) Fail(v, key, "empty grid axis: give at least one value");
        std::size_t booleans = 0;
        for (std::size_t k = 0; k < v.size(); ++k) {
          if (!v[k].IsScalar())
            Fail(v[k], key, "grid values must be single values, got " + Kind(v[k]));
          if (IsBoolean(v[k])) {
            ++booleans;
            a.values.push_back(BooleanText(v[k]));
          } else {
            a.values.push_back(v[k].Scalar());
          }
        }
        if (booleans != 0 && booleans != v.size())
          Fail(v, key, "mixes true/false with other values");
        a.boolean = booleans != 0;
      } else {
        Fail(v, key,
             "expected a list of values ([6, 3]) or {range: [first, last]}, got " + Kind(v) +
                 " (a single value belongs under `" +
                 (target == Target::kDriver ? "driver" : "sumo") + ":`)");
      }
      std::set<std::string> seen;
      for (const auto& s : a.values) {
        if (!seen.insert(s).second) Fail(v, key, "value '" + s + "' appears twice");
      }
      out.push_back(std::move(a));
    }
    return out;
  }

  EgoSelection Egos(const YAML::Node& n, const std::string& key) const {
    EgoSelection e;
    e.line = Line(n);
    if (n.IsScalar() && n.Scalar() == "all") {
      e.kind = EgoSelection::Kind::kAll;
    } else if (n.IsScalar() && !n.Scalar().empty()) {
      e.kind = EgoSelection::Kind::kIds;
      e.ids.push_back(n.Scalar());
    } else if (n.IsSequence()) {
      if (n.size() == 0) Fail(n, key, "empty list of ego IDs");
      e.kind = EgoSelection::Kind::kIds;
      for (std::size_t k = 0; k < n.size(); ++k) e.ids.push_back(String(n[k], key));
    } else if (n.IsMap()) {
      CheckKeys(n, key + ".", {"type"});
      if (!n["type"]) Fail(n, key, "expected {type: VTYPE_ID}");
      e.kind = EgoSelection::Kind::kType;
      e.type = String(n["type"], key + ".type");
      if (e.type.empty()) Fail(n, key + ".type", "empty vehicle type");
    } else {
      Fail(n, key, "expected all, a list of vehicle IDs, or {type: VTYPE_ID}; got " + Kind(n));
    }
    return e;
  }

  std::vector<ScenarioEntry> Scenarios(const YAML::Node& n) const {
    if (!n)
      Fail(0, "scenarios", "missing (a list of scenario.cfg or .sumocfg files; globs allowed)");
    if (!n.IsSequence()) Fail(n, "scenarios", "expected a list of files, got " + Kind(n));
    if (n.size() == 0) Fail(n, "scenarios", "empty list: give at least one scenario");
    std::vector<ScenarioEntry> out;
    for (std::size_t k = 0; k < n.size(); ++k) {
      const std::string key = "scenarios[" + std::to_string(k) + "]";
      ScenarioEntry e;
      e.line = Line(n[k]);
      if (n[k].IsScalar()) {
        e.pattern = n[k].Scalar();
      } else if (n[k].IsMap()) {
        CheckKeys(n[k], key + ".", {"path", "name", "egos"});
        if (!n[k]["path"]) Fail(n[k], key + ".path", "missing");
        e.pattern = String(n[k]["path"], key + ".path");
        if (n[k]["name"]) e.name = String(n[k]["name"], key + ".name");
        if (n[k]["egos"]) e.egos = Egos(n[k]["egos"], key + ".egos");
      } else {
        Fail(n[k], key, "expected a path or {path: ..., name: ..., egos: ...}, got " + Kind(n[k]));
      }
      if (e.pattern.empty()) Fail(n[k], key, "empty path");
      out.push_back(std::move(e));
    }
    return out;
  }

 private:
  fs::path file_;
};

}  // namespace

CampaignSpec ParseCampaign(const std::string& text, const fs::path& file) {
  Reader r(file);
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    r.Fail(e.mark.line + 1, "", "YAML syntax error: " + e.msg);
  }
  if (!root.IsMap()) r.Fail(0, "", "expected a campaign (name: value lines), got " + r.Kind(root));
  r.CheckNoDuplicateKeys(root, "");
  r.CheckKeys(root, "",
              {"name", "output", "scenarios", "egos", "driver", "sumo", "grid", "repetitions",
               "limits", "slurm"});
  CampaignSpec c;
  c.file = fs::absolute(file).lexically_normal();
  c.base_dir = c.file.parent_path();
  c.name = root["name"] ? r.String(root["name"], "name") : c.file.stem().string();
  if (!root["output"])
    r.Fail(0, "output", "missing: the campaign folder, e.g. `output: out/my-campaign`");
  const std::string out = r.String(root["output"], "output");
  if (out.empty()) r.Fail(root["output"], "output", "empty folder name");
  c.output = (c.base_dir / out).lexically_normal();
  c.scenarios = r.Scenarios(root["scenarios"]);
  if (root["egos"]) c.egos = r.Egos(root["egos"], "egos");
  c.driver_options = r.Options(root["driver"], "driver", Target::kDriver);
  c.sumo_options = r.Options(root["sumo"], "sumo", Target::kSumo);
  if (const YAML::Node g = root["grid"]; g && !g.IsNull()) {
    r.RequireMap(g, "grid");
    r.CheckKeys(g, "grid.", {"driver", "sumo"});
    c.axes = r.Axes(g["driver"], "grid.driver", Target::kDriver);
    for (Axis& a : r.Axes(g["sumo"], "grid.sumo", Target::kSumo)) c.axes.push_back(std::move(a));
    if (c.axes.empty()) r.Fail(g, "grid", "empty grid: give at least one axis or remove `grid`");
  }
  // An option fixed and also on the grid would be given twice.
  for (const Axis& a : c.axes) {
    const auto& fixed = a.target == Target::kDriver ? c.driver_options : c.sumo_options;
    for (const FixedOption& o : fixed) {
      if (o.name == a.name) {
        r.Fail(a.line,
               std::string(a.target == Target::kDriver ? "grid.driver." : "grid.sumo.") + a.name,
               "also fixed at line " + std::to_string(o.line) + "; keep one of them");
      }
    }
  }
  if (root["repetitions"])
    c.repetitions = static_cast<int>(r.Integer(root["repetitions"], "repetitions", 1));
  if (const YAML::Node l = root["limits"]; l && !l.IsNull()) {
    r.RequireMap(l, "limits");
    r.CheckKeys(l, "limits.", {"time_s", "kill_after_s"});
    if (l["time_s"]) c.time_limit_s = r.Number(l["time_s"], "limits.time_s", 0.0);
    if (l["kill_after_s"]) c.kill_after_s = r.Number(l["kill_after_s"], "limits.kill_after_s", 0.0);
  }
  if (const YAML::Node s = root["slurm"]; s && !s.IsNull()) {
    r.RequireMap(s, "slurm");
    r.CheckKeys(s, "slurm.",
                {"time", "mem", "partition", "cpus_per_task", "throttle", "runs_per_task",
                 "max_array_size", "extra"});
    SlurmSettings& st = c.slurm;
    if (s["time"]) st.time = r.String(s["time"], "slurm.time");
    if (s["mem"]) st.mem = r.String(s["mem"], "slurm.mem");
    if (s["partition"]) st.partition = r.String(s["partition"], "slurm.partition");
    if (s["cpus_per_task"])
      st.cpus_per_task = static_cast<int>(r.Integer(s["cpus_per_task"], "slurm.cpus_per_task", 1));
    if (s["throttle"])
      st.throttle = static_cast<int>(r.Integer(s["throttle"], "slurm.throttle", 0));
    if (s["runs_per_task"])
      st.runs_per_task = static_cast<int>(r.Integer(s["runs_per_task"], "slurm.runs_per_task", 1));
    if (s["max_array_size"])
      st.max_array_size =
          static_cast<int>(r.Integer(s["max_array_size"], "slurm.max_array_size", 1));
    if (const YAML::Node e = s["extra"]) {
      if (!e.IsSequence()) r.Fail(e, "slurm.extra", "expected a list of sbatch options");
      for (std::size_t k = 0; k < e.size(); ++k) {
        const std::string line = r.String(e[k], "slurm.extra");
        if (line.rfind("--", 0) != 0 && line.rfind("-", 0) != 0)
          r.Fail(e[k], "slurm.extra", "'" + line + "' is not an sbatch option (--name=value)");
        st.extra.push_back(line);
      }
    }
  }
  return c;
}

CampaignSpec LoadCampaignFile(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw CampaignError(file.string() + ": cannot read the campaign file");
  std::stringstream text;
  text << in.rdbuf();
  return ParseCampaign(text.str(), file);
}

}  // namespace criticality::campaign
