#pragma once
// The co-simulation loop: each step, SUMO moves, then the stages run in the order data flows:
// observe (observe_stage.h) -> scenes (scene_stage.h) -> estimate (estimate_stage.h) ->
// act (act_stage.h) -> record (record_stage.h).
#include "plugin/driver_options.h"
#include "plugin/run_summary.h"

namespace criticality::plugin {

/** Exit codes (plugin/README.md). */
enum ExitCode : int {
  kExitDone = 0,
  kExitInternal = 1,
  kExitBadInput = 2,
  kExitSumo = 3,
  kExitResults = 4,
  kExitEgo = 5,
  kExitSigint = 130,
  kExitSigterm = 143,
};

/** Runs the simulation until SUMO ends, --end, every named ego has arrived, or a signal.
 *  Never throws: fills `summary` (status, exit code, error, counts, times) and returns the exit
 *  code. The database keeps every step completed before a failure; a run that fails before its
 *  first step leaves no file. */
int RunDriver(const DriverOptions& options, RunSummary* summary);

/** The exit code and one-line message for an exception escaping a run or option parsing. */
int ExitCodeFor(std::exception_ptr error, std::string* message);

}  // namespace criticality::plugin
