#pragma once
// What the co-simulation loop itself needs: which SUMO to run or attach to, where the results
// go, when to stop, the scenario's scripted events, and the scenario's metadata (recorded for
// tests and evaluations, never acted on).
#include <string>
#include <vector>

#include "plugin/script/scenario_event.h"

namespace criticality::plugin {

struct RunConfig {
  std::string sumo_config;             ///< -c; relative paths in a --config file are relative to it
  std::vector<std::string> sumo_args;  ///< passed through to SUMO (after --)
  std::string connect;                 ///< HOST:PORT of a running SUMO ("" : run SUMO in-process)
  std::string output;                  ///< SQLite file, required
  double end_time_s{-1.0};             ///< stop at this simulated time (<0: when SUMO is done)
  std::vector<ScenarioEvent> events;
  /** Scenario metadata: "", "collision" or "no-collision"; the ID of the vehicle or person the
   *  ego is expected to collide with; the end of the scenario's quiet phase (s: nothing
   *  critical happens before it, so a warning that starts earlier is a false alarm); a
   *  category: static-object, moving-object, pedestrian or free. */
  std::string expect;
  std::string expect_partner;
  double quiet_until_s{0.0};
  std::string category;
  bool progress{true};       ///< progress line on a terminal
  /** Estimate step k while SUMO makes step k+1 (not under --act brake, whose commands need the
   *  results first); false: --no-pipeline. */
  bool pipeline{true};
  std::string command_line;  ///< for the runs table
};

}  // namespace criticality::plugin
