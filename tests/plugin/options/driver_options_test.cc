// sumo-criticality's options and scenario events.
#include "plugin/options/driver_options.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <thread>
#include <vector>

#include "plugin/record/results_db.h"
#include "plugin/script/scenario_event.h"

namespace criticality::plugin {
namespace {

ParseOutcome Parse(std::vector<const char*> args) {
  args.insert(args.begin(), "sumo-criticality");
  return ParseDriverOptions(static_cast<int>(args.size()), args.data());
}

TEST(ScenarioEvent, ParsesEveryAction) {
  ScenarioEvent e = ParseEvent("4.5 ego speed-mode 0");
  EXPECT_EQ(e.time_s, 4.5);
  EXPECT_EQ(e.target, "ego");
  EXPECT_EQ(e.action, EventAction::kSpeedMode);
  e = ParseEvent("2 ego lane-change 1 30");
  EXPECT_EQ(e.action, EventAction::kLaneChange);
  EXPECT_EQ(e.number, 1.0);
  EXPECT_EQ(e.duration_s, 30.0);
  e = ParseEvent("0 car7 param junctionModel.ignoreFoeProb 1");
  EXPECT_EQ(e.key, "junctionModel.ignoreFoeProb");
  EXPECT_EQ(ParseEvent("1 p0 person-speed 2.5").action, EventAction::kPersonSpeed);
}

TEST(ScenarioEvent, RejectsBadLinesWithTheLineInTheMessage) {
  for (const char* bad : {"x ego speed 3", "-1 ego speed 3", "1 ego fly 3", "1 ego speed",
                          "1 ego speed fast", "1 ego lane-change 1"}) {
    try {
      ParseEvent(bad);
      ADD_FAILURE() << bad;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
  }
}

// A .sumocfg that exists (the parser checks that -c names a file).
std::string SumoCfg() {
  const std::string path = ::testing::TempDir() + "s.sumocfg";
  std::ofstream(path) << "<configuration/>\n";
  return path;
}

TEST(DriverOptions, CommandLine) {
  const std::string cfg = SumoCfg();
  const ParseOutcome o = Parse({"-c", cfg.c_str(), "--ego", "a", "--ego", "b", "--act", "brake",
                                "--output", "x.sqlite", "--profiles", "5", "--", "--seed", "7"});
  EXPECT_EQ(o.options.observe.egos, (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(o.options.act.act, Act::kBrake);
  EXPECT_EQ(o.options.params.profiles, 5);
  EXPECT_EQ(o.options.run.sumo_args, (std::vector<std::string>{"--seed", "7"}));
  EXPECT_DOUBLE_EQ(o.options.act.warning.release, 0.8 * o.options.act.warning.threshold);
  EXPECT_DOUBLE_EQ(o.options.act.warning.release_after_s, 0.3);
  for (const char* alias : {"--sumocfg", "--configuration-file"}) {
    try {
      Parse({alias, cfg.c_str(), "--ego", "a", "--output", "x.sqlite"});
      ADD_FAILURE() << alias << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("-c FILE"), std::string::npos) << e.what();
    }
  }
  const ParseOutcome z =
      Parse({"-c", cfg.c_str(), "--ego", "a", "--output", "x.sqlite", "--warn-release-after", "0"});
  EXPECT_DOUBLE_EQ(z.options.act.warning.release_after_s, 0.0);
  try {
    Parse({"-c", cfg.c_str(), "--ego", "a", "--output", "x.sqlite", "--warn-release-after", "-1"});
    ADD_FAILURE() << "--warn-release-after -1 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("--warn-release-after"), std::string::npos) << e.what();
  }
}

// Only whole option names: Boost's default style also takes an unambiguous prefix, and a
// misspelt --all-vehicle ran a whole run as --all-vehicles, --thr 2 as --threads 2. And a
// --step above the horizon is named in the user's terms, not by a Params field.
TEST(DriverOptions, AnOptionsPrefixIsNoOptionAndErrorsNameOptions) {
  const std::string cfg = SumoCfg();
  for (const std::vector<const char*>& extra :
       {std::vector<const char*>{"--all-vehicle"}, std::vector<const char*>{"--thr", "2"}}) {
    std::vector<const char*> args = {"-c", cfg.c_str(), "--output", "x.sqlite"};
    args.insert(args.end(), extra.begin(), extra.end());
    try {
      Parse(args);
      ADD_FAILURE() << extra[0] << " accepted";
    } catch (const std::exception& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("'") + extra[0] + "'"), std::string::npos)
          << e.what();
    }
  }
  try {
    Parse({"-c", cfg.c_str(), "--ego", "a", "--output", "x.sqlite", "--step", "5"});
    ADD_FAILURE() << "--step 5 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("--step = 5: must not exceed --horizon"),
              std::string::npos)
        << e.what();
  }
}

TEST(DriverOptions, ConfigFileIsRelativeToItsFolderAndCommandLineWins) {
  const std::string dir = ::testing::TempDir();
  {
    std::ofstream sumocfg(dir + "/s.sumocfg");
    sumocfg << "<configuration/>\n";
    std::ofstream cfg(dir + "/scenario.cfg");
    cfg << "sumo-config = s.sumocfg\nego = ego\nact = none\nevent = 1 ego speed 3\nevent = 2 ego "
           "speed-mode 0\n";
  }
  const std::string cfg = dir + "/scenario.cfg";
  const ParseOutcome o = Parse({"--config", cfg.c_str(), "--act", "warn", "--output", "y.sqlite"});
  EXPECT_EQ(o.options.run.sumo_config,
            (std::filesystem::path(dir) / "s.sumocfg").lexically_normal().string());
  EXPECT_EQ(o.options.act.act, Act::kWarn);
  EXPECT_EQ(o.options.run.events.size(), 2u);
}

TEST(DriverOptions, ScenarioMetadata) {
  const ParseOutcome o = Parse({"--connect", "h:1", "--ego", "e", "--output", "x", "--expect",
                                "collision", "--expect-partner", "obstacle", "--quiet-until", "4.5",
                                "--category", "static-object"});
  EXPECT_EQ(o.options.run.expect_partner, "obstacle");
  EXPECT_EQ(o.options.run.quiet_until_s, 4.5);
  EXPECT_EQ(o.options.run.category, "static-object");
  // A partner without an expected collision, or a negative quiet phase, is a mistake.
  EXPECT_THROW(Parse({"--connect", "h:1", "--ego", "e", "--output", "x", "--expect-partner", "o"}),
               std::invalid_argument);
  EXPECT_THROW(Parse({"--connect", "h:1", "--ego", "e", "--output", "x", "--quiet-until", "-1"}),
               std::invalid_argument);
}

TEST(DriverOptions, LaneHeadingAndLaneChangeRulesAreOnUnlessSwitchedOff) {
  const auto parse = [](std::vector<const char*> extra) {
    std::vector<const char*> args = {"--connect", "h:1", "--ego", "e", "--output", "x"};
    args.insert(args.end(), extra.begin(), extra.end());
    return Parse(args).options.scenes;
  };
  const SceneConfig plain = parse({});
  EXPECT_TRUE(plain.lane_heading_yaw_rate);
  EXPECT_FALSE(parse({"--no-lane-heading-yaw-rate"}).lane_heading_yaw_rate);
  EXPECT_FALSE(plain.lane_change_target);  // experimental: off unless asked for
  EXPECT_TRUE(parse({"--lane-change-target"}).lane_change_target);
  EXPECT_TRUE(plain.lane_change_yaw_rate);
  EXPECT_FALSE(parse({"--no-lane-change-yaw-rate"}).lane_change_yaw_rate);
}

TEST(DriverOptions, ThreadsBesideSumo) {
  // Pipelined (--act warn, the default loop), named egos: --threads 0 leaves SUMO a core and
  // the estimator's helpers do not spin; a fleet keeps every core; --act brake (SUMO and the
  // estimate take turns) and --no-pipeline keep both; a number given stays.
  const unsigned cores = std::thread::hardware_concurrency();
  const int all_but_one = cores > 1 ? static_cast<int>(cores) - 1 : 1;
  auto opts = [](std::vector<const char*> extra) {
    std::vector<const char*> args{"--connect", "h:1", "--output", "x"};
    args.insert(args.end(), extra.begin(), extra.end());
    return Parse(args).options.estimator;
  };
  const EstimatorOptions named = opts({"--ego", "e"});
  EXPECT_EQ(named.threads, all_but_one);
  EXPECT_FALSE(named.spin_wait);
  const EstimatorOptions fleet = opts({"--all-vehicles"});
  EXPECT_EQ(fleet.threads, 0);
  EXPECT_FALSE(fleet.spin_wait);
  for (const char* serial : {"--no-pipeline", "--act=brake"}) {
    const EstimatorOptions o = opts({"--ego", "e", serial});
    EXPECT_EQ(o.threads, 0) << serial;
    EXPECT_TRUE(o.spin_wait) << serial;
  }
  EXPECT_EQ(opts({"--ego", "e", "--threads", "2"}).threads, 2);
  // Escape routes only for the closed loop, their only reader.
  auto routes = [](const char* act) {
    return Parse({"--connect", "h:1", "--output", "x", "--ego", "e", "--act", act})
        .options.params.max_escape_routes;
  };
  EXPECT_EQ(routes("none"), 0);
  EXPECT_EQ(routes("warn"), 0);
  EXPECT_EQ(routes("brake"), Params{}.max_escape_routes);
  EXPECT_GT(routes("brake"), 0);
}

TEST(DriverOptions, PresetAblationsAndWarningEstimate) {
  const std::vector<const char*> base{"--connect", "h:1", "--ego", "e", "--output", "x"};
  auto with = [&](std::vector<const char*> extra) {
    std::vector<const char*> args = base;
    args.insert(args.end(), extra.begin(), extra.end());
    return Parse(args).options;
  };
  // Defaults: the calibrated parameters, warning on p_collision >= 0.9.
  const DriverOptions d = with({});
  EXPECT_EQ(d.act.warn_on, WarnOn::kPCollision);
  EXPECT_EQ(d.act.warning.threshold, 0.9);
  EXPECT_TRUE(d.params.lateral_controller);
  EXPECT_TRUE(d.params.road_model);
  EXPECT_TRUE(d.params.expected_accel_reference);
  EXPECT_EQ(d.params.scoring, Params{}.scoring);
  // The preset, and explicit estimator options on top of it.
  const DriverOptions p = with({"--preset", "paper-literal", "--profiles", "5"});
  EXPECT_EQ(p.params.scoring, ParamsPreset("paper-literal").scoring);
  EXPECT_FALSE(p.params.friction_limited_lateral);
  EXPECT_EQ(p.params.profiles, 5);
  const DriverOptions a = with({"--no-lateral-controller", "--no-road-model"});
  EXPECT_FALSE(a.params.lateral_controller);
  EXPECT_FALSE(a.params.road_model);
  EXPECT_TRUE(a.params.expected_accel_reference);
  EXPECT_FALSE(with({"--no-car-following"}).params.expected_accel_reference);
  EXPECT_FALSE(d.scenes.observable_only);
  EXPECT_TRUE(with({"--observable-only"}).scenes.observable_only);
  EXPECT_TRUE(d.scenes.crossing_obligations);
  EXPECT_FALSE(with({"--no-crossing-obligations"}).scenes.crossing_obligations);
  EXPECT_TRUE(d.scenes.crossing_stops);
  EXPECT_FALSE(with({"--no-crossing-stops"}).scenes.crossing_stops);
  EXPECT_TRUE(with({"--no-crossing-stops"}).scenes.crossing_obligations);
  EXPECT_FALSE(d.scenes.bent_bodies);
  EXPECT_TRUE(with({"--bent-bodies"}).scenes.bent_bodies);
  EXPECT_FALSE(d.scenes.bodies_on_path);
  EXPECT_TRUE(with({"--bodies-on-path"}).scenes.bodies_on_path);
  EXPECT_TRUE(d.scenes.sumo_box);
  EXPECT_FALSE(with({"--no-sumo-box"}).scenes.sumo_box);
  EXPECT_FALSE(with({"--no-sumo-box"}).scenes.bodies_on_path);
  // A shorter horizon scales the path sample instants (1.0, 1.5, 2.0 of 2 s).
  const DriverOptions h = with({"--horizon", "1.5"});
  EXPECT_EQ(h.params.horizon_s, 1.5);
  EXPECT_EQ(h.params.path_sample_times_s, (std::vector<double>{0.75, 1.125, 1.5}));
  EXPECT_EQ(with({"--warn-on", "unavoidability"}).act.warn_on, WarnOn::kUnavoidability);
  Result r;
  r.p_collision = 0.1;
  r.p_reference = 0.2;
  r.unavoidability = 0.3;
  EXPECT_EQ(WarnValue(WarnOn::kPCollision, r), 0.1);
  EXPECT_EQ(WarnValue(WarnOn::kPReference, r), 0.2);
  EXPECT_EQ(WarnValue(WarnOn::kUnavoidability, r), 0.3);
  for (std::vector<const char*> bad :
       {std::vector<const char*>{"--preset", "fast"}, {"--warn-on", "p"}}) {
    try {
      with(bad);
      ADD_FAILURE() << bad[0];
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(bad[1]), std::string::npos) << e.what();
    }
  }
}

TEST(DriverOptions, BadOptionsAreOneLineErrors) {
  EXPECT_THROW(Parse({"--ego", "e", "--output", "x.sqlite"}),
               std::invalid_argument);  // no sumo config
  EXPECT_THROW(Parse({"--connect", "host", "--ego", "e", "--output", "x"}), std::invalid_argument);
  EXPECT_THROW(Parse({"--connect", "h:70000", "--ego", "e", "--output", "x"}),
               std::invalid_argument);
  EXPECT_THROW(Parse({"--connect", "h:1", "--output", "x"}), std::invalid_argument);  // no ego
  EXPECT_THROW(Parse({"--connect", "h:1", "--ego", "e"}), std::invalid_argument);     // no output
  EXPECT_THROW(
      Parse({"--connect", "h:1", "--ego", "e", "--output", "x", "--warn-threshold", "1.5"}),
      std::invalid_argument);
  EXPECT_THROW(Parse({"--connect", "h:1", "--ego", "e", "--output", "x", "--horizon", "0"}),
               std::invalid_argument);
  EXPECT_THROW(Parse({"--connect", "h:1", "--ego", "e", "--output", "x", "--bogus"}),
               std::invalid_argument);
  EXPECT_NO_THROW(Parse({"--connect", "localhost:8813", "--all-vehicles", "--output", "x"}));
}

std::string ErrorOf(std::vector<const char*> args) {
  try {
    Parse(args);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(DriverOptions, ErrorsUseOptionNames) {
  EXPECT_NE(ErrorOf({"--connect", "h:1", "--ego", "e", "--output", "x", "--horizon", "0"})
                .find("--horizon = 0"),
            std::string::npos);
  EXPECT_NE(ErrorOf({"--connect", "h:1", "--ego", "e", "--output", "x", "--profiles", "2"})
                .find("--profiles"),
            std::string::npos);
  EXPECT_EQ(ErrorOf({"--connect", "h:1", "--ego", "e", "--output", "x", "--profiles", "2"})
                .find("params."),
            std::string::npos);
}

TEST(DriverOptions, EndMustBeAFiniteTimeOrAbsent) {
  for (const char* bad : {"-5", "nan", "inf", "-inf"}) {
    EXPECT_NE(
        ErrorOf({"--connect", "h:1", "--ego", "e", "--output", "x", "--end", bad}).find("--end"),
        std::string::npos)
        << bad;
  }
  EXPECT_EQ(
      Parse({"--connect", "h:1", "--ego", "e", "--output", "x", "--end", "0"}).options.run.end_time_s,
      0.0);
  EXPECT_LT(Parse({"--connect", "h:1", "--ego", "e", "--output", "x"}).options.run.end_time_s, 0.0);
}

TEST(DriverOptions, ConfigFileErrorsNameFileAndLine) {
  const std::string path = ::testing::TempDir() + "lines.cfg";
  std::ofstream(path) << "# comment\nego = e\n\nwarn-threshold = high\n";
  const std::string err = ErrorOf({"--config", path.c_str(), "--connect", "h:1", "--output", "x"});
  EXPECT_NE(err.find(path + ":4:"), std::string::npos) << err;
  std::ofstream(path) << "ego = e\nno equals sign\n";
  EXPECT_NE(ErrorOf({"--config", path.c_str(), "--connect", "h:1", "--output", "x"})
                .find(path + ":2: expected 'name = value'"),
            std::string::npos);
  // A .sumocfg given as the scenario file: the error names the option that runs it.
  std::ofstream(path) << "<configuration>\n  <input/>\n</configuration>\n";
  const std::string xml = ErrorOf({"--config", path.c_str(), "--connect", "h:1", "--output", "x"});
  EXPECT_NE(xml.find(path + ":1: this is XML"), std::string::npos) << xml;
  EXPECT_NE(xml.find("-c " + path), std::string::npos) << xml;
  std::ofstream(path) << "ego = e\nbogus-option = 1\n";
  EXPECT_NE(ErrorOf({"--config", path.c_str(), "--connect", "h:1", "--output", "x"})
                .find(path + ":2: unknown option 'bogus-option'"),
            std::string::npos);
}

TEST(DriverOptions, SumoOptionsBelongAfterTheSeparatorAndNotUnderConnect) {
  // `sumo` (Debian's sumo package) knows --collision.action: the error says where it goes.
  EXPECT_NE(
      ErrorOf({"--connect", "h:1", "--ego", "e", "--output", "x", "--collision.action", "teleport"})
          .find("-- --collision.action"),
      std::string::npos);
  EXPECT_NE(ErrorOf({"--connect", "h:1", "--ego", "e", "--output", "x", "--", "--seed", "3"})
                .find("already running"),
            std::string::npos);
}

TEST(DriverOptions, VersionAndReachShortcut) {
  EXPECT_TRUE(Parse({"--version"}).exit_now);
  EXPECT_TRUE(
      Parse({"--connect", "h:1", "--ego", "e", "--output", "x"}).options.estimator.reach_shortcut);
  EXPECT_FALSE(Parse({"--connect", "h:1", "--ego", "e", "--output", "x", "--no-reach-shortcut"})
                   .options.estimator.reach_shortcut);
}

TEST(DriverOptions, EachStageGetsItsConfigFromTheOptionsAndTheFinalParameters) {
  const ParseOutcome o =
      Parse({"--connect", "h:1", "--ego", "e", "--output", "x", "--range", "55", "--horizon", "3",
             "--preset", "paper-literal", "--brake-threshold", "0.8", "--no-steer"});
  const DriverOptions& d = o.options;
  EXPECT_TRUE(d.observe.attached);  // under --connect
  EXPECT_EQ(d.observe.range_m, 55.0);
  EXPECT_EQ(d.scenes.range_m, 55.0);
  EXPECT_EQ(d.scenes.horizon_s, 3.0);  // the lanes reach as far as the horizon asks
  EXPECT_EQ(d.scenes.max_accel_mps2, d.params.vehicle_accel_max_mps2);
  // paper-literal samples lanes in the paper's frame, without the straight-before-turn mark.
  EXPECT_FALSE(d.scenes.lane_sampling.turn_lane_frame);
  EXPECT_FALSE(d.scenes.lane_sampling.straight_before_turn);
  EXPECT_FALSE(d.scenes.lane_sampling.straight_by_fit);
  EXPECT_TRUE(Parse({"--connect", "h:1", "--ego", "e", "--output", "x"})
                  .options.scenes.lane_sampling.turn_lane_frame);
  EXPECT_TRUE(Parse({"--connect", "h:1", "--ego", "e", "--output", "x"})
                  .options.scenes.lane_sampling.straight_by_fit);
  const ParseOutcome no_fit =
      Parse({"--connect", "h:1", "--ego", "e", "--output", "x", "--no-straight-by-fit"});
  EXPECT_FALSE(no_fit.options.params.straight_before_turn_by_fit);
  EXPECT_FALSE(no_fit.options.scenes.lane_sampling.straight_by_fit);
  EXPECT_TRUE(no_fit.options.scenes.lane_sampling.straight_before_turn);
  // Narrow vehicles hold their line: on by default (a third of the lane's width), off with its
  // switch and in paper-literal.
  EXPECT_EQ(Parse({"--connect", "h:1", "--ego", "e", "--output", "x"})
                .options.params.hold_line_max_width_share,
            1.0 / 3.0);
  EXPECT_EQ(Parse({"--connect", "h:1", "--ego", "e", "--output", "x", "--no-hold-line"})
                .options.params.hold_line_max_width_share,
            0.0);
  EXPECT_EQ(d.params.hold_line_max_width_share, 0.0);
  // The other vehicles' expected braking at once: on by default, off with its switch and in
  // paper-literal; a tight turn's corner: an experiment, on only when asked for.
  const ParseOutcome plain = Parse({"--connect", "h:1", "--ego", "e", "--output", "x"});
  EXPECT_FALSE(plain.options.scenes.lane_sampling.corner_in_turn);
  EXPECT_TRUE(plain.options.params.expected_accel_at_once);
  EXPECT_FALSE(d.params.expected_accel_at_once);
  EXPECT_TRUE(plain.options.params.stop_obligation_at_once);
  EXPECT_FALSE(d.params.stop_obligation_at_once);
  // Yield lines where SUMO's vehicle waits inside the junction: on, off with its switch.
  EXPECT_TRUE(plain.options.scenes.internal_junction_yield);
  EXPECT_FALSE(
      Parse({"--connect", "h:1", "--ego", "e", "--output", "x", "--no-internal-junction-yield"})
          .options.scenes.internal_junction_yield);
  EXPECT_TRUE(Parse({"--connect", "h:1", "--ego", "e", "--output", "x", "--internal-junction-yield"})
                  .options.scenes.internal_junction_yield);
  EXPECT_NE(ErrorOf({"--connect", "h:1", "--ego", "e", "--output", "x", "--internal-junction-yield",
                     "--no-internal-junction-yield"})
                .find("choose one"),
            std::string::npos);
  const ParseOutcome asked =
      Parse({"--connect", "h:1", "--ego", "e", "--output", "x", "--lane-corner-in-turn",
             "--no-expected-accel-at-once", "--no-stop-at-once"});
  EXPECT_TRUE(asked.options.params.lane_corner_in_turn);
  EXPECT_TRUE(asked.options.scenes.lane_sampling.corner_in_turn);
  EXPECT_FALSE(asked.options.params.expected_accel_at_once);
  EXPECT_FALSE(asked.options.params.stop_obligation_at_once);
  // The closed loop brakes as the escape routes do, and releases at half its threshold.
  EXPECT_EQ(d.act.closed_loop.brake.latency_s, d.params.latency_s);
  EXPECT_EQ(d.act.closed_loop.brake.jerk_mps3, d.params.jerk_mps3);
  EXPECT_DOUBLE_EQ(d.act.closed_loop.policy.engage_threshold, 0.8);
  EXPECT_DOUBLE_EQ(d.act.closed_loop.policy.release_threshold, 0.4);
  EXPECT_TRUE(d.act.closed_loop.no_steer);
}

TEST(DriverOptions, AThresholdOutOfRangeNamesItsOption) {
  EXPECT_NE(ErrorOf({"--connect", "h:1", "--ego", "e", "--output", "x", "--brake-threshold", "0"})
                .find("--brake-threshold 0: must be in (0, 1]"),
            std::string::npos);
  EXPECT_NE(ErrorOf({"--connect", "h:1", "--ego", "e", "--output", "x", "--warn-threshold", "2"})
                .find("--warn-threshold 2"),
            std::string::npos);
}

TEST(DriverOptions, CheckOptionsParsesEverythingAndExitsWithoutARun) {
  const ParseOutcome ok =
      Parse({"--connect", "h:1", "--ego", "e", "--output", "x", "--check-options"});
  EXPECT_TRUE(ok.exit_now);
  EXPECT_EQ(ok.exit_code, 0);
  EXPECT_FALSE(Parse({"--connect", "h:1", "--ego", "e", "--output", "x"}).exit_now);
  // A bad value is the run's error, not "options ok".
  EXPECT_THROW(Parse({"--connect", "h:1", "--ego", "e", "--output", "x", "--check-options", "--act",
                      "brak"}),
               std::invalid_argument);
  // The SUMO configuration must exist, as for a run.
  EXPECT_THROW(
      Parse({"-c", "/nonexistent/x.sumocfg", "--ego", "e", "--output", "x", "--check-options"}),
      std::invalid_argument);
  // So must the results file's folder, and the file must not: the run's errors (exit 4).
  const std::string here = ::testing::TempDir() + "check_options_output.sqlite";
  std::remove(here.c_str());
  auto check = [](const std::string& output) {
    Parse({"--connect", "h:1", "--ego", "e", "--output", output.c_str(), "--check-options"});
  };
  EXPECT_NO_THROW(check(here));
  EXPECT_THROW(check("/nonexistent-folder/run.sqlite"), ResultsError);
  EXPECT_THROW(check(::testing::TempDir()), ResultsError);  // a folder
  std::ofstream(here) << "earlier results";
  EXPECT_THROW(check(here), ResultsError);
  std::remove(here.c_str());
}

// Whether `err` names `option` followed by `value` ("--range 0:", "--profiles = 2:", "--act
// 'brak'"): only blanks, '=' and quotes between them (the "0" of "must be > 0" does not count);
// or names the option and quotes the value anywhere (Boost's "the argument ('abc') for option
// '--warn-threshold' is invalid").
bool NamesOptionAndValue(const std::string& err, const std::string& option,
                         const std::string& value) {
  if (err.find(option) != std::string::npos && err.find("'" + value + "'") != std::string::npos)
    return true;
  for (size_t at = err.find(option); at != std::string::npos; at = err.find(option, at + 1)) {
    size_t v = at + option.size();
    while (v < err.size() && std::string(" ='\"").find(err[v]) != std::string::npos) ++v;
    if (err.compare(v, value.size(), value) == 0) return true;
  }
  return false;
}

TEST(DriverOptions, EveryValueErrorNamesItsOptionAndValue) {
  const std::vector<std::vector<const char*>> cases = {{"--act", "brak"},
                                                       {"--warn-on", "p"},
                                                       {"--warn-threshold", "-0.5"},
                                                       {"--brake-threshold", "7"},
                                                       {"--warn-release", "0.95"},
                                                       {"--warn-release-after", "-1"},
                                                       {"--brake-release", "0.99"},
                                                       {"--act-hold", "-2"},
                                                       {"--act-release-after", "-3"},
                                                       {"--backend", "gpu"},
                                                       {"--preset", "fancy"},
                                                       {"--threads", "-4"},
                                                       {"--range", "0"},
                                                       {"--quiet-until", "-5"},
                                                       {"--horizon", "-1"},
                                                       {"--profiles", "2"},
                                                       {"--expect", "maybe"},
                                                       {"--warn-threshold", "abc"},
                                                       {"--event", "1 ego fly"}};
  for (const auto& c : cases) {
    std::vector<const char*> args{"--connect", "h:1", "--ego", "e", "--output", "x"};
    args.insert(args.end(), c.begin(), c.end());
    const std::string err = ErrorOf(args);
    EXPECT_TRUE(NamesOptionAndValue(err, c[0], c[1])) << c[0] << " " << c[1] << ": " << err;
  }
}

}  // namespace
}  // namespace criticality::plugin
