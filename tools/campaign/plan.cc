#include "tools/campaign/plan.h"

#include <algorithm>
#include <cctype>
#include <cstdio>

#include "tools/campaign/campaign_error.h"

namespace criticality::campaign {
namespace {

constexpr std::size_t kMaxRuns = 1'000'000'000;

class Fnv1a {
 public:
  void Add(const std::string& s) {
    for (unsigned char c : s) {
      h_ ^= c;
      h_ *= 1099511628211ULL;
    }
    h_ ^= 0xff;  // separator, so that ("ab","c") differs from ("a","bc")
    h_ *= 1099511628211ULL;
  }
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_{14695981039346656037ULL};
};

std::string Flag(const std::string& name) { return (name.size() == 1 ? "-" : "--") + name; }

void AddOption(std::vector<std::string>& argv, Target target, const std::string& name,
               const std::string& value, bool boolean) {
  if (boolean && target == Target::kDriver) {
    if (value == "true") argv.push_back(Flag(name));  // a switch; false leaves it out
    return;
  }
  argv.push_back(Flag(name));
  argv.push_back(value);
}

}  // namespace

Plan::Plan(CampaignSpec spec) : spec_(std::move(spec)) {
  scenarios_ = ResolveScenarios(spec_);
  Init();
}

Plan::Plan(CampaignSpec spec, std::vector<Scenario> scenarios)
    : spec_(std::move(spec)), scenarios_(std::move(scenarios)) {
  Init();
}

void Plan::Init() {
  std::size_t n = scenarios_.size();
  auto multiply = [&](std::size_t k, const std::string& what) {
    if (k != 0 && n > kMaxRuns / k) {
      throw CampaignError(spec_.file.string() + ": " + what +
                          ": the plan would exceed 1,000,000,000 runs; split the campaign");
    }
    n *= k;
  };
  for (const Axis& a : spec_.axes) multiply(a.values.size(), "grid axis " + a.name);
  multiply(static_cast<std::size_t>(spec_.repetitions), "repetitions");
  size_ = n;

  Fnv1a h;
  h.Add("campaign-plan-v1");
  for (const Scenario& s : scenarios_) {
    h.Add(s.rel_path);
    h.Add(s.kind == ScenarioKind::kDriverConfig ? "cfg" : "sumocfg");
    h.Add(s.name);
    h.Add(s.has_egos ? std::to_string(static_cast<int>(s.egos.kind)) : "own");
    for (const std::string& id : s.egos.ids) h.Add(id);
  }
  for (const auto* list : {&spec_.driver_options, &spec_.sumo_options}) {
    h.Add(list == &spec_.driver_options ? "driver" : "sumo");
    for (const FixedOption& o : *list) {
      h.Add(o.name);
      for (const std::string& v : o.values) h.Add(v);
    }
  }
  for (const Axis& a : spec_.axes) {
    h.Add(a.target == Target::kDriver ? "axis-driver" : "axis-sumo");
    h.Add(a.name);
    for (const std::string& v : a.values) h.Add(v);
  }
  h.Add(std::to_string(spec_.repetitions));
  fingerprint_ = h.value();
}

std::string Plan::FingerprintHex() const {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(fingerprint_));
  return buf;
}

PlanRun Plan::Run(std::size_t index) const {
  PlanRun r;
  r.index = index;
  std::size_t rest = index;
  r.repetition = static_cast<int>(rest % static_cast<std::size_t>(spec_.repetitions));
  rest /= static_cast<std::size_t>(spec_.repetitions);
  r.value.resize(spec_.axes.size());
  for (std::size_t k = spec_.axes.size(); k-- > 0;) {
    const std::size_t m = spec_.axes[k].values.size();
    r.value[k] = rest % m;
    rest /= m;
  }
  r.scenario = rest;
  return r;
}

std::size_t Plan::IndexOf(const PlanRun& run) const {
  std::size_t i = run.scenario;
  for (std::size_t k = 0; k < spec_.axes.size(); ++k)
    i = i * spec_.axes[k].values.size() + run.value.at(k);
  return i * static_cast<std::size_t>(spec_.repetitions) + static_cast<std::size_t>(run.repetition);
}

std::string Plan::Identity(const PlanRun& run) const {
  const Scenario& s = scenarios_[run.scenario];
  std::vector<std::string> argv = Command(run, "", "");
  return RunIdentity(s.rel_path, run.repetition, argv);
}

std::string RunIdentity(const std::string& scenario, int repetition,
                        const std::vector<std::string>& argv) {
  // argv: DRIVER (--config|--sumo-config) FILE options --output OUT --no-progress [-- SUMO].
  std::vector<std::pair<std::string, std::string>> driver, sumo;
  auto is_flag = [](const std::string& a) {
    return a.size() >= 2 && a[0] == '-' &&
           (a[1] == '-' || std::isalpha(static_cast<unsigned char>(a[1])));
  };
  bool after = false;
  for (std::size_t i = 1; i < argv.size(); ++i) {
    const std::string& a = argv[i];
    if (a == "--" && !after) {
      after = true;
      continue;
    }
    if (!is_flag(a)) continue;  // a value without its option: not ours
    std::string name = a.substr(a[1] == '-' ? 2 : 1);
    const bool has_value = i + 1 < argv.size() && !is_flag(argv[i + 1]) && argv[i + 1] != "--";
    const std::string value = has_value ? argv[++i] : "";
    if (!after && (name == "config" || name == "sumo-config" || name == "c" || name == "output" ||
                   name == "no-progress"))
      continue;  // the scenario (given apart), the output and what every run gets
    (after ? sumo : driver).emplace_back(name, has_value ? name + "=" + value : name);
  }
  std::string id = "scenario=" + scenario + "\nrepetition=" + std::to_string(repetition);
  for (auto* list : {&driver, &sumo}) {
    std::stable_sort(list->begin(), list->end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });
    id += list == &driver ? "\ndriver:" : "\nsumo:";
    for (const auto& [name, token] : *list) id += " " + token;
  }
  return id;
}

std::vector<std::pair<std::string, std::string>> Plan::GridValues(const PlanRun& run) const {
  std::vector<std::pair<std::string, std::string>> out;
  out.reserve(spec_.axes.size());
  for (std::size_t k = 0; k < spec_.axes.size(); ++k)
    out.emplace_back(spec_.axes[k].name, spec_.axes[k].values[run.value[k]]);
  return out;
}

std::string Plan::Label(const PlanRun& run) const {
  std::string s;
  for (const auto& [name, value] : GridValues(run))
    s += (s.empty() ? "" : " ") + name + "=" + value;
  return s.empty() ? "-" : s;
}

std::vector<std::string> Plan::Command(const PlanRun& run, const std::string& driver,
                                       const std::string& output) const {
  const Scenario& s = scenarios_[run.scenario];
  std::vector<std::string> argv{driver};
  argv.push_back(s.kind == ScenarioKind::kDriverConfig ? "--config" : "--sumo-config");
  argv.push_back(s.path.string());
  if (s.has_egos) {
    if (s.egos.kind == EgoSelection::Kind::kAll) {
      argv.push_back("--all-vehicles");
    } else {
      for (const std::string& id : s.egos.ids) {
        argv.push_back("--ego");
        argv.push_back(id);
      }
    }
  }
  for (const FixedOption& o : spec_.driver_options) {
    for (const std::string& v : o.values) AddOption(argv, Target::kDriver, o.name, v, o.boolean);
  }
  for (std::size_t k = 0; k < spec_.axes.size(); ++k) {
    const Axis& a = spec_.axes[k];
    if (a.target == Target::kDriver)
      AddOption(argv, Target::kDriver, a.name, a.values[run.value[k]], a.boolean);
  }
  argv.insert(argv.end(), {"--output", output, "--no-progress"});
  std::vector<std::string> sumo;
  for (const FixedOption& o : spec_.sumo_options) {
    for (const std::string& v : o.values) AddOption(sumo, Target::kSumo, o.name, v, o.boolean);
  }
  for (std::size_t k = 0; k < spec_.axes.size(); ++k) {
    const Axis& a = spec_.axes[k];
    if (a.target == Target::kSumo)
      AddOption(sumo, Target::kSumo, a.name, a.values[run.value[k]], a.boolean);
  }
  if (!sumo.empty()) {
    argv.push_back("--");
    argv.insert(argv.end(), sumo.begin(), sumo.end());
  }
  return argv;
}

}  // namespace criticality::campaign
