#pragma once
// What the act stage needs to know: what to do with the estimates (--act), which estimate a
// warning reads and its thresholds, and the closed loop's settings.
#include <string>

#include "criticality/result.h"
#include "plugin/act/avoidance_manoeuvre.h"
#include "plugin/act/avoidance_policy.h"

namespace criticality::plugin {

enum class Act { kNone, kWarn, kBrake };
/** none | warn | brake */
std::string ActName(Act act);

/** Which estimate the warning (and --act brake) reads: p_collision (the paper's p_cra, the
 *  default: estimator/ALGORITHM.md "Outputs that serve decisions" says why), p_reference or
 *  unavoidability. */
enum class WarnOn { kPCollision, kPReference, kUnavoidability };
/** The estimate a WarnOn names, from a result. */
double WarnValue(WarnOn on, const Result& r);
/** p_collision | p_reference | unavoidability */
std::string WarnOnName(WarnOn on);

/** Warning episodes (plugin/act/warning_episodes.h). */
struct WarningConfig {
  double threshold{0.9};  ///< --warn-threshold: opens an episode
  double release{0.72};   ///< --warn-release: below it the episode may end
  /** --warn-release-after: how long the estimate must stay below `release` (s); 0: the first
   *  step below ends the episode. */
  double release_after_s{0.3};
};

/** The closed loop (plugin/act/closed_loop.h). */
struct ClosedLoopConfig {
  AvoidancePolicyConfig policy;  ///< --brake-threshold, --brake-release, --act-hold, ...
  bool no_steer{false};          ///< --no-steer: follow only routes that keep their lane
  /** The escape routes' braking model (Params::latency_s, jerk_mps3). */
  BrakeModel brake;
  /** Control is handed back only when the scene re-estimated with the ego as SUMO would drive
   *  it from there (its hand-back ramp's acceleration) is below the release threshold
   *  (ClosedLoop::HandBackRisk); --no-hand-back-check: the estimate under our braking only. */
  bool hand_back_check{true};
};

struct ActConfig {
  Act act{Act::kWarn};
  WarnOn warn_on{WarnOn::kPCollision};
  WarningConfig warning;
  ClosedLoopConfig closed_loop;
};

}  // namespace criticality::plugin
