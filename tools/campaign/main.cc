// criticality-campaign: parameter sweeps of sumo-criticality across SUMO scenarios, on one
// machine (a process pool) or on a Slurm cluster (job arrays); merge and report. See --help and
// tools/campaign/README.md.
#include <sched.h>
#include <unistd.h>

#include <boost/program_options.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "tools/campaign/campaign_error.h"
#include "tools/campaign/campaign_file.h"
#include "tools/campaign/campaign_folder.h"
#include "tools/campaign/driver_locator.h"
#include "tools/campaign/merge.h"
#include "tools/campaign/plan.h"
#include "tools/campaign/plan_check.h"
#include "tools/campaign/replan.h"
#include "tools/campaign/report.h"
#include "tools/campaign/run_campaign.h"
#include "tools/campaign/slurm_job.h"

namespace po = boost::program_options;
namespace fs = std::filesystem;
using nlohmann::json;
using namespace criticality::campaign;

namespace {

constexpr int kExitOk = 0;
constexpr int kExitInternal = 1;
constexpr int kExitBadInput = 2;
constexpr int kExitRunsFailed = 3;
constexpr int kExitInterrupted = 130;

// A command that fails still ends its standard output with a JSON summary (README: the last
// stdout line), as the driver does: its status, exit code and error.
int FailedSummary(int code, const std::string& error) {
  std::cout << json{{"status", "failed"}, {"exit_code", code}, {"error", error}}.dump()
            << std::endl;
  return code;
}

const char* kUsage =
    "criticality-campaign: parameter sweeps of sumo-criticality across SUMO scenarios, on this "
    "machine or on a Slurm cluster.\n\n"
    "Usage:\n"
    "  criticality-campaign plan FILE [--list]           the runs, and proof each can start\n"
    "  criticality-campaign run FILE [-j N]               run (resuming) through a process pool\n"
    "  criticality-campaign slurm FILE [--submit [--wait]]  write (and submit) a job array\n"
    "  criticality-campaign merge DIR                     complete runs -> DIR/campaign.sqlite\n"
    "  criticality-campaign report DIR                    tables, figures, DIR/report/index.html\n"
    "  criticality-campaign COMMAND --help                the options of a command\n\n"
    "FILE is a campaign file (YAML; tools/campaign/README.md, scenarios/campaigns/example.yaml);\n"
    "DIR its output folder. Each run is `sumo-criticality ... --output run.sqlite --no-progress`,\n"
    "found with --driver, $SUMO_CRITICALITY_DRIVER, next to this program, or on PATH.\n"
    "The last line of standard output is a JSON summary. Exit codes: 0 done, 1 internal error,\n"
    "2 bad campaign file, options or folder, or a run that could not start (plan's checks),\n"
    "3 some runs failed (recorded; the others went on),\n"
    "130 interrupted (SIGINT/SIGTERM: running runs are left to be redone).\n";

int CpuCount() {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  return static_cast<int>(std::max(1L, sysconf(_SC_NPROCESSORS_ONLN)));
}

std::string SelfPath() {
  std::error_code ec;
  const fs::path p = fs::read_symlink("/proc/self/exe", ec);
  return ec ? "criticality-campaign" : p.string();
}

// Parses one subcommand's options; returns false when --help was printed.
bool Parse(const std::vector<std::string>& args, po::options_description& opts,
           const std::string& positional, po::variables_map& vm, const std::string& usage) {
  opts.add_options()("help,h", "show this help");
  po::positional_options_description pos;
  if (!positional.empty()) pos.add(positional.c_str(), 1);
  try {
    po::store(po::command_line_parser(args)
                  .options(opts)
                  .positional(pos)
                  .style(po::command_line_style::default_style &
                         ~po::command_line_style::allow_guessing)  // whole names only
                  .run(),
              vm);
    if (vm.count("help")) {
      std::cout << usage << "\n" << opts << "\n";
      return false;
    }
    po::notify(vm);
  } catch (const po::error& e) {
    throw CampaignError(std::string(e.what()) + " (see --help)");
  }
  if (!positional.empty() && !vm.count(positional))
    throw CampaignError("give the campaign " +
                        std::string(positional == "file" ? "file" : "folder") + " (see --help)");
  return true;
}

Plan LoadPlan(const std::string& file, const std::string& output) {
  CampaignSpec spec = LoadCampaignFile(file);
  if (!output.empty()) spec.output = fs::absolute(output).lexically_normal();
  return Plan(std::move(spec));
}

// Checks the campaign's driver options against the driver's --help; whether the driver can
// check values too (--check-options).
bool CheckOptions(const Plan& plan, const std::string& driver) {
  const std::set<std::string> names = DriverOptionNames(driver);
  CheckDriverOptions(plan.spec(), names);
  return names.count("check-options") > 0;
}

// How `plan` (and `run`, `slurm` unless --no-check) proves that the runs can start.
struct CheckChoice {
  std::string sumo;
  std::size_t max_sets{200};
  int jobs{1};
  bool skip{false};
};

void AddCheckOptions(po::options_description& o, CheckChoice& c) {
  o.add_options()("sumo", po::value(&c.sumo),
                  "sumo binary for checking the SUMO options (default: $SUMO_HOME/bin/sumo, "
                  "then PATH)")(
      "check-sets", po::value(&c.max_sets)->default_value(c.max_sets),
      "check every distinct option set up to this many per program; beyond, each grid value "
      "at least once per scenario");
}

// Runs the checks (plan_check.h), printing what was checked to `log`; prints each error and
// returns false when a run could not start.
bool ProveRunsStart(const Plan& plan, const std::string& driver, bool driver_checks,
                    const CheckChoice& c, std::ostream& log, json* summary) {
  CheckSettings s;
  s.driver = driver;
  s.driver_checks = driver_checks;
  std::string why;
  s.sumo = FindSumo(c.sumo, why);
  if (s.sumo.empty() && !c.sumo.empty()) throw CampaignError(why);
  s.jobs = c.jobs;
  s.max_sets = c.max_sets;
  const PlanCheck check = CheckPlan(plan, s);
  for (const std::string& l : check.checked) log << "checked: " << l << "\n";
  for (const std::string& l : check.unchecked) log << "not checked: " << l << "\n";
  if (s.sumo.empty()) log << "  (" << why << ")\n";
  for (const std::string& e : check.errors)
    std::cerr << "criticality-campaign: error: " << e << "\n";
  if (summary) {
    (*summary)["check"] = {{"errors", check.errors.size()},
                           {"driver_sets", check.driver_sets},
                           {"driver_checked", check.driver_checked},
                           {"sumo_sets", check.sumo_sets},
                           {"sumo_checked", check.sumo_checked},
                           {"scenario_files", check.scenario_files},
                           {"unchecked", check.unchecked}};
  }
  return check.errors.empty();
}

std::string Joined(const std::vector<std::string>& argv) {
  std::string s;
  for (const std::string& a : argv) {
    const bool quote = a.empty() || a.find_first_of(" \t'\"$") != std::string::npos;
    s += (s.empty() ? "" : " ") + (quote ? "'" + a + "'" : a);
  }
  return s;
}

// A folder of this very plan: how far its runs are, and what `run` would do with them.
json FolderState(const Plan& plan, std::ostream* out) {
  const CampaignFolder folder = CampaignFolder::Layout(plan.spec().output, plan.size());
  std::size_t complete = 0, failed = 0, partial = 0;
  for (std::size_t i = 0; i < plan.size(); ++i) {
    if (folder.IsComplete(i)) {
      ++complete;
      failed += IsFailedRecord(folder.RunDir(i)) ? 1 : 0;
    } else if (fs::exists(folder.PartialDir(i))) {
      ++partial;
    }
  }
  const std::size_t missing = plan.size() - complete - partial;
  *out << "folder: " << complete << " of " << plan.size() << " runs complete";
  if (failed) *out << " (" << failed << " failed: `run --retry-failed` redoes them)";
  *out << ", " << partial << " half done (`run` redoes them), " << missing << " not started\n";
  return {{"complete", complete}, {"failed", failed}, {"partial", partial}, {"missing", missing}};
}

int CmdPlan(const std::vector<std::string>& args) {
  std::string file, output, driver_opt;
  int show = 5;
  bool list = false;
  CheckChoice check;
  check.jobs = CpuCount();
  po::options_description o("plan options");
  o.add_options()("file", po::value(&file), "campaign file")(
      "output,o", po::value(&output), "campaign folder (default: the file's `output`)")(
      "show", po::value(&show)->default_value(show), "print the first N runs with their commands")(
      "list", po::bool_switch(&list), "print every run: index, scenario, parameters, repetition")(
      "driver", po::value(&driver_opt), "sumo-criticality to check the options with")(
      "jobs,j", po::value(&check.jobs)->default_value(check.jobs), "checks at once")(
      "no-check", po::bool_switch(&check.skip),
      "only the campaign file: no driver or SUMO run to check the options");
  AddCheckOptions(o, check);
  po::variables_map vm;
  if (!Parse(args, o, "file", vm,
             "Usage: criticality-campaign plan FILE [--list]\n"
             "Lists the runs and proves that they can start: every scenario's files exist,\n"
             "every driver option set passes sumo-criticality --check-options, every SUMO option\n"
             "set passes SUMO (--save-configuration, then a dry start). Exit code 2 with one\n"
             "line per error (file, line, key) when a run could not start."))
    return 0;
  const Plan plan = LoadPlan(file, output);
  std::string driver;
  std::string checked = "not checked: ";
  bool driver_checks = false, found = false;
  try {
    driver = FindDriver(driver_opt);
    found = true;
    driver_checks = CheckOptions(plan, driver);
    checked = "driver option names checked against " + driver + " --help";
  } catch (const CampaignError& e) {
    if (found) throw;  // found, and an option is wrong
    checked += e.what();
    driver = "sumo-criticality";
  }
  json j{{"runs", plan.size()},
         {"scenarios", plan.scenarios().size()},
         {"repetitions", plan.spec().repetitions},
         {"fingerprint", plan.FingerprintHex()},
         {"output", plan.spec().output.string()}};
  std::ostringstream log;
  const bool can_start =
      check.skip || ProveRunsStart(plan, found ? driver : "", driver_checks, check, log, &j);
  std::ostringstream shape;
  shape << plan.scenarios().size() << " scenario" << (plan.scenarios().size() == 1 ? "" : "s");
  for (const Axis& a : plan.axes()) shape << " x " << a.values.size() << " " << a.name;
  shape << " x " << plan.spec().repetitions << " repetition"
        << (plan.spec().repetitions == 1 ? "" : "s");
  std::cout << "campaign " << plan.spec().name << ": " << plan.size() << " runs (" << shape.str()
            << ")\n"
            << "output: " << plan.spec().output.string() << "\n"
            << checked << "\n"
            << (check.skip ? "not checked: option values, SUMO options (--no-check)\n" : log.str());
  if (list) {
    std::cout << "index\tscenario\tparameters\trepetition\n";
    for (std::size_t i = 0; i < plan.size(); ++i) {
      const PlanRun r = plan.Run(i);
      std::cout << i << '\t' << plan.scenarios()[r.scenario].name << '\t' << plan.Label(r) << '\t'
                << r.repetition << '\n';
    }
  } else {
    const std::size_t n =
        std::min<std::size_t>(plan.size(), static_cast<std::size_t>(std::max(0, show)));
    if (n) std::cout << "first " << n << " runs:\n";
    for (std::size_t i = 0; i < n; ++i) {
      const PlanRun r = plan.Run(i);
      std::cout << "  run " << i << ": " << plan.scenarios()[r.scenario].name << ", "
                << plan.Label(r)
                << (plan.spec().repetitions > 1 ? ", repetition " + std::to_string(r.repetition)
                                                : "")
                << "\n    " << Joined(plan.Command(r, driver, "run.sqlite")) << "\n";
    }
  }
  j["axes"] = json::object();
  for (const Axis& a : plan.axes()) j["axes"][a.name] = a.values.size();
  j["can_start"] = can_start;
  // A folder started with an earlier version of the file: what `run` would do with its runs.
  if (fs::exists(plan.spec().output / "campaign.json")) {
    const PlanChanges changes = CompareWithFolder(plan.spec().output, plan);
    if (changes.changed) {
      std::cout << changes.Describe()
                << (changes.superseded.empty() ? ""
                                               : "(`run` needs --replan to move the superseded "
                                                 "runs aside)\n");
      j["folder"] = {{"kept", changes.kept.size()},
                     {"redone", changes.redone.size()},
                     {"superseded", changes.superseded.size()}};
    } else {
      j["folder"] = FolderState(plan, &std::cout);
    }
  }
  std::cout << j.dump() << std::endl;
  return can_start ? kExitOk : kExitBadInput;
}

void ParseRange(const std::string& text, std::size_t& first, std::size_t& last) {
  const auto dash = text.find('-');
  try {
    std::size_t used = 0;
    if (dash == std::string::npos) {
      first = last = std::stoull(text, &used);
      if (used != text.size()) throw std::invalid_argument(text);
    } else {
      first = std::stoull(text.substr(0, dash), &used);
      if (used != dash) throw std::invalid_argument(text);
      const std::string b = text.substr(dash + 1);
      last = std::stoull(b, &used);
      if (used != b.size()) throw std::invalid_argument(text);
    }
  } catch (const std::exception&) {
    throw CampaignError("--runs '" + text + "': expected FIRST-LAST or INDEX (run indices)");
  }
  if (last < first) throw CampaignError("--runs '" + text + "': LAST is smaller than FIRST");
}

int CmdRun(const std::vector<std::string>& args) {
  std::string file, output, driver_opt, runs;
  int jobs = CpuCount();
  double time_limit = -1.0, log_every = 30.0;
  bool retry = false, no_progress = false, replan = false;
  CheckChoice check;
  po::options_description o("run options");
  o.add_options()("file", po::value(&file), "campaign file")(
      "jobs,j", po::value(&jobs)->default_value(jobs), "runs at once (default: the cores)")(
      "runs", po::value(&runs), "only these runs: FIRST-LAST or INDEX (a Slurm task's share)")(
      "retry-failed", po::bool_switch(&retry), "redo complete runs whose status is not ok")(
      "replan", po::bool_switch(&replan),
      "the campaign file changed and drops successful runs of the folder: move them to "
      "OUT/superseded/ and go on (without it the run stops and lists them)")(
      "time-limit", po::value(&time_limit),
      "seconds per run, then SIGTERM and SIGKILL (default: the file's limits.time_s)")(
      "output,o", po::value(&output), "campaign folder (default: the file's `output`)")(
      "driver", po::value(&driver_opt), "sumo-criticality to run")(
      "no-progress", po::bool_switch(&no_progress), "no progress output")(
      "log-every", po::value(&log_every)->default_value(log_every),
      "seconds between progress lines when stderr is not a terminal")(
      "no-check", po::bool_switch(&check.skip),
      "start the runs without first checking their options through the driver and SUMO (as "
      "`plan` does; Slurm tasks, whose script `slurm` wrote after checking)");
  AddCheckOptions(o, check);
  po::variables_map vm;
  if (!Parse(args, o, "file", vm, "Usage: criticality-campaign run FILE [-j N] [--runs A-B]"))
    return 0;
  if (jobs < 1) throw CampaignError("--jobs must be at least 1");
  const Plan plan = LoadPlan(file, output);
  RunOptions ro;
  ro.jobs = jobs;
  if (!runs.empty()) ParseRange(runs, ro.first, ro.last);
  ro.retry_failed = retry;
  ro.replan = replan;
  ro.driver = FindDriver(driver_opt);
  const bool driver_checks = CheckOptions(plan, ro.driver);
  check.jobs = jobs;
  if (!check.skip && !ProveRunsStart(plan, ro.driver, driver_checks, check, std::cerr, nullptr))
    return FailedSummary(kExitBadInput, "the runs cannot start (the errors above); nothing ran");
  ro.time_limit_s = time_limit >= 0 ? time_limit : plan.spec().time_limit_s;
  ro.kill_after_s = plan.spec().kill_after_s;
  ro.progress = no_progress ? nullptr : stderr;
  ro.progress_terminal = isatty(2);
  ro.log_every_s = log_every;
  const RunTotals t = RunCampaign(plan, plan.spec().output, ro);
  json j{{"runs", t.in_range},
         {"complete_before", t.done_before},
         {"ok", t.ok},
         {"failed", t.failed},
         {"failed_before", t.failed_before},
         {"remaining", t.remaining},
         {"interrupted", t.interrupted},
         {"wall_s", t.wall_s},
         {"max_rss_kb", t.max_rss_kb},
         {"cpu_s", t.cpu_s},
         {"output", plan.spec().output.string()}};
  if (t.failed_before > 0) {
    std::cerr << "criticality-campaign: " << t.failed_before
              << " run(s) of the folder failed before and were not run again; "
                 "`run --retry-failed` redoes them\n";
  }
  if (t.stopped_by_signal) {
    std::cerr << "criticality-campaign: interrupted; " << t.interrupted
              << " run(s) stopped and left to redo: the same `run` command resumes\n";
  }
  std::cout << j.dump() << std::endl;
  if (t.stopped_by_signal) return kExitInterrupted;
  return t.failed + t.failed_before > 0 ? kExitRunsFailed : kExitOk;
}

int CmdSlurm(const std::vector<std::string>& args) {
  std::string file, output, driver_opt;
  bool submit = false, wait = false, replan = false;
  double poll = 2.0, time_limit = -1.0;
  CheckChoice check;
  check.jobs = CpuCount();
  po::options_description o("slurm options");
  o.add_options()("file", po::value(&file), "campaign file")("submit", po::bool_switch(&submit),
                                                             "submit the script with sbatch")(
      "wait", po::bool_switch(&wait), "with --submit: wait until the job has left the queue")(
      "replan", po::bool_switch(&replan),
      "the campaign file changed and drops successful runs of the folder: move them aside "
      "(see run --help)")("poll", po::value(&poll)->default_value(poll),
                          "seconds between squeue polls (--wait)")(
      "time-limit", po::value(&time_limit), "seconds per run (default: limits.time_s)")(
      "output,o", po::value(&output), "campaign folder (default: the file's `output`)")(
      "driver", po::value(&driver_opt), "sumo-criticality the tasks run")(
      "no-check", po::bool_switch(&check.skip),
      "write the script without first checking the options through the driver and SUMO");
  AddCheckOptions(o, check);
  po::variables_map vm;
  if (!Parse(
          args, o, "file", vm,
          "Usage: criticality-campaign slurm FILE [--submit [--wait]]\n"
          "Writes OUT/slurm/campaign.sbatch (array size, %throttle, time, memory, CPUs from the\n"
          "file's `slurm:` section); task logs go to OUT/slurm/logs/."))
    return 0;
  if (wait && !submit) throw CampaignError("--wait needs --submit");
  const Plan plan = LoadPlan(file, output);
  const std::string driver = FindDriver(driver_opt);
  const bool driver_checks = CheckOptions(plan, driver);
  if (!check.skip && !ProveRunsStart(plan, driver, driver_checks, check, std::cerr, nullptr))
    return FailedSummary(kExitBadInput, "the runs cannot start (the errors above); no script");
  const CampaignFolder folder = CampaignFolder::Prepare(plan.spec().output, plan, replan);
  if (!folder.changes().empty()) std::cerr << "criticality-campaign: " << folder.changes();
  const SlurmJob job = MakeSlurmJob(plan, folder, SelfPath(), driver,
                                    time_limit >= 0 ? time_limit : plan.spec().time_limit_s);
  const fs::path dir = folder.dir() / "slurm";
  fs::create_directories(dir / "logs");
  const fs::path script = dir / "campaign.sbatch";
  {
    std::ofstream out(script);
    out << job.script;
    if (!out) throw CampaignError("cannot write '" + script.string() + "'");
  }
  fs::permissions(script, fs::perms::owner_exec, fs::perm_options::add);
  std::cerr << "criticality-campaign: wrote " << script.string() << " (" << job.tasks
            << " array tasks, " << job.runs_per_task << " run"
            << (job.runs_per_task == 1 ? "" : "s") << " each)\n";
  if (!job.time_warning.empty())
    std::cerr << "criticality-campaign: warning: " << job.time_warning << "\n";
  json j{{"script", script.string()},
         {"time_warning", job.time_warning},
         {"tasks", job.tasks},
         {"runs_per_task", job.runs_per_task},
         {"runs", plan.size()}};
  if (submit) {
    const std::string id = SubmitSlurmJob(script);
    std::cerr << "criticality-campaign: submitted job " << id << "\n";
    j["job_id"] = id;
    if (wait) {
      WaitForSlurmJob(id, poll);
      std::size_t complete = 0;
      for (std::size_t i = 0; i < folder.runs(); ++i) complete += folder.IsComplete(i) ? 1 : 0;
      j["complete"] = complete;
      std::cerr << "criticality-campaign: job " << id << " has left the queue; " << complete << "/"
                << folder.runs() << " runs complete\n";
    }
  }
  std::cout << j.dump() << std::endl;
  return kExitOk;
}

int CmdMerge(const std::vector<std::string>& args) {
  std::string dir;
  po::options_description o("merge options");
  o.add_options()("dir", po::value(&dir), "campaign folder");
  po::variables_map vm;
  if (!Parse(args, o, "dir", vm, "Usage: criticality-campaign merge DIR")) return 0;
  const CampaignFolder folder = CampaignFolder::Open(dir);
  const MergeTotals t = MergeCampaign(folder);
  for (const std::string& u : t.unreadable)
    std::cerr << "criticality-campaign: warning: " << u << "\n";
  std::cerr << "criticality-campaign: " << t.complete << "/" << t.runs << " runs complete; merged "
            << t.merged << ", unchanged " << t.unchanged << ", removed " << t.removed << " -> "
            << t.database.string() << "\n";
  json j{{"runs", t.runs},
         {"complete", t.complete},
         {"merged", t.merged},
         {"unchanged", t.unchanged},
         {"removed", t.removed},
         {"incomplete", t.incomplete},
         {"tables", t.tables},
         {"wall_s", t.wall_s},
         {"database", t.database.string()},
         {"unreadable", t.unreadable.size()}};
  std::cout << j.dump() << std::endl;
  return kExitOk;
}

int CmdReport(const std::vector<std::string>& args) {
  std::string dir;
  ReportOptions ro;
  bool no_plots = false;
  std::string script;
  po::options_description o("report options");
  o.add_options()("dir", po::value(&dir), "campaign folder")(
      "grace", po::value(&ro.grace_s)->default_value(ro.grace_s),
      "seconds after a warning's end within which a collision, overlap, pass-through or hard "
      "braking of its ego makes it a true alarm")(
      "horizon", po::value(&ro.default_horizon_s)->default_value(ro.default_horizon_s),
      "reliability diagram: prediction horizon (s) for runs whose plan does not set --horizon")(
      "min-collisions",
      po::value(&ro.reliability_min_collisions)->default_value(ro.reliability_min_collisions),
      "fewest egos that collided for a reliability diagram")("no-plots", po::bool_switch(&no_plots),
                                                             "tables only")(
      "python", po::value(&ro.python),
      "Python 3 with matplotlib (default: $CRIT_PYTHON, /usr/bin/python3, python3)")(
      "script", po::value(&script), "figure script (default: tools/campaign/campaign_report.py)")(
      "scene-pictures", po::value(&ro.scene_pictures)->default_value(ro.scene_pictures),
      "draw the scene of at most this many warnings (0: none), linked from the warning table")(
      "bench", po::value(&ro.bench),
      "criticality-bench that replays a warning's scene for its hypotheses (default: "
      "$CRIT_BENCH, the build tree next to this program, PATH)");
  po::variables_map vm;
  if (!Parse(
          args, o, "dir", vm,
          "Usage: criticality-campaign report DIR\n"
          "Merges first, then writes DIR/report/: summary.md, CSV tables, figures and index.html."))
    return 0;
  ro.plots = !no_plots;
  ro.script = script;
  const CampaignFolder folder = CampaignFolder::Open(dir);
  const MergeTotals m = MergeCampaign(folder);
  for (const std::string& u : m.unreadable)
    std::cerr << "criticality-campaign: warning: " << u << "\n";
  const ReportResult r = MakeReport(folder, ro);
  for (const std::string& n : r.notes) std::cerr << "criticality-campaign: note: " << n << "\n";
  if (!r.figures_missing.empty())
    std::cerr << "criticality-campaign: no figures: " << r.figures_missing << "\n";
  std::cerr << "criticality-campaign: report in " << r.dir.string() << "/"
            << (r.figures ? "index.html" : "summary.md") << "\n";
  json j{{"report", r.dir.string()}, {"files", r.files},       {"figures", r.figures},
         {"notes", r.notes.size()},  {"complete", m.complete}, {"runs", m.runs}};
  if (!r.figures_missing.empty()) j["figures_missing"] = r.figures_missing;
  std::cout << j.dump() << std::endl;
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    std::cout << kUsage;
    return args.empty() ? kExitBadInput : kExitOk;
  }
  const std::string cmd = args[0];
  args.erase(args.begin());
  try {
    if (cmd == "plan") return CmdPlan(args);
    if (cmd == "run") return CmdRun(args);
    if (cmd == "slurm") return CmdSlurm(args);
    if (cmd == "merge") return CmdMerge(args);
    if (cmd == "report") return CmdReport(args);
    const std::string error =
        "unknown command '" + cmd + "' (plan, run, slurm, merge, report; see --help)";
    std::cerr << "criticality-campaign: error: " << error << "\n";
    return FailedSummary(kExitBadInput, error);
  } catch (const CampaignError& e) {
    std::cerr << "criticality-campaign: error: " << e.what() << "\n";
    return FailedSummary(kExitBadInput, e.what());
  } catch (const std::exception& e) {
    std::cerr << "criticality-campaign: internal error: " << e.what() << "\n";
    return FailedSummary(kExitInternal, std::string("internal error: ") + e.what());
  }
}
