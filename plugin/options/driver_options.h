#pragma once
// sumo-criticality's options: command line, or the same options in a config file (--config),
// which is how a scenario folder describes its run (ego, scripted events, expectations). Parsed
// into one small config per stage of a step, so that each stage sees only what it uses.
#include <string>

#include "criticality/estimator.h"
#include "criticality/params.h"
#include "plugin/act/act_config.h"
#include "plugin/observe/observe_config.h"
#include "plugin/record/record_stage.h"
#include "plugin/run/run_config.h"
#include "plugin/scenes/scene_config.h"

namespace criticality::plugin {

struct DriverOptions {
  RunConfig run;          ///< the loop: SUMO, output, end, scripted events, scenario metadata
  ObserveConfig observe;  ///< egos, range
  SceneConfig scenes;     ///< range, reach, lane sampling
  /** The estimate stage: the estimator's parameters (--preset and the options on top) and
   *  execution settings (--backend, --threads, the reach shortcut). */
  Params params;
  EstimatorOptions estimator;
  ActConfig act;  ///< warnings and the closed loop
  RecordConfig record;
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

}  // namespace criticality::plugin
