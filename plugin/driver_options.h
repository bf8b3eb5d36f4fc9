#pragma once
// sumo-criticality's options: command line, or the same options in a config file (--config),
// which is how a scenario folder describes its run (ego, scripted events, expectations).
#include <optional>
#include <string>
#include <vector>

#include "criticality/estimator.h"
#include "criticality/params.h"
#include "criticality/result.h"
#include "plugin/scenario_event.h"

namespace criticality::plugin {

enum class Act { kNone, kWarn, kBrake };
enum class WarnOn { kPCollision, kPReference, kUnavoidability };

/** The estimate a WarnOn names, from a result. */
double WarnValue(WarnOn on, const Result& r);
std::string WarnOnName(WarnOn on);

struct DriverOptions {
  std::string sumo_config;             ///< -c; relative paths in a --config file are relative to it
  std::vector<std::string> sumo_args;  ///< passed through to SUMO (after --)
  std::vector<std::string> egos;
  bool all_vehicles{false};
  Act act{Act::kWarn};
  /** Which estimate the warning (and --act brake) reads: p_collision (the paper's p_cra, the
   *  default: estimator/ALGORITHM.md "Outputs that serve decisions" says why), p_reference or
   *  unavoidability. */
  WarnOn warn_on{WarnOn::kPCollision};
  double warn_threshold{0.9};
  double brake_threshold{0.9};
  /** --act brake (plugin/avoidance_policy.h): control is handed back once the estimate has
   *  stayed below brake_release (negative: 0.5 x brake_threshold) for act_release_after_s, and
   *  not before act_hold_s after taking it; no_steer: braking only. */
  double brake_release{-1.0};
  double act_hold_s{1.0};
  double act_release_after_s{0.5};
  bool no_steer{false};
  /** Params preset the estimator parameters start from (criticality::ParamsPresetNames()). */
  std::string preset{"default"};
  /** A warning episode ends when p_cra falls below this (hysteresis, so that one approach is
   *  one episode); negative: 0.8 x warn_threshold. */
  double warn_release{-1.0};
  /** ... once it has stayed below for this long (s): a one-step dip does not split an approach
   *  into two episodes. 0: at the first step below. */
  double warn_release_after_s{0.3};
  double range_m{80.0};
  Params params;
  EstimatorOptions estimator;
  std::string output;         ///< SQLite file, required
  std::string record_scenes;  ///< directory, optional
  std::string connect;        ///< HOST:PORT, optional
  std::vector<ScenarioEvent> events;
  double end_time_s{-1.0};  ///< stop at this simulated time (<0: when SUMO is done)
  std::string expect;       ///< "", "collision" or "no-collision" (scenario metadata)
  /** Scenario metadata for tests and evaluations (the driver records them, never acts on them):
   *  the ID of the vehicle or person the ego is expected to collide with; the end of the
   *  scenario's quiet phase (s: nothing critical happens before it, so a warning that starts
   *  earlier is a false alarm); a category: static-object, moving-object, pedestrian or free. */
  std::string expect_partner;
  double quiet_until_s{0.0};
  std::string category;
  bool progress{true};       ///< progress line on a terminal
  std::string command_line;  ///< for the runs table
};

/** What ParseDriverOptions decided. */
struct ParseOutcome {
  bool exit_now{false};  ///< --help / --version printed
  int exit_code{0};
  DriverOptions options;
};

/** Parses argv (and the --config file it names). Throws std::invalid_argument with a one-line
 *  message for bad options. */
ParseOutcome ParseDriverOptions(int argc, const char* const* argv);

std::string ActName(Act act);

}  // namespace criticality::plugin
