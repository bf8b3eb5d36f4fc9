#pragma once
// What the act stage hands on to the record stage: one row per estimated ego, the warning
// episodes' changes, and the closed loop's actions. Plain data; the results database stores
// them as they are (plugin/record/results_db.h).
#include <string>
#include <vector>

namespace criticality::plugin {

/** One ego's row of the step (the steps table). */
struct EgoStep {
  std::string ego;
  double speed_mps{0.0};
  double p_collision{0.0};
  double p_reference{0.0};
  double unavoidability{0.0};
  double estimator_ms{0.0};
  int objects{0};           ///< objects in the scene
  int objects_in_reach{0};  ///< of those, not left out by the exact reach shortcut
  bool shortcut{false};     ///< answered without trajectories (no object in reach)
  bool acting{false};       ///< the closed loop has control
  /** The object with the largest share of p (criticality/result.h MainObject); "": none (p = 0).
   *  A collision's anticipation counts from the first step of a warning at which its partner
   *  was this object (plugin/record/result_views.sql). */
  std::string main_object;
};

enum class WarningChange { kOpen, kPeak, kClose };
struct WarningEvent {
  std::string ego;
  WarningChange change{WarningChange::kOpen};
  double p_collision{0.0};    ///< the --warn-on estimate (kOpen, kPeak: the new peak)
  double x_m{0.0}, y_m{0.0};  ///< where the ego was (kOpen)
  std::string edge;           ///< its edge (kOpen)
  std::string object;         ///< the object with the largest share of p (kOpen; "": none)
};

/** One action of the closed loop (--act brake), as the actions table records it. */
struct ActionEvent {
  std::string ego;
  std::string kind;        ///< brake | steer | release
  double accel_mps2{0.0};  ///< brake: the deceleration commanded (negative); else 0
  double speed_mps{0.0};   ///< the ego's speed before
  /** The speed after: brake: the speed commanded for the next step (min of SUMO's own choice
   *  and ours); release: SUMO's own choice, handed back; steer: unchanged (= speed_mps). */
  double speed_after_mps{0.0};
  double p_collision{0.0};  ///< the --warn-on estimate that drove the decision
  std::string lane_before;
  /** steer: the target lane (or "LANE +0.80 m" for a sublane offset); else lane_before. */
  std::string lane_after;
  /** The escape route followed (EscapeRoute::ego_trajectory; -1: none, emergency braking),
   *  its collision probability and its own probability. */
  int route{-1};
  double route_collision_probability{0.0};
  double route_probability{0.0};
  /** What the closed loop changed of the user's settings, or how it executed the route:
   *  e.g. "speed mode 31 kept (bit 2: decel raised to emergencyDecel while braking)", "lane-change mode 0 kept". */
  std::string detail;
};

struct ActOutcome {
  std::vector<EgoStep> steps;
  std::vector<WarningEvent> warnings;
  std::vector<ActionEvent> actions;
};

}  // namespace criticality::plugin
