#include "tools/campaign/plan_check.h"

#include <stdlib.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <sstream>

#include "tools/campaign/campaign_error.h"
#include "tools/campaign/process_pool.h"
#include "tools/campaign/scenario_files.h"

namespace fs = std::filesystem;

namespace criticality::campaign {
namespace {

std::string ReadText(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

bool IsNameChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '.' || c == '_';
}

// Where `name` occurs in `text` as a whole option name; npos when it does not.
std::size_t FindName(const std::string& text, const std::string& name) {
  for (std::size_t at = text.find(name); at != std::string::npos; at = text.find(name, at + 1)) {
    std::size_t before = at;
    while (before > 0 && text[before - 1] == '-') --before;  // "--name" counts as "name"
    const bool starts = before == 0 || !IsNameChar(text[before - 1]);
    const std::size_t end = at + name.size();
    // A trailing '.' ends a sentence, not a longer name ("step-length." vs "step-length.x").
    const bool ends = end >= text.size() || !IsNameChar(text[end]) ||
                      (text[end] == '.' && (end + 1 >= text.size() || !IsNameChar(text[end + 1])));
    if (starts && ends) return before;
  }
  return std::string::npos;
}

// A temporary folder for the checks' files, removed with it.
class Scratch {
 public:
  Scratch() {
    std::string tmpl = (fs::temp_directory_path() / "criticality-plan-check.XXXXXX").string();
    if (!mkdtemp(tmpl.data())) throw CampaignError("cannot create a temporary folder for checks");
    dir_ = tmpl;
  }
  ~Scratch() { RemoveTreeQuietly(); }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
  fs::path Next() {
    const fs::path d = dir_ / std::to_string(count_++);
    fs::create_directories(d);
    return d;
  }

 private:
  void RemoveTreeQuietly() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path dir_;
  std::size_t count_{0};
};

// One program run of a check, in its own folder; `done` gets its result and its output.
struct Job {
  std::vector<std::string> argv;
  fs::path dir;
  std::function<void(const ChildResult&, const std::string& out, const std::string& err)> done;
};

void RunJobs(std::vector<Job>& jobs, const CheckSettings& s) {
  ProcessPool pool(std::max(1, s.jobs), s.time_limit_s, 5.0);
  std::size_t next = 0;
  while (next < jobs.size() || pool.running() > 0) {
    while (!pool.full() && next < jobs.size()) {
      const Job& j = jobs[next];
      pool.Start({next, j.argv, j.dir, j.dir / "stdout.txt", j.dir / "stderr.txt"});
      ++next;
    }
    for (const ChildResult& c : pool.Wait(1.0)) {
      const Job& j = jobs[c.id];
      j.done(c, ReadText(j.dir / "stdout.txt"), ReadText(j.dir / "stderr.txt"));
    }
  }
}

// Errors, each once: the same complaint about the same key (a fixed option, a scenario) from
// many option sets is one line, with how many sets gave it.
class Errors {
 public:
  // `run` is the first run that gets the set (the lowest index of those that failed is shown).
  void Add(int line, const std::string& where, const std::string& what, std::size_t run,
           const std::string& run_text) {
    auto [it, fresh] = seen_.emplace(where + what, order_.size());
    if (fresh) {
      order_.push_back({line, where + what, run, run_text, 0});
      return;
    }
    Entry& e = order_[it->second];
    ++e.more;
    if (run < e.run) {
      e.run = run;
      e.run_text = run_text;
    }
  }
  // In the campaign file's order (checks finish in any order).
  void Into(std::vector<std::string>& out) {
    std::stable_sort(order_.begin(), order_.end(), [](const Entry& a, const Entry& b) {
      return a.line != b.line ? a.line < b.line : a.run < b.run;
    });
    for (const Entry& e : order_) {
      out.push_back(
          e.text + " (" + e.run_text +
          (e.more ? " and " + std::to_string(e.more) + " more option set" + (e.more == 1 ? "" : "s")
                  : "") +
          ")");
    }
  }

 private:
  struct Entry {
    int line;
    std::string text;
    std::size_t run;
    std::string run_text;
    std::size_t more;
  };
  std::map<std::string, std::size_t> seen_;
  std::vector<Entry> order_;
};

std::string Where(const CampaignSpec& spec, int line, const std::string& key) {
  return spec.file.string() + ":" + std::to_string(line) + ": " + key + ": ";
}

std::string ScenarioKey(const Scenario& sc) {
  return "scenarios[" + std::to_string(sc.entry) + "] (" + sc.rel_path + ")";
}

std::string RunText(const Plan& plan, const PlanRun& r) {
  return "run " + std::to_string(plan.IndexOf(r)) + ": " + plan.scenarios()[r.scenario].name +
         ", " + plan.Label(r);
}

// The options of `target` a run gives, as the campaign file names them.
std::vector<OptionSource> Sources(const Plan& plan, const PlanRun& r, Target target) {
  const CampaignSpec& spec = plan.spec();
  std::vector<OptionSource> out;
  const std::string prefix = target == Target::kDriver ? "driver." : "sumo.";
  for (const FixedOption& o : target == Target::kDriver ? spec.driver_options : spec.sumo_options) {
    std::string v;
    for (const std::string& x : o.values) v += (v.empty() ? "" : ", ") + x;
    out.push_back({o.name, v, prefix + o.name, o.line, false});
  }
  for (std::size_t k = 0; k < spec.axes.size(); ++k) {
    const Axis& a = spec.axes[k];
    if (a.target == target)
      out.push_back({a.name, a.values[r.value[k]], "grid." + prefix + a.name, a.line, true});
  }
  return out;
}

// An error of one option set: on the option it names, else on the scenario entry.
void AddError(const Plan& plan, const PlanRun& r, Target target, const std::string& program,
              const std::string& message, Errors& errors) {
  const std::vector<OptionSource> sources = Sources(plan, r, target);
  const Scenario& sc = plan.scenarios()[r.scenario];
  if (const OptionSource* o = NamedOption(message, sources)) {
    errors.Add(o->line,
               Where(plan.spec(), o->line, o->key) + (o->grid ? "'" + o->value + "': " : ""),
               program + " says: " + message, r.index, RunText(plan, r));
  } else {
    errors.Add(sc.line, Where(plan.spec(), sc.line, ScenarioKey(sc)), program + " says: " + message,
               r.index, RunText(plan, r));
  }
}

// The files a scenario needs before any program reads it: its SUMO configuration and the net,
// route and additional files that names.
bool CheckScenarioFiles(const Plan& plan, const Scenario& sc, Errors& errors, std::size_t* files) {
  const std::string where = Where(plan.spec(), sc.line, ScenarioKey(sc));
  const fs::path cfg = SumoConfigOf(sc);
  if (cfg.empty()) {
    errors.Add(sc.line, where, "names no SUMO configuration (a 'sumo-config = FILE' line)", 0,
               "every run");
    return false;
  }
  if (!fs::is_regular_file(cfg)) {
    errors.Add(sc.line, where, "its SUMO configuration " + cfg.string() + " does not exist", 0,
               "every run");
    return false;
  }
  ++*files;  // the files found: the line "N scenario files exist" counts only those
  bool ok = true;
  for (const char* key : {"net-file", "route-files", "additional-files"}) {
    for (const fs::path& f : SumoConfigFiles(cfg, key)) {
      if (fs::exists(f)) ++*files;
      if (!fs::exists(f)) {
        errors.Add(
            sc.line, where,
            cfg.filename().string() + " names " + key + " " + f.string() + ", which does not exist",
            0, "every run");
        ok = false;
      }
    }
  }
  return ok;
}

// The run of scenario `s` with the given values of the axes of `target` (the others at their
// first value).
PlanRun RunWith(const Plan& plan, std::size_t s, const std::vector<std::size_t>& axes,
                const std::vector<std::size_t>& values) {
  PlanRun r;
  r.scenario = s;
  r.value.assign(plan.axes().size(), 0);
  for (std::size_t k = 0; k < axes.size(); ++k) r.value[axes[k]] = values[k];
  r.index = plan.IndexOf(r);
  return r;
}

// The axes of one target and their sizes.
std::vector<std::size_t> AxesOf(const Plan& plan, Target target, std::vector<std::size_t>* sizes) {
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k < plan.axes().size(); ++k) {
    if (plan.axes()[k].target != target) continue;
    out.push_back(k);
    sizes->push_back(plan.axes()[k].values.size());
  }
  return out;
}

std::size_t Product(const std::vector<std::size_t>& sizes) {
  std::size_t n = 1;
  for (std::size_t k : sizes) n = n > 1000000000 / std::max<std::size_t>(k, 1) ? n : n * k;
  return n;
}

std::string DriverError(const ChildResult& c, const std::string& out, const std::string& err) {
  std::string line;
  std::istringstream in(err);
  for (std::string l; std::getline(in, l);) {
    const std::string prefix = "sumo-criticality: error: ";
    if (l.rfind(prefix, 0) == 0) line = l.substr(prefix.size());
  }
  if (!line.empty()) return line;
  if (const auto nl = err.find_last_not_of('\n'); nl != std::string::npos) {
    const std::string trimmed = err.substr(0, nl + 1);
    return trimmed.substr(trimmed.find_last_of('\n') + 1);
  }
  (void)out;
  return c.signal ? "killed by signal " + std::to_string(c.signal)
                  : "exit code " + std::to_string(c.exit_code) + " without a message";
}

void CheckDriver(const Plan& plan, const CheckSettings& s, const std::vector<bool>& usable,
                 Scratch& scratch, Errors& errors, PlanCheck& out) {
  std::vector<std::size_t> sizes;
  const std::vector<std::size_t> axes = AxesOf(plan, Target::kDriver, &sizes);
  const std::size_t per = Product(sizes);
  out.driver_sets = per * plan.scenarios().size();
  bool all = true;
  const std::vector<std::vector<std::size_t>> combos = OptionCombinations(
      sizes, std::max<std::size_t>(1, s.max_sets / std::max<std::size_t>(1, usable.size())), &all);
  std::vector<Job> jobs;
  for (std::size_t sc = 0; sc < plan.scenarios().size(); ++sc) {
    if (!usable[sc]) continue;
    for (const auto& values : combos) {
      const PlanRun r = RunWith(plan, sc, axes, values);
      Job j;
      j.dir = scratch.Next();
      j.argv = plan.Command(r, s.driver, "run.sqlite");
      j.argv.insert(j.argv.begin() + 1, "--check-options");
      j.done = [&plan, &errors, r](const ChildResult& c, const std::string& o,
                                   const std::string& e) {
        if (c.exit_code == 0 && c.signal == 0) return;
        AddError(plan, r, Target::kDriver, "sumo-criticality", DriverError(c, o, e), errors);
      };
      jobs.push_back(std::move(j));
    }
  }
  out.driver_checked = jobs.size();
  RunJobs(jobs, s);
  out.checked.push_back(std::to_string(out.driver_checked) + " of " +
                        std::to_string(out.driver_sets) +
                        " driver option sets through sumo-criticality --check-options" +
                        (all ? "" : " (each grid value at least once per scenario)"));
}

// The SUMO arguments of a run's command (after "--").
std::vector<std::string> SumoArgs(const Plan& plan, const PlanRun& r) {
  const std::vector<std::string> argv = plan.Command(r, "driver", "run.sqlite");
  const auto dashes = std::find(argv.begin(), argv.end(), "--");
  return dashes == argv.end() ? std::vector<std::string>{}
                              : std::vector<std::string>(dashes + 1, argv.end());
}

struct SumoSet {
  PlanRun run;
  fs::path cfg, dir;
};

void CheckSumo(const Plan& plan, const CheckSettings& s, const std::vector<bool>& usable,
               Scratch& scratch, Errors& errors, PlanCheck& out) {
  std::vector<std::size_t> sizes;
  const std::vector<std::size_t> axes = AxesOf(plan, Target::kSumo, &sizes);
  // Scenarios that run the same .sumocfg give SUMO the same sets.
  std::map<std::string, std::size_t> by_cfg;
  for (std::size_t sc = 0; sc < plan.scenarios().size(); ++sc) {
    if (usable[sc]) by_cfg.emplace(SumoConfigOf(plan.scenarios()[sc]).string(), sc);
  }
  out.sumo_sets = Product(sizes) * by_cfg.size();
  bool all = true;
  const auto combos = OptionCombinations(
      sizes, std::max<std::size_t>(1, s.max_sets / std::max<std::size_t>(1, by_cfg.size())), &all);
  std::vector<std::unique_ptr<SumoSet>> sets;
  std::vector<Job> save;
  for (const auto& [cfg, sc] : by_cfg) {
    for (const auto& values : combos) {
      auto set =
          std::make_unique<SumoSet>(SumoSet{RunWith(plan, sc, axes, values), cfg, scratch.Next()});
      Job j;
      j.dir = set->dir;
      j.argv = {s.sumo, "-c", cfg, "--no-step-log", "true", "--xml-validation", "never"};
      const auto args = SumoArgs(plan, set->run);
      j.argv.insert(j.argv.end(), args.begin(), args.end());
      j.argv.insert(j.argv.end(), {"--save-configuration", (set->dir / "saved.sumocfg").string()});
      SumoSet* p = set.get();
      j.done = [&plan, &errors, p](const ChildResult& c, const std::string& o,
                                   const std::string& e) {
        const std::string msg = SumoErrors(o + "\n" + e);
        if (c.exit_code == 0 && c.signal == 0 && msg.empty()) return;
        AddError(plan, p->run, Target::kSumo, "sumo",
                 msg.empty() ? "exit code " + std::to_string(c.exit_code) : msg, errors);
        p->dir.clear();  // no dry start for a set SUMO did not take
      };
      save.push_back(std::move(j));
      sets.push_back(std::move(set));
    }
  }
  RunJobs(save, s);
  // The dry start: the saved configuration without its outputs, ending where it begins.
  std::vector<Job> dry;
  for (const auto& set : sets) {
    if (set->dir.empty()) continue;
    std::string begin;
    {
      std::ofstream f(set->dir / "dry.sumocfg");
      f << WithoutOutputs(ReadText(set->dir / "saved.sumocfg"), &begin);
    }
    Job j;
    j.dir = set->dir;
    j.argv = {s.sumo, "-c", (set->dir / "dry.sumocfg").string(), "--end", begin};
    SumoSet* p = set.get();
    j.done = [&plan, &errors, p](const ChildResult& c, const std::string& o, const std::string& e) {
      const std::string msg = SumoErrors(o + "\n" + e);
      if (c.exit_code == 0 && c.signal == 0 && msg.empty()) return;
      AddError(plan, p->run, Target::kSumo, "sumo",
               msg.empty() ? "exit code " + std::to_string(c.exit_code) : msg, errors);
    };
    dry.push_back(std::move(j));
  }
  RunJobs(dry, s);
  out.sumo_checked = sets.size();
  out.checked.push_back(std::to_string(out.sumo_checked) + " of " + std::to_string(out.sumo_sets) +
                        " SUMO option sets through sumo (--save-configuration, then a dry start)" +
                        (all ? "" : " (each grid value at least once per SUMO configuration)"));
}

}  // namespace

std::vector<std::vector<std::size_t>> OptionCombinations(const std::vector<std::size_t>& sizes,
                                                         std::size_t limit, bool* all) {
  std::vector<std::vector<std::size_t>> out;
  const std::size_t total = Product(sizes);
  *all = total <= limit;
  if (*all) {
    for (std::size_t i = 0; i < total; ++i) {
      std::vector<std::size_t> v(sizes.size());
      std::size_t rest = i;
      for (std::size_t k = sizes.size(); k-- > 0;) {
        v[k] = rest % sizes[k];
        rest /= sizes[k];
      }
      out.push_back(std::move(v));
    }
    return out;
  }
  const std::size_t n = *std::max_element(sizes.begin(), sizes.end());
  for (std::size_t j = 0; j < n; ++j) {
    std::vector<std::size_t> v(sizes.size());
    for (std::size_t k = 0; k < sizes.size(); ++k) v[k] = j % sizes[k];
    out.push_back(std::move(v));
  }
  return out;
}

const OptionSource* NamedOption(const std::string& message,
                                const std::vector<OptionSource>& sources) {
  const OptionSource* best = nullptr;
  std::size_t best_at = std::string::npos;
  for (const OptionSource& o : sources) {
    const std::size_t at = FindName(message, o.name);
    // The earliest mention wins ("--warn-release 0.95: must not exceed --warn-threshold"); of
    // two at one place, the longer name.
    if (at != std::string::npos &&
        (at < best_at || (at == best_at && o.name.size() > best->name.size()))) {
      best = &o;
      best_at = at;
    }
  }
  return best;
}

std::string SumoErrors(const std::string& output) {
  std::string out;
  bool in_error = false;
  std::istringstream in(output);
  for (std::string l; std::getline(in, l);) {
    if (!l.empty() && l.back() == '\r') l.pop_back();
    if (l.rfind("Error: ", 0) == 0) {
      // SUMO's closing summary adds nothing to the error before it.
      const std::string text = l.substr(7);
      // The first error is the cause; those after it follow from it ("The parameter '0.1' is
      // not allowed in this context" after an unknown option name).
      in_error = out.empty();
      if (in_error) out = text;
    } else if (in_error && !l.empty() && l[0] == ' ') {
      out += " " + l.substr(l.find_first_not_of(' '));
    } else {
      in_error = false;
    }
  }
  return out;
}

std::string WithoutOutputs(const std::string& saved, std::string* begin) {
  *begin = "0";
  std::ostringstream out;
  std::istringstream in(saved);
  bool in_output = false;
  for (std::string l; std::getline(in, l);) {
    const std::size_t lt = l.find('<');
    std::string tag;
    if (lt != std::string::npos) {
      std::size_t e = lt + 1;
      while (e < l.size() && (IsNameChar(l[e]) || l[e] == '/')) ++e;
      tag = l.substr(lt + 1, e - lt - 1);
    }
    if (tag == "output") in_output = true;
    if (in_output) {
      if (tag == "/output") in_output = false;
      continue;
    }
    if (tag == "begin") {
      const std::size_t v = l.find("value=\"");
      if (v != std::string::npos) *begin = l.substr(v + 7, l.find('"', v + 7) - v - 7);
    }
    auto ends = [&](const char* suffix) {
      const std::string s(suffix);
      return tag.size() >= s.size() && tag.compare(tag.size() - s.size(), s.size(), s) == 0;
    };
    const bool writes = tag == "log" || tag == "message-log" || tag == "error-log" ||
                        tag.rfind("save-state.", 0) == 0 || tag == "save-configuration" ||
                        tag == "save-template" || ends("-output") || ends(".output") ||
                        (tag.rfind("device.", 0) == 0 && ends(".file"));
    if (writes || tag == "end") continue;
    out << l << "\n";
  }
  return out.str();
}

std::string FindSumo(const std::string& option, std::string& why) {
  auto executable = [](const fs::path& p) {
    std::error_code ec;
    return fs::is_regular_file(p, ec) && access(p.c_str(), X_OK) == 0;
  };
  if (!option.empty()) {
    if (executable(option)) return fs::absolute(option).string();
    why = "--sumo '" + option + "': not an executable file";
    return "";
  }
  if (const char* home = std::getenv("SUMO_HOME"); home && *home) {
    if (executable(fs::path(home) / "bin" / "sumo"))
      return (fs::path(home) / "bin" / "sumo").string();
  }
  if (const char* path = std::getenv("PATH")) {
    std::stringstream dirs(path);
    for (std::string d; std::getline(dirs, d, ':');) {
      if (!d.empty() && executable(fs::path(d) / "sumo")) return (fs::path(d) / "sumo").string();
    }
  }
  why = "no sumo found ($SUMO_HOME/bin, PATH; give --sumo PATH)";
  return "";
}

PlanCheck CheckPlan(const Plan& plan, const CheckSettings& s) {
  PlanCheck out;
  Errors errors;
  std::vector<bool> usable(plan.scenarios().size(), true);
  for (std::size_t k = 0; k < plan.scenarios().size(); ++k)
    usable[k] = CheckScenarioFiles(plan, plan.scenarios()[k], errors, &out.scenario_files);
  const std::size_t n = plan.scenarios().size();
  out.checked.push_back(std::to_string(out.scenario_files) + " scenario files exist (" +
                        std::to_string(n) + (n == 1 ? " scenario" : " scenarios") +
                        ": SUMO configurations, networks, routes, additional files)");
  // SUMO would look its XML schemas up on the web without SUMO_HOME (the driver sets it too).
  if (!std::getenv("SUMO_HOME") && fs::exists("/usr/share/sumo"))
    setenv("SUMO_HOME", "/usr/share/sumo", 0);
  Scratch scratch;
  if (s.driver.empty()) {
    out.unchecked.push_back("driver options: no driver to check them with");
  } else if (!s.driver_checks) {
    out.unchecked.push_back("driver option values: " + s.driver +
                            " has no --check-options (an older build); names checked against "
                            "its --help only");
  } else {
    CheckDriver(plan, s, usable, scratch, errors, out);
  }
  if (s.sumo.empty()) {
    out.unchecked.push_back("SUMO options: no sumo binary to check them with");
  } else {
    CheckSumo(plan, s, usable, scratch, errors, out);
  }
  errors.Into(out.errors);
  return out;
}

}  // namespace criticality::campaign
