#pragma once
// The one-line JSON summary that ends standard output on every exit of a run, failures
// included (keys in plugin/README.md), and in the database's runs.summary.
#include <cstdio>
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
  /** Pipelined: how long the loop waited for estimates after SUMO's next step and its
   *  observation (the part of estimate_s that SUMO did not hide). */
  double estimate_wait_s{0.0};
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
  /** Exposure of the estimation: ego estimates x step length (hours), and the distance the
   *  estimated egos covered (speed x step length, km). Rates per vehicle-hour and per
   *  vehicle-km divide by these. */
  double vehicle_hours{0.0};
  double vehicle_km{0.0};
  long long shortcut_estimates{0};  ///< answered p = 0 without trajectories (no object in reach)
  long long objects_out_of_reach{0};
  long long invalid_objects{0};  ///< object reads left out of scenes (NaN values)
  /** Object reads whose yaw rate or acceleration was made plausible (object_reading.h). */
  long long conditioned_states{0};
  long long parked_objects{0};       ///< vehicle reads left out: parked beside the road
  long long other_class_objects{0};  ///< vehicle reads left out: no road user (ship, aircraft)
  long long parked_egos{0};          ///< ego reads not estimated: the ego was parked
  long long warnings{0};
  long long actions{0};
  long long collisions{0};
  long long ego_collisions{0};
  long long ego_events{0};
  StageTimes times;
  bool pipelined{false};  ///< estimates overlapped SUMO's next step (RunConfig::pipeline)
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

/** What the progress line on a terminal shows while a run goes on. */
struct ProgressState {
  double time_s{0.0};   ///< the last step's stamp
  double begin_s{0.0};  ///< the simulation's time when the run started
  double end_s{-1.0};   ///< when the run ends (--end or SUMO's end time); < 0: not known
  double wall_s{0.0};   ///< wall time since the run started
  long long steps{0}, egos{0}, warnings{0}, collisions{0};
};

/** The progress line on standard error (a terminal). While it shows, whatever is written to
 *  standard error between Hold() and Release() (a step: SUMO's warnings, the stages' notes) goes
 *  to a temporary file and is written out at Release(), the line cleared first, so that SUMO's
 *  messages stand on lines of their own instead of running into it; Show() draws the line
 *  again. Off (`on` false, or no temporary file): every call does nothing. */
class ProgressLine {
 public:
  explicit ProgressLine(bool on);
  ~ProgressLine();  ///< releases what is held
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  bool on() const { return on_; }
  void Hold();
  /** True when something had been written meanwhile (then Show() at once). */
  bool Release();
  void Show(const std::string& text);
  /** The last line stays; what follows starts below it. */
  void End();

 private:
  bool on_{false}, holding_{false}, shown_{false};
  std::FILE* held_{nullptr};
  int terminal_{-1};
};

/** "t 12.3 / 120 s  10 %  ETA 1:42  34 steps/s  egos 3  warnings 1  collisions 0": simulated
 *  time, end time, share done and the time left at the pace so far (no end time: simulated
 *  time and pace only). One line, no line break. */
std::string ProgressText(const ProgressState& p);

}  // namespace criticality::plugin
