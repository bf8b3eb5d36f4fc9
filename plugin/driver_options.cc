#include "plugin/driver_options.h"

#include <boost/program_options.hpp>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>

namespace po = boost::program_options;
namespace fs = std::filesystem;

namespace criticality::plugin {
namespace {

// True when SUMO has an option of this name (asked from the sumo binary only on this error
// path: `sumo --save-template` lists every option).
bool SumoKnowsOption(const std::string& name) {
  if (name.empty()) return false;
  std::FILE* p = popen("sumo --save-template /dev/stdout 2>/dev/null", "r");
  if (!p) return false;
  std::string text;
  char buf[4096];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) text.append(buf, n);
  pclose(p);
  return text.find("<" + name + " value=") != std::string::npos;
}

// The option a Params field is set by, for messages in the user's terms.
std::string WithOptionNames(std::string msg) {
  const std::pair<const char*, const char*> names[] = {
      {"params.horizon_s", "--horizon"},
      {"params.step_s", "--step"},
      {"params.profiles", "--profiles"},
      {"params.own_lane_samples", "--own-lane-samples"},
      {"params.neighbour_lane_samples", "--neighbour-lane-samples"},
      {"options.threads", "--threads"}};
  for (const auto& [field, option] : names) {
    for (size_t at = msg.find(field); at != std::string::npos; at = msg.find(field, at)) {
      msg.replace(at, std::strlen(field), option);
    }
  }
  return msg;
}

// Checks a config file line by line, so that an error names the file and the line.
void CheckConfigFile(const std::string& path, const po::options_description& all) {
  std::ifstream in(path);
  if (!in) throw std::invalid_argument("--config '" + path + "': cannot read the file");
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::string where = path + ":" + std::to_string(number) + ": ";
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    const auto eq = line.find('=');
    if (eq == std::string::npos)
      throw std::invalid_argument(where + "expected 'name = value', got '" + line + "'");
    std::string name = line.substr(first, eq - first);
    name.erase(name.find_last_not_of(" \t") + 1);
    if (!all.find_nothrow(name, false)) {
      throw std::invalid_argument(where + "unknown option '" + name + "'" +
                                  (SumoKnowsOption(name)
                                       ? " (a SUMO option: put it in the .sumocfg file)"
                                       : " (see --help)"));
    }
    std::istringstream one(line + "\n");
    po::variables_map scratch;
    try {
      po::store(po::parse_config_file(one, all), scratch);
    } catch (const po::error& e) {
      throw std::invalid_argument(where + e.what());
    }
  }
}

}  // namespace

double WarnValue(WarnOn on, const Result& r) {
  switch (on) {
    case WarnOn::kPCollision:
      return r.p_collision;
    case WarnOn::kPReference:
      return r.p_reference;
    case WarnOn::kUnavoidability:
      return r.unavoidability;
  }
  return r.p_collision;
}

std::string WarnOnName(WarnOn on) {
  switch (on) {
    case WarnOn::kPCollision:
      return "p_collision";
    case WarnOn::kPReference:
      return "p_reference";
    case WarnOn::kUnavoidability:
      return "unavoidability";
  }
  return "?";
}

std::string ActName(Act act) {
  switch (act) {
    case Act::kNone:
      return "none";
    case Act::kWarn:
      return "warn";
    case Act::kBrake:
      return "brake";
  }
  return "?";
}

ParseOutcome ParseDriverOptions(int argc, const char* const* argv) {
  ParseOutcome out;
  DriverOptions& o = out.options;
  // Everything after "--" goes to SUMO untouched.
  std::vector<const char*> own{argv[0]};
  int i = 1;
  for (; i < argc && std::string(argv[i]) != "--"; ++i) own.push_back(argv[i]);
  for (++i; i < argc; ++i) o.sumo_args.push_back(argv[i]);
  for (int k = 0; k < argc; ++k) o.command_line += (k ? " " : "") + std::string(argv[k]);

  std::string config, act = "warn", backend = "cpu", expect;  // expect: see DriverOptions
  std::string warn_on = "p_collision";
  bool no_lateral_controller = false, no_road_model = false, no_car_following = false;
  std::vector<std::string> events;
  bool no_progress = false, no_shortcut = false;
  po::options_description generic("General");
  generic.add_options()("help,h", "show this help and exit")(
      "version", "show the version (and the SUMO it was built for) and exit")(
      "config", po::value(&config),
      "read further options from FILE (same names, one 'name = value' per line; a scenario's "
      "scenario.cfg). Paths in it are relative to its folder. Command-line values win.");
  po::options_description run("Simulation");
  run.add_options()("sumo-config,c", po::value(&o.sumo_config),
                    "SUMO configuration (.sumocfg) to run in-process (libsumo)")(
      "connect", po::value(&o.connect),
      "HOST:PORT of a SUMO or sumo-gui already running with --remote-port PORT; attach to it "
      "through libtraci instead of running SUMO in-process")(
      "ego", po::value(&o.egos)->composing(),
      "vehicle ID whose criticality is estimated (repeatable)")(
      "all-vehicles", po::bool_switch(&o.all_vehicles), "every vehicle present is an ego")(
      "event", po::value(&events)->composing(),
      "scripted event 'TIME TARGET ACTION ARGS' (repeatable; usually in a scenario.cfg). ACTION: "
      "speed-mode VEH BITS | lane-change-mode VEH BITS | speed VEH MPS | slow-down VEH MPS SEC | "
      "lane-change VEH INDEX SEC | param VEH KEY VALUE | person-speed PERSON MPS")(
      "end", po::value(&o.end_time_s)->default_value(-1.0, "when SUMO ends"),
      "stop at this simulated time (s)")(
      "expect", po::value(&expect),
      "scenario expectation, reported in the summary: collision | no-collision")(
      "expect-partner", po::value(&o.expect_partner),
      "scenario expectation: ID of the vehicle or person the ego collides with")(
      "quiet-until", po::value(&o.quiet_until_s)->default_value(0.0),
      "scenario metadata: end of the quiet phase (s); a warning that starts earlier is a false "
      "alarm")("category", po::value(&o.category),
               "scenario metadata for evaluations: static-object, moving-object, pedestrian or "
               "free (collision-free)");
  po::options_description action("Acting on the estimate");
  action.add_options()(
      "act", po::value(&act)->default_value(act),
      "none: only record; warn: record warning episodes, publish the criticality as vehicle "
      "parameter 'criticality' and colour the ego red while warning; brake: warn and also take "
      "control (plugin/README.md, Closed loop): from p >= brake threshold follow the best "
      "escape route (its braking, and its lane change unless --no-steer), never braking less "
      "than SUMO would; hand control back after --act-hold once p stays below --brake-release "
      "for --act-release-after")(
      "warn-on", po::value(&warn_on)->default_value(warn_on),
      "the estimate the warning reads: p_collision (the paper's p_cra: the probability that the "
      "scene ends in a collision of the ego, over all its hypotheses), p_reference (if the ego "
      "keeps its most probable course) or unavoidability (the least colliding ego hypothesis: 1 "
      "= nothing helps)")("warn-threshold",
                          po::value(&o.warn_threshold)->default_value(o.warn_threshold),
                          "value of the --warn-on estimate that starts a warning episode")(
      "warn-release", po::value(&o.warn_release)->default_value(-1.0, "0.8 x warn threshold"),
      "value below which a warning episode ends (hysteresis)")(
      "warn-release-after",
      po::value(&o.warn_release_after_s)->default_value(o.warn_release_after_s),
      "seconds the estimate must stay below --warn-release before the episode ends (a one-step "
      "dip does not split a warning; 0: end at the first step below)")(
      "brake-threshold", po::value(&o.brake_threshold)->default_value(o.brake_threshold),
      "value of the --warn-on estimate at which --act brake takes control")(
      "brake-release", po::value(&o.brake_release)->default_value(-1.0, "0.5 x brake threshold"),
      "value of the --warn-on estimate below which --act brake may hand control back "
      "(hysteresis)")("act-hold", po::value(&o.act_hold_s)->default_value(o.act_hold_s),
                      "seconds --act brake keeps control at least, whatever the estimate")(
      "act-release-after", po::value(&o.act_release_after_s)->default_value(o.act_release_after_s),
      "seconds the estimate must stay below --brake-release before control is handed back")(
      "no-steer", po::bool_switch(&o.no_steer),
      "--act brake only brakes: follows the best escape route that keeps its lane");
  po::options_description est("Estimator");
  est.add_options()("backend", po::value(&backend)->default_value(backend),
                    "reference | cpu | cuda | auto (cuda when a GPU is usable, else cpu)")(
      "preset", po::value(&o.preset)->default_value(o.preset),
      "estimator parameters to start from: default (drivable hypotheses, naturalistic scores) "
      "or paper-literal (the paper's models and our first scoring, for comparisons); the "
      "options below change them further")(
      "no-lateral-controller", po::bool_switch(&no_lateral_controller),
      "ablation (paper Sec. V-A): no lateral controller, constant open-loop steering per path "
      "section, so hypotheses may leave the road")(
      "no-road-model", po::bool_switch(&no_road_model),
      "ablation (paper Sec. V-A): ignore SUMO's lanes; every vehicle gets virtual lanes along "
      "its heading")(
      "no-car-following", po::bool_switch(&no_car_following),
      "ablation (ours): the reference hypothesis keeps the current acceleration (the paper's) "
      "instead of the braking each vehicle's leader asks for (estimator/ALGORITHM.md)")(
      "threads", po::value(&o.estimator.threads)->default_value(0),
      "estimator threads (0 = all cores)")(
      "profiles", po::value(&o.params.profiles)->default_value(o.params.profiles),
      "acceleration/slip profiles per object (paper: 6 or 5)")(
      "own-lane-samples",
      po::value(&o.params.own_lane_samples)->default_value(o.params.own_lane_samples),
      "lateral path samples across the own lane (paper: 3)")(
      "neighbour-lane-samples",
      po::value(&o.params.neighbour_lane_samples)->default_value(o.params.neighbour_lane_samples),
      "lateral path samples across each neighbouring lane (paper: 2); ego paths = samples^3")(
      "horizon", po::value(&o.params.horizon_s)->default_value(o.params.horizon_s),
      "prediction horizon (s); the path sample instants (paper: 1.0, 1.5, 2.0 s of 2 s) scale "
      "with it")("step", po::value(&o.params.step_s)->default_value(o.params.step_s),
                 "prediction step (s)")(
      "range", po::value(&o.range_m)->default_value(o.range_m),
      "vehicles and pedestrians within this distance of an ego are considered (m)")(
      "no-reach-shortcut", po::bool_switch(&no_shortcut),
      "estimate objects that cannot reach the ego within the horizon, and egos with no object "
      "in reach, in full (the exact shortcut changes no result; this is for checking that)");
  po::options_description output("Output");
  output.add_options()("output", po::value(&o.output),
                       "results database (SQLite) to create; must not exist")(
      "record-scenes", po::value(&o.record_scenes),
      "write every estimated scene to DIR as a scene file that 'criticality-bench --scene-file' "
      "replays without SUMO")("no-progress", po::bool_switch(&no_progress),
                              "no progress line even on a terminal");
  po::options_description all;
  all.add(generic).add(run).add(action).add(est).add(output);

  po::variables_map vm;
  try {
    try {
      po::store(po::parse_command_line(static_cast<int>(own.size()), own.data(), all), vm);
    } catch (const po::unknown_option& e) {
      std::string name = e.get_option_name();
      while (!name.empty() && name[0] == '-') name.erase(0, 1);
      if (name == "configuration-file" || name == "sumocfg" || name == "sumo-cfg") {
        throw std::invalid_argument("unrecognised option '--" + name +
                                    "': the SUMO configuration is given with -c FILE "
                                    "(--sumo-config FILE)");
      }
      if (SumoKnowsOption(name)) {
        throw std::invalid_argument("unrecognised option '--" + name +
                                    "': it is a SUMO option; give SUMO's options after '--', "
                                    "e.g. sumo-criticality ... -- --" +
                                    name + " VALUE");
      }
      throw;
    }
    if (vm.count("version")) {
      std::cout << "sumo-criticality " << CRIT_VERSION << " (built with SUMO " << CRIT_SUMO_VERSION
                << " headers)\n";
      out.exit_now = true;
      return out;
    }
    if (vm.count("help")) {
      std::cout
          << "sumo-criticality: runs SUMO and estimates, every step, each ego's collision "
             "probability with the multi-hypothesis algorithm; records steps, warnings, "
             "actions and SUMO's collisions in SQLite.\n\n"
             "Usage: sumo-criticality -c scenario.sumocfg --ego ego0 --act warn --output "
             "run.sqlite [-- SUMO options]\n"
             "       sumo-criticality --config scenarios/rear_end/scenario.cfg --output "
             "run.sqlite\n"
          << all
          << "\nThe last line of standard output, on every exit, is a JSON summary. Exit "
             "codes: 0 done, 1 internal error, 2 bad options or input, 3 SUMO error, 4 results "
             "could not be written, 5 ego error (a named ego SUMO never loads, or a person), 130 "
             "interrupted (SIGINT), 143 terminated (SIGTERM).\n";
      out.exit_now = true;
      return out;
    }
    if (vm.count("config")) {
      config = vm["config"].as<std::string>();  // stored only at notify()
      CheckConfigFile(config, all);
      std::ifstream in(config);
      po::store(po::parse_config_file(in, all), vm);
    }
    po::notify(vm);
  } catch (const po::error& e) {
    throw std::invalid_argument(std::string(e.what()) + " (see --help)");
  }
  if (vm.count("config") && !o.sumo_config.empty() && fs::path(o.sumo_config).is_relative() &&
      !vm["sumo-config"].defaulted()) {
    // A sumo-config given in the config file is relative to that file's folder.
    std::ifstream in(config);
    po::variables_map only_file;
    po::store(po::parse_config_file(in, all), only_file);
    if (only_file.count("sumo-config") &&
        only_file["sumo-config"].as<std::string>() == o.sumo_config) {
      o.sumo_config = (fs::path(config).parent_path() / o.sumo_config).lexically_normal().string();
    }
  }
  for (const std::string& e : events) o.events.push_back(ParseEvent(e));
  o.progress = !no_progress;
  o.estimator.reach_shortcut = !no_shortcut;
  if (!vm["end"].defaulted() && !(std::isfinite(o.end_time_s) && o.end_time_s >= 0.0)) {
    throw std::invalid_argument("--end " + std::to_string(o.end_time_s) +
                                ": must be a finite time >= 0 s");
  }
  if (!o.connect.empty() && !o.sumo_args.empty()) {
    throw std::invalid_argument(
        "options after '--' go to the SUMO that sumo-criticality starts; under --connect SUMO "
        "is already running: give them to it (sumo -c ... --remote-port PORT " +
        o.sumo_args.front() + " ...)");
  }
  if (act == "none")
    o.act = Act::kNone;
  else if (act == "warn")
    o.act = Act::kWarn;
  else if (act == "brake")
    o.act = Act::kBrake;
  else
    throw std::invalid_argument("--act '" + act + "': use none, warn or brake");
  o.estimator.backend = ParseBackend(backend);
  if (warn_on == "p_collision")
    o.warn_on = WarnOn::kPCollision;
  else if (warn_on == "p_reference")
    o.warn_on = WarnOn::kPReference;
  else if (warn_on == "unavoidability")
    o.warn_on = WarnOn::kUnavoidability;
  else
    throw std::invalid_argument("--warn-on '" + warn_on +
                                "': use p_collision, p_reference or unavoidability");
  {
    // The preset, with the estimator options given explicitly on top of it.
    Params p = ParamsPreset(o.preset);  // InputError names the accepted presets
    auto given = [&](const char* name) { return vm.count(name) && !vm[name].defaulted(); };
    if (given("profiles")) p.profiles = o.params.profiles;
    if (given("own-lane-samples")) p.own_lane_samples = o.params.own_lane_samples;
    if (given("neighbour-lane-samples")) p.neighbour_lane_samples = o.params.neighbour_lane_samples;
    if (given("horizon")) {  // the path sample instants keep their share of the horizon
      for (double& t : p.path_sample_times_s) t *= o.params.horizon_s / p.horizon_s;
      p.horizon_s = o.params.horizon_s;
    }
    if (given("step")) p.step_s = o.params.step_s;
    if (no_lateral_controller) p.lateral_controller = false;
    if (no_road_model) p.road_model = false;
    if (no_car_following) p.expected_accel_reference = false;
    o.params = p;
  }
  if (!expect.empty() && expect != "collision" && expect != "no-collision") {
    throw std::invalid_argument("--expect '" + expect + "': use collision or no-collision");
  }
  o.expect = expect;
  if (!o.expect_partner.empty() && o.expect != "collision")
    throw std::invalid_argument("--expect-partner needs --expect collision");
  if (!std::isfinite(o.quiet_until_s) || o.quiet_until_s < 0.0)
    throw std::invalid_argument("--quiet-until must be a finite time >= 0 s");
  if (o.sumo_config.empty() && o.connect.empty()) {
    throw std::invalid_argument(
        "no simulation: give -c/--sumo-config FILE (or --connect HOST:PORT)");
  }
  if (!o.sumo_config.empty() && o.connect.empty() && !fs::exists(o.sumo_config)) {
    throw std::invalid_argument("--sumo-config '" + o.sumo_config + "': no such file");
  }
  if (!o.connect.empty()) {
    const auto colon = o.connect.rfind(':');
    int port = 0;
    try {
      port = colon == std::string::npos ? 0 : std::stoi(o.connect.substr(colon + 1));
    } catch (const std::exception&) {
    }
    if (colon == std::string::npos || colon == 0 || port <= 0 || port > 65535) {
      throw std::invalid_argument("--connect '" + o.connect +
                                  "': expected HOST:PORT, e.g. localhost:8813");
    }
  }
  if (o.output.empty()) throw std::invalid_argument("no --output FILE.sqlite given");
  if (o.egos.empty() && !o.all_vehicles)
    throw std::invalid_argument("no ego: give --ego ID (repeatable) or --all-vehicles");
  for (double t : {o.warn_threshold, o.brake_threshold}) {
    if (!(t > 0.0 && t <= 1.0))
      throw std::invalid_argument("thresholds must be in (0, 1], got " + std::to_string(t));
  }
  if (o.warn_release < 0.0) o.warn_release = 0.8 * o.warn_threshold;
  if (o.warn_release > o.warn_threshold)
    throw std::invalid_argument("--warn-release must not exceed --warn-threshold");
  if (!(o.warn_release_after_s >= 0.0) || !std::isfinite(o.warn_release_after_s))
    throw std::invalid_argument("--warn-release-after must be >= 0 s");
  if (o.brake_release < 0.0) o.brake_release = 0.5 * o.brake_threshold;
  if (o.brake_release > o.brake_threshold)
    throw std::invalid_argument("--brake-release must not exceed --brake-threshold");
  if (!(o.act_hold_s >= 0.0) || !(o.act_release_after_s >= 0.0))
    throw std::invalid_argument("--act-hold and --act-release-after must be >= 0 s");
  if (!(o.range_m > 0.0)) throw std::invalid_argument("--range must be > 0");
  if (o.estimator.threads < 0) throw std::invalid_argument("--threads must be >= 0");
  try {
    ValidateParams(o.params);
  } catch (const std::invalid_argument& e) {  // InputError names the Params field
    throw std::invalid_argument(WithOptionNames(e.what()));
  }
  return out;
}

}  // namespace criticality::plugin
