#pragma once
// The closed loop (--act brake), per ego, through SumoWorld: when to take control
// (avoidance_policy.h), what to do with it (avoidance_manoeuvre.h: the escape route's braking
// and lane change), and handing it back. Each ego's engagement is a state machine:
//
//   idle --p >= brake threshold--> engaged --policy releases, speed handed back--> idle
//   engaged --policy releases, but the scenario forces a speed above what the type's accel
//            reaches in one step, or above SUMO's car following--> handing back (ramping up
//            at accel, no faster than SUMO's car following) --ramp done--> idle
//   handing back --p >= brake threshold--> engaged
//
// Within an engagement:
//  - speed: nothing of ours until the route brakes and its brake latency has passed; from the
//    first braking on (`braking_started`) a speed of ours every step (`speed_in_force`) until
//    the engagement ends; a threat from behind gets none (braking would raise its closing speed);
//  - lane change: none -> pending (decided, waits until the vehicle should start to cross) ->
//    done (changeLane sent; with the sublane model at once). Decided once per engagement.
// An ego that leaves ends its engagement; one whose speed was commanded when its teleport
// started gets its speed handed back when the teleport ends (SUMO keeps a commanded speed).
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "criticality/result.h"
#include "criticality/scene.h"
#include "plugin/act/act_config.h"
#include "plugin/act/act_outcome.h"
#include "plugin/act/avoidance_manoeuvre.h"
#include "plugin/act/avoidance_policy.h"
#include "plugin/scenes/object_snapshot.h"
#include "plugin/sumo/sumo_world.h"

namespace criticality::plugin {

class ClosedLoop {
 public:
  enum class Phase { kIdle, kEngaged, kHandingBack };
  enum class LaneChange { kNone, kPending, kDone };

  /** The --warn-on estimate of a scene (for ClosedLoopConfig::hand_back_check). */
  using SceneRisk = std::function<double(const Scene&)>;

  /** `hand_back_risk` empty: no hand-back check (as with hand_back_check false). */
  ClosedLoop(const ClosedLoopConfig& config, SumoWorld* world, double step_s,
             SceneRisk hand_back_risk = {});
  /** One step for `ego`: `p` is the --warn-on estimate of `r`, the result of `scene`. */
  void Step(double t, const ObjectSnapshot& ego, const Scene& scene, const Result& r, double p,
            std::vector<ActionEvent>* actions);
  /** The ego left the simulation (arrive, vanish) or its teleport started: its engagement ends.
   */
  void Leave(const std::string& ego, bool teleport);
  /** The ego's teleport ended: a speed of ours still in force from before is handed back. */
  void TeleportEnded(const std::string& ego);
  /** Whether the closed loop has control of the ego (steps.acting). */
  bool Acting(const std::string& ego) const;
  Phase PhaseOf(const std::string& ego) const;
  LaneChange LaneChangeOf(const std::string& ego) const;

  /** Below this speed (m/s) an ego stands. */
  static constexpr double kStandstill = 0.1;

 private:
  struct PendingChange {
    double at_s{0.0};
    int lane{0};
    double hold_s{0.0};
    ActionEvent row;
  };
  struct Engagement {
    explicit Engagement(const AvoidancePolicyConfig& c) : policy(c) {}
    AvoidancePolicy policy;
    Phase phase{Phase::kIdle};
    bool braking_started{false};  ///< a deceleration of ours was commanded in this engagement
    bool speed_in_force{false};   ///< a speed of ours is commanded (braking, or a ramp up)
    double previous_accel{0.0};   ///< the acceleration commanded at the previous step
    LaneChange lane_change{LaneChange::kNone};
    PendingChange pending;
    double hand_back_p{-1.0};  ///< this step's HandBackRisk; -1: none made this step
    double engaged_p{0.0};     ///< the estimate that took control (the brake row reports it)
  };
  // What one step of an engaged ego sees.
  struct Now {
    double t{0.0};
    const ObjectSnapshot* ego{nullptr};
    const Scene* scene{nullptr};
    const Result* result{nullptr};
    double p{0.0};
    VehicleControl control;
    double v() const { return ego->state.speed_mps; }
  };

  Engagement& StateOf(const std::string& ego);
  ActionEvent Row(const Now& n, const std::string& kind, const EscapeRoute* route) const;
  /** Whether the policy may hand control back now (plugin/README.md, Closed loop); keeps the
   *  hand-back check's estimate in s->hand_back_p. */
  bool MayRelease(const Now& n, Engagement* s) const;
  /** The --warn-on estimate of the scene with the ego as SUMO would drive it once handed back:
   *  its acceleration that of the hand-back ramp's next step (HandBackSpeed). While we brake the
   * estimate reads our braking as the ego's own, so a threat that handing back would drive into
   * again (a crossing tram) looked gone. */
  double HandBackRisk(const Now& n) const;
  void Engage(Engagement* s) const;
  void Release(const Now& n, Engagement* s, std::vector<ActionEvent>* actions);
  /** While engaged: the route, its lane change and its speed. */
  void Control(const Now& n, Engagement* s, std::vector<ActionEvent>* actions);
  /** The route to follow, best executable first; a lane change needs a lane to go to. */
  const EscapeRoute* Route(const Now& n, const Engagement& s, const LaneChanging& lc,
                           LateralPlan* plan) const;
  void Steer(const Now& n, const EscapeRoute& route, const LateralPlan& plan,
             const LaneChanging& lc, bool threat_behind, Engagement* s,
             std::vector<ActionEvent>* actions);
  void CommandSpeed(const Now& n, const EscapeRoute* route, bool threat_behind, Engagement* s,
                    std::vector<ActionEvent>* actions);
  /** Gives the speed back to SUMO; where SUMO's own choice is a speed the scenario forces
   *  above the next speed of the hand-back ramp (HandBackSpeed; speed mode 0 would jump to
   *  it), commands that speed instead and returns false. */
  bool HandBack(const std::string& ego, const VehicleControl& c, double v);
  /** The hand-back ramp's next speed: one step at the type's accel, capped by SUMO's car
   *  following behind the leader (VehicleControl::follow_speed_mps), braking at most at
   *  emergencyDecel. */
  double HandBackSpeed(const VehicleControl& c, double v) const;
  /** Whether the closed loop can execute a route: it keeps its lane, or (steering allowed) it
   *  goes to a lane of the same edge. */
  bool Executable(const EscapeRoute& e, const VehicleControl& c) const;
  /** Whether the estimate still sees the threat (p at or above the release threshold): only
   *  then does a manoeuvre, lateral or braking, start. */
  bool ThreatSeen(const Now& n) const { return n.p >= config_.policy.release_threshold; }
  /** Whether an executable route as safe as the best (within kSameRisk) does not brake. */
  bool AnyNonBrakingRoute(const std::vector<EscapeRoute>& ranked, const VehicleControl& c) const;

  static constexpr double kJumpMargin = 0.5;    // m/s
  static constexpr double kBrakingAccel = 0.5;  // m/s^2: a route below -this still brakes
  static constexpr double kSameRisk = 0.01;     // collision probability: as safe as the best
  static constexpr double kMitigation = 0.5;    // route collision probability: brake fully

  ClosedLoopConfig config_;
  SceneRisk hand_back_risk_;
  SumoWorld* world_;
  double dt_;
  std::map<std::string, Engagement> egos_;
  std::set<std::string> release_after_teleport_;
};

}  // namespace criticality::plugin
