#pragma once
// The one-line JSON summary that ends standard output on every exit of a run, failures
// included (keys in plugin/README.md), and in the database's runs.summary.
#include <optional>
#include <string>

namespace criticality::plugin {

/** Wall time per stage of the step, summed over the run (seconds). */
struct StageTimes {
  double sumo_s{0.0};      ///< Simulation::step
  double observe_s{0.0};   ///< SUMO's reports, reading the egos and what is around them
  double scenes_s{0.0};    ///< building the scenes
  double estimate_s{0.0};  ///< the estimator
  double act_s{0.0};       ///< warnings, publishing, braking
  double record_s{0.0};    ///< the database (and scene files)
};

struct RunSummary {
  std::string status{"failed"};  ///< completed | interrupted | failed
  int exit_code{1};
  std::string error;       ///< one line; empty when none
  std::string end_reason;  ///< see plugin/README.md; empty before the run started
  double sim_time_s{0.0};
  long long steps{0};
  long long egos{0};
  long long estimates{0};
  long long shortcut_estimates{0};  ///< answered p = 0 without trajectories (no object in reach)
  long long objects_out_of_reach{0};
  long long invalid_objects{0};  ///< object reads left out of scenes (NaN values)
  long long warnings{0};
  long long actions{0};
  long long collisions{0};
  long long ego_collisions{0};
  long long ego_events{0};
  StageTimes times;
  double wall_s{0.0};
  double cpu_s{0.0};  ///< user + system CPU time of the process, every thread
  double estimator_ms_sum{0.0};
  double estimator_ms_max{0.0};
  double max_rss_mb{0.0};
  std::optional<bool> expectation_met;
  std::string category;
  std::string output;  ///< the database; empty when none was kept
};

/** One line of JSON, no newline. */
std::string SummaryJson(const RunSummary& s);

}  // namespace criticality::plugin
