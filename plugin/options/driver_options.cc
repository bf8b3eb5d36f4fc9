#include "plugin/options/driver_options.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <thread>

#include "plugin/options/config_file.h"
#include "plugin/options/option_table.h"
#include "plugin/record/results_db.h"

namespace po = boost::program_options;
namespace fs = std::filesystem;

namespace criticality::plugin {
namespace {

[[noreturn]] void Bad(const std::string& message) { throw std::invalid_argument(message); }

std::string Number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

// The option a Params field is set by, for messages in the user's terms.
std::string WithOptionNames(std::string msg) {
  const std::pair<const char*, const char*> names[] = {
      {"params.horizon_s", "--horizon"},
      {"params.step_s", "--step"},
      {"must not exceed horizon_s", "must not exceed --horizon"},
      {"params.profiles", "--profiles"},
      {"params.own_lane_samples", "--own-lane-samples"},
      {"params.neighbour_lane_samples", "--neighbour-lane-samples"},
      {"options.threads", "--threads"},
      {"backend = ", "--backend "},
      {"preset = ", "--preset "}};
  for (const auto& [field, option] : names) {
    for (size_t at = msg.find(field); at != std::string::npos; at = msg.find(field, at)) {
      msg.replace(at, std::strlen(field), option);
    }
  }
  return msg;
}

// The command line: an option SUMO knows, given before "--", gets that hint.
void StoreCommandLine(const std::vector<const char*>& own, const OptionTable& table,
                      po::variables_map* vm) {
  try {
    // Whole option names only: Boost's default style also takes an unambiguous prefix, so a
    // misspelt --all-vehicle ran as --all-vehicles and --thr 2 as --threads 2, unannounced.
    const int style = po::command_line_style::default_style & ~po::command_line_style::allow_guessing;
    po::store(po::command_line_parser(static_cast<int>(own.size()), own.data())
                  .options(table.all())
                  .style(style)
                  .run(),
              *vm);
  } catch (const po::unknown_option& e) {
    std::string name = e.get_option_name();
    while (!name.empty() && name[0] == '-') name.erase(0, 1);
    if (name == "configuration-file" || name == "sumocfg" || name == "sumo-cfg") {
      Bad("unrecognised option '--" + name +
          "': the SUMO configuration is given with -c FILE (--sumo-config FILE)");
    }
    if (SumoKnowsOption(name)) {
      Bad("unrecognised option '--" + name +
          "': it is a SUMO option; give SUMO's options after '--', e.g. sumo-criticality ... -- "
          "--" +
          name + " VALUE");
    }
    throw;
  }
}

// Command line, then the --config file (command-line values win). Returns false when --help or
// --version was printed.
bool Store(const std::vector<const char*>& own, OptionTable* table, po::variables_map* vm) {
  try {
    StoreCommandLine(own, *table, vm);
    if (vm->count("version")) {
      std::cout << "sumo-criticality " << CRIT_VERSION << " (built with SUMO " << CRIT_SUMO_VERSION
                << " headers)\n";
      return false;
    }
    if (vm->count("help")) {
      std::cout << HelpText(*table);
      return false;
    }
    if (vm->count("config")) {
      const std::string config = (*vm)["config"].as<std::string>();  // stored only at notify()
      CheckConfigFile(config, table->all());
      std::ifstream in(config);
      po::store(po::parse_config_file(in, table->all()), *vm);
    }
    po::notify(*vm);
  } catch (const po::error& e) {
    Bad(std::string(e.what()) + " (see --help)");
  }
  return true;
}

// A sumo-config given in the config file is relative to that file's folder.
void SumoConfigRelativeToConfigFile(const OptionTable& table, const po::variables_map& vm,
                                    RunConfig* run) {
  const std::string& config = table.raw.config;
  if (!vm.count("config") || run->sumo_config.empty() || fs::path(run->sumo_config).is_absolute() ||
      vm["sumo-config"].defaulted())
    return;
  std::ifstream in(config);
  po::variables_map only_file;
  po::store(po::parse_config_file(in, table.all()), only_file);
  if (only_file.count("sumo-config") &&
      only_file["sumo-config"].as<std::string>() == run->sumo_config) {
    run->sumo_config = RelativeToConfig(config, run->sumo_config);
  }
}

void CheckSimulation(RunConfig* run, const RawOptions& raw, const po::variables_map& vm) {
  for (const std::string& e : raw.events) {
    try {
      run->events.push_back(ParseEvent(e));
    } catch (const std::invalid_argument& err) {  // "event '...': ...": name the option
      Bad("--" + std::string(err.what()));
    }
  }
  run->progress = !raw.no_progress;
  run->pipeline = !raw.no_pipeline;
  if (!vm["end"].defaulted() && !(std::isfinite(run->end_time_s) && run->end_time_s >= 0.0)) {
    Bad("--end " + Number(run->end_time_s) + ": must be a finite time >= 0 s");
  }
  if (!run->connect.empty() && !run->sumo_args.empty()) {
    Bad("options after '--' go to the SUMO that sumo-criticality starts; under --connect SUMO "
        "is already running: give them to it (sumo -c ... --remote-port PORT " +
        run->sumo_args.front() + " ...)");
  }
  if (!raw.expect.empty() && raw.expect != "collision" && raw.expect != "no-collision")
    Bad("--expect '" + raw.expect + "': use collision or no-collision");
  run->expect = raw.expect;
  if (!run->expect_partner.empty() && run->expect != "collision")
    Bad("--expect-partner needs --expect collision");
  if (!std::isfinite(run->quiet_until_s) || run->quiet_until_s < 0.0)
    Bad("--quiet-until " + Number(run->quiet_until_s) + ": must be a finite time >= 0 s");
  if (run->sumo_config.empty() && run->connect.empty())
    Bad("no simulation: give -c/--sumo-config FILE (or --connect HOST:PORT)");
  if (!run->sumo_config.empty() && run->connect.empty() && !fs::exists(run->sumo_config))
    Bad("--sumo-config '" + run->sumo_config + "': no such file");
  if (!run->connect.empty()) {
    const auto colon = run->connect.rfind(':');
    int port = 0;
    try {
      port = colon == std::string::npos ? 0 : std::stoi(run->connect.substr(colon + 1));
    } catch (const std::exception&) {
    }
    if (colon == std::string::npos || colon == 0 || port <= 0 || port > 65535)
      Bad("--connect '" + run->connect + "': expected HOST:PORT, e.g. localhost:8813");
  }
  if (run->output.empty()) Bad("no --output FILE.sqlite given");
}

// The preset, with the estimator options given explicitly on top of it.
void Estimation(const RawOptions& raw, const po::variables_map& vm, DriverOptions* o) {
  Params p;
  try {  // InputError names the accepted values, in the estimator's terms
    o->estimator.backend = ParseBackend(raw.backend);
    p = ParamsPreset(raw.preset);
  } catch (const std::invalid_argument& e) {
    Bad(WithOptionNames(e.what()));
  }
  o->estimator.reach_shortcut = !raw.no_shortcut;
  o->estimator.simd = !raw.no_simd;
  auto given = [&](const char* name) { return vm.count(name) && !vm[name].defaulted(); };
  if (given("profiles")) p.profiles = o->params.profiles;
  if (given("own-lane-samples")) p.own_lane_samples = o->params.own_lane_samples;
  if (given("neighbour-lane-samples")) p.neighbour_lane_samples = o->params.neighbour_lane_samples;
  if (given("horizon")) {  // the path sample instants keep their share of the horizon
    for (double& t : p.path_sample_times_s) t *= o->params.horizon_s / p.horizon_s;
    p.horizon_s = o->params.horizon_s;
  }
  if (given("step")) p.step_s = o->params.step_s;
  if (raw.no_lateral_controller) p.lateral_controller = false;
  if (raw.no_road_model) p.road_model = false;
  if (raw.no_car_following) p.expected_accel_reference = false;
  if (raw.no_lane_fit_check) p.lane_fit_within_lane = false;
  if (raw.no_straight_by_fit) p.straight_before_turn_by_fit = false;
  if (raw.no_hold_line) p.hold_line_max_width_share = 0.0;
  if (raw.lane_corners) p.lane_corners = true;
  if (raw.lane_corner_in_turn) p.lane_corner_in_turn = true;
  if (raw.no_expected_accel_at_once) p.expected_accel_at_once = false;
  if (raw.no_stop_at_once) p.stop_obligation_at_once = false;
  if (raw.way_lateral_paths) p.way_lateral_paths = true;
  if (raw.ego_on_way) p.ego_on_way = true;
  if (raw.euler_stops) p.euler_stops = true;
  if (raw.release_braking) {
    p.release_unexplained_braking = true;
    o->scenes.braking_causes = true;
  }
  if (raw.ego_stops) p.ego_stop_obligations = true;
  if (raw.no_world_step_collisions) p.collisions_at_world_steps = false;
  if (raw.no_crossing_obligations) o->scenes.crossing_obligations = false;
  if (raw.no_crossing_stops) o->scenes.crossing_stops = false;
  if (raw.no_yield_stops) o->scenes.yield_stops = false;
  if (raw.internal_junction_yield && raw.no_internal_junction_yield)
    Bad("--internal-junction-yield and --no-internal-junction-yield: choose one (the first is "
        "the default)");
  if (raw.no_internal_junction_yield) o->scenes.internal_junction_yield = false;
  if (raw.no_heading_hold) o->scenes.heading_hold = false;
  if (raw.no_way_heading) o->scenes.way_heading = false;
  if (raw.junction_chord_heading && raw.no_junction_chord_heading)
    Bad("--junction-chord-heading and --no-junction-chord-heading: choose one (the first is the "
        "default)");
  if (raw.no_junction_chord_heading) o->scenes.junction_chord_heading = false;
  if (raw.no_lane_heading_yaw_rate) o->scenes.lane_heading_yaw_rate = false;
  if (raw.lane_change_target) o->scenes.lane_change_target = true;
  if (raw.no_lane_change_yaw_rate) o->scenes.lane_change_yaw_rate = false;
  if (raw.junction_shapes && raw.no_junction_shapes)
    Bad("--junction-shapes and --no-junction-shapes: choose one (the first is the default)");
  if (raw.no_junction_shapes) o->scenes.junction_shapes = false;
  if (raw.bent_bodies) o->scenes.bent_bodies = true;
  if (raw.bodies_on_path) o->scenes.bodies_on_path = true;
  if (raw.no_sumo_box) o->scenes.sumo_box = false;
  if (raw.no_junction_ways) o->scenes.junction_ways = false;
  o->params = p;
  if (o->estimator.threads < 0)
    Bad("--threads " + std::to_string(o->estimator.threads) + ": must be >= 0 (0: all cores)");
  try {
    ValidateParams(o->params);
  } catch (const std::invalid_argument& e) {  // InputError names the Params field
    Bad(WithOptionNames(e.what()));
  }
}

void Threshold(const char* option, double t) {
  if (!(t > 0.0 && t <= 1.0)) Bad(std::string(option) + " " + Number(t) + ": must be in (0, 1]");
}

void Acting(const RawOptions& raw, ActConfig* act) {
  act->closed_loop.hand_back_check = !raw.no_hand_back_check;
  if (raw.act == "none")
    act->act = Act::kNone;
  else if (raw.act == "warn")
    act->act = Act::kWarn;
  else if (raw.act == "brake")
    act->act = Act::kBrake;
  else
    Bad("--act '" + raw.act + "': use none, warn or brake");
  if (raw.warn_on == "p_collision")
    act->warn_on = WarnOn::kPCollision;
  else if (raw.warn_on == "p_reference")
    act->warn_on = WarnOn::kPReference;
  else if (raw.warn_on == "unavoidability")
    act->warn_on = WarnOn::kUnavoidability;
  else
    Bad("--warn-on '" + raw.warn_on + "': use p_collision, p_reference or unavoidability");
  WarningConfig& w = act->warning;
  AvoidancePolicyConfig& p = act->closed_loop.policy;
  Threshold("--warn-threshold", w.threshold);
  Threshold("--brake-threshold", p.engage_threshold);
  if (w.release < 0.0) w.release = 0.8 * w.threshold;
  if (w.release > w.threshold) {
    Bad("--warn-release " + Number(w.release) + ": must not exceed --warn-threshold " +
        Number(w.threshold));
  }
  if (!(w.release_after_s >= 0.0) || !std::isfinite(w.release_after_s))
    Bad("--warn-release-after " + Number(w.release_after_s) + ": must be a finite time >= 0 s");
  if (p.release_threshold < 0.0) p.release_threshold = 0.5 * p.engage_threshold;
  if (p.release_threshold > p.engage_threshold) {
    Bad("--brake-release " + Number(p.release_threshold) + ": must not exceed --brake-threshold " +
        Number(p.engage_threshold));
  }
  if (!(p.min_hold_s >= 0.0) || !std::isfinite(p.min_hold_s))
    Bad("--act-hold " + Number(p.min_hold_s) + ": must be a finite time >= 0 s");
  if (!(p.release_after_s >= 0.0) || !std::isfinite(p.release_after_s))
    Bad("--act-release-after " + Number(p.release_after_s) + ": must be a finite time >= 0 s");
}

// What the other stages take from the estimator's final parameters; the observe checks.
void Derive(DriverOptions* o) {
  ObserveConfig& observe = o->observe;
  if (observe.egos.empty() && !observe.all_vehicles)
    Bad("no ego: give --ego ID (repeatable) or --all-vehicles");
  if (!(observe.range_m > 0.0) || !std::isfinite(observe.range_m))
    Bad("--range " + Number(observe.range_m) + ": must be a finite distance > 0 m");
  observe.attached = !o->run.connect.empty();
  SceneConfig& scenes = o->scenes;
  if (!(scenes.accel_window_s >= 0.0 && scenes.accel_window_s <= 10.0))
    Bad("--accel-window " + Number(scenes.accel_window_s) +
        ": must be a time from 0 to 10 s (0: SUMO's acceleration of the last step)");
  scenes.range_m = observe.range_m;
  scenes.horizon_s = o->params.horizon_s;
  scenes.max_accel_mps2 = o->params.vehicle_accel_max_mps2;
  scenes.lane_sampling = LaneSamplingFor(o->params);
  scenes.friction = o->params.friction;
  scenes.max_steer_rad = o->params.max_steer_rad;
  scenes.all_vehicles = observe.all_vehicles;
  observe.ego_class = [classes = scenes.ego_classes](const std::string& vehicle_class) {
    return classes.Includes(vehicle_class);
  };
  o->act.closed_loop.brake.latency_s = o->params.latency_s;  // the escape routes' braking
  o->act.closed_loop.brake.jerk_mps3 = o->params.jerk_mps3;
  // Only the closed loop reads the escape routes (plugin/act/closed_loop.cc); each is
  // re-simulated step by step with its trace, so the other modes ask for none.
  if (o->act.act != Act::kBrake) o->params.max_escape_routes = 0;
  // Pipelined, SUMO's step runs beside the estimate: the estimator's helper threads sleep
  // between its parallel loops instead of spinning on SUMO's core, and --threads 0 with named
  // egos (one small estimate per step) leaves SUMO a core. A fleet (--all-vehicles) keeps
  // every core: there the estimates are nearly all of the step (bench/RESULTS.md).
  if (o->run.pipeline && o->act.act != Act::kBrake) {
    o->estimator.spin_wait = false;
    if (o->estimator.threads == 0 && !observe.all_vehicles) {
      const unsigned cores = std::thread::hardware_concurrency();
      o->estimator.threads = cores > 1 ? static_cast<int>(cores) - 1 : 1;
    }
  }
}

}  // namespace

ParseOutcome ParseDriverOptions(int argc, const char* const* argv) {
  ParseOutcome out;
  DriverOptions& o = out.options;
  // Everything after "--" goes to SUMO untouched.
  std::vector<const char*> own{argv[0]};
  int i = 1;
  for (; i < argc && std::string(argv[i]) != "--"; ++i) own.push_back(argv[i]);
  for (++i; i < argc; ++i) o.run.sumo_args.push_back(argv[i]);
  for (int k = 0; k < argc; ++k) o.run.command_line += (k ? " " : "") + std::string(argv[k]);

  OptionTable table(&o);
  po::variables_map vm;
  if (!Store(own, &table, &vm)) {
    out.exit_now = true;
    return out;
  }
  SumoConfigRelativeToConfigFile(table, vm, &o.run);
  CheckSimulation(&o.run, table.raw, vm);
  Acting(table.raw, &o.act);
  if (!table.raw.ego_classes.empty()) {
    if (!o.observe.all_vehicles) Bad("--ego-classes needs --all-vehicles (named egos are egos)");
    o.scenes.ego_classes = ParseEgoClasses(table.raw.ego_classes);
  }
  Estimation(table.raw, vm, &o);
  Derive(&o);
  if (vm.count("check-options")) {
    // A dry check: everything a run parses and that its results file can be created, then
    // no run.
    CheckOutputCreatable(o.run.output);
    std::cout << "sumo-criticality: options ok\n";
    out.exit_now = true;
  }
  return out;
}

}  // namespace criticality::plugin
