#pragma once
// Stage 4 of a step: what the driver does with the estimates. Warning episodes (hysteresis
// between --warn-threshold and --warn-release), the criticality published to SUMO, and under
// --act brake the closed loop: when to take control (avoidance_policy.h), what to do with it
// (avoidance_manoeuvre.h: the escape route's braking and lane change) and handing it back. An
// ego that arrives, vanishes or starts a teleport ends its episode and its engagement.
#include <map>
#include <set>
#include <string>
#include <vector>

#include "criticality/result.h"
#include "plugin/avoidance_manoeuvre.h"
#include "plugin/avoidance_policy.h"
#include "plugin/driver_options.h"
#include "plugin/observe_stage.h"
#include "plugin/scene_stage.h"
#include "plugin/sumo_world.h"

namespace criticality::plugin {

/** One ego's row of the step. */
struct EgoStep {
  const ObjectSnapshot* ego{nullptr};
  double p_collision{0.0};
  double p_reference{0.0};
  double unavoidability{0.0};
  double estimator_ms{0.0};
  int objects{0};
  int objects_in_reach{0};
  bool shortcut{false};  ///< answered without trajectories (no object in reach)
  bool acting{false};
};

enum class WarningChange { kOpen, kPeak, kClose };
struct WarningEvent {
  std::string ego;
  WarningChange change{WarningChange::kOpen};
  double p_collision{0.0};
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
   *  e.g. "speed mode 0 -> 0 (bit 2 cleared)", "lane-change mode 0 kept". */
  std::string detail;
};

struct ActOutcome {
  std::vector<EgoStep> steps;
  std::vector<WarningEvent> warnings;
  std::vector<ActionEvent> actions;
};

class ActStage {
 public:
  ActStage(const DriverOptions& options, SumoWorld* world);
  ActOutcome Run(const Observation& obs, const SceneBatch& batch,
                 const std::vector<Result>& results);
  /** Egos whose warning episode is open (to close them when the run ends). */
  std::vector<std::string> OpenEpisodes() const;

 private:
  struct EgoState {
    explicit EgoState(const AvoidancePolicyConfig& c) : policy(c) {}
    bool warning{false};
    double peak{0.0};
    double below_release_since{-1.0};  ///< time p fell below --warn-release (-1: it is not)
    AvoidancePolicy policy;
    bool braking{false};         ///< a deceleration of ours is commanded
    bool commanding{false};      ///< a speed of ours is commanded (braking or handing back)
    bool handing_back{false};    ///< released, ramping up to a speed the scenario forces
    double previous_accel{0.0};  ///< the deceleration commanded at the previous step
    bool steered{false};         ///< the engagement's lane change is decided
    bool steer_pending{false};   ///< ... and waits for steer_at_s
    double steer_at_s{0.0};
    int steer_lane{0};
    double steer_hold_s{0.0};
    ActionEvent steer_row;
  };
  EgoState& StateOf(const std::string& ego);
  /** The closed loop for one ego at time t (--act brake). */
  void Avoid(double t, const ObjectSnapshot& ego, const Scene& scene, const Result& r, double p,
             EgoState* s, ActOutcome* out);
  /** Gives the speed back to SUMO; where SUMO's own choice is a speed the scenario forces
   *  above what the type's accel reaches in one step (speed mode 0 would jump to it), commands
   *  that step of the ramp instead and returns false. */
  bool HandBack(const std::string& ego, const VehicleControl& c, double v);
  static constexpr double kJumpMargin = 0.5;    // m/s
  static constexpr double kStandstill = 0.1;    // m/s
  static constexpr double kBrakingAccel = 0.5;  // m/s^2: a route below -this still brakes
  static constexpr double kSameRisk = 0.01;     // collision probability: as safe as the best
  static constexpr double kMitigation = 0.5;    // route collision probability: brake fully
  /** Whether the closed loop can execute a route: it keeps its lane, or (steering allowed) it
   *  goes to a lane of the same edge. */
  bool Executable(const EscapeRoute& e, const VehicleControl& c) const;
  /** Whether an executable route as safe as the best (within kSameRisk) does not brake. */
  bool AnyNonBrakingRoute(const std::vector<EscapeRoute>& ranked, const VehicleControl& c) const;

  const DriverOptions& options_;
  SumoWorld* world_;
  double dt_{0.1};
  AvoidancePolicyConfig policy_config_;
  BrakeModel brake_model_;
  std::map<std::string, EgoState> state_;
  std::set<std::string> release_after_teleport_;
};

}  // namespace criticality::plugin
