#pragma once
// The co-simulation loop: each step, SUMO moves, then the stages run in the order data flows:
// observe (plugin/observe/) -> scenes (plugin/scenes/) -> estimate (plugin/estimate/) ->
// act (plugin/act/) -> record (plugin/record/). Scripted events (plugin/script/) are applied
// before the step they are due in. Errors end the run with the exit code ExitCodeFor gives.
#include <functional>
#include <memory>

#include "plugin/options/driver_options.h"
#include "plugin/run/run_summary.h"
#include "plugin/sumo/sumo_world.h"

namespace criticality::plugin {

/** Starts or attaches to SUMO as `run` says (plugin/sumo/: libsumo or libtraci; tests: a fake
 *  world). Throws SumoError when it cannot. */
using OpenWorld = std::function<std::unique_ptr<SumoWorld>(const RunConfig& run)>;

/** Runs the simulation until SUMO ends, --end, every named ego has arrived, or a signal.
 *  Never throws: fills `summary` (status, exit code, error, counts, times) and returns the exit
 *  code. The database keeps every step completed before a failure; a run that fails before its
 *  first step leaves no file. */
int RunDriver(const DriverOptions& options, RunSummary* summary, const OpenWorld& open);

}  // namespace criticality::plugin
