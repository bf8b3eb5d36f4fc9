#pragma once
// What the closed loop does while it has control of an ego: which escape route it follows,
// the speed it commands along it and the route's lateral manoeuvre. SUMO-independent
// (unit-tested in avoidance_manoeuvre_test.cc); closed_loop.cc applies it through SumoWorld.
#include <vector>

#include "criticality/result.h"
#include "criticality/scene.h"

namespace criticality::plugin {

/** Whether the object contributing most to the ego's collision probability is behind the ego
 *  (its centre behind the ego's rear along the ego's heading). Braking harder than the
 *  followed route then raises the closing speed of the car coming up behind: the closed loop's
 *  mitigation (full braking when every route probably collides) is for threats ahead only. An
 *  object beside the ego's body is not behind it: a cyclist beside a truck's trailer passes
 *  ahead of the truck that brakes (truck_right_hook). The rear is the scene's ego box's (for
 *  an ego that is a chain, e.g. a tram, its first box's). False when no object contributes. */
bool MainThreatBehind(const Scene& scene, const Result& result);

/** The lane an escape route ends up in and how it gets there. */
struct LateralPlan {
  int direction{0};  ///< -1 right, +1 left, 0 the route keeps its lane
  /** Seconds after the route's start when its lateral offset first reaches half the lane
   *  width toward the target lane (its centre crosses the boundary); the horizon's end when
   *  it never does. */
  double cross_s{0.0};
  /** Seconds after the route's start when its lateral offset first reaches 90 % of its
   *  largest value toward the target lane: the manoeuvre's duration. */
  double duration_s{0.0};
  /** Its lateral offset at the end of the horizon (m, positive left). */
  double final_offset_m{0.0};
};
/** direction: the first non-zero EscapeRoute::target_lanes entry (the lane of the section
 *  the route heads for); times from its lateral offset and the own lane's width. */
LateralPlan LateralPlanOf(const EscapeRoute& route, double lane_width_m);

/** The route to follow: the best ranked one (Result::escape_routes is ranked by collision
 *  probability, then own probability) that can be executed; a route that leaves the lane
 *  only when `may_steer`. Returns nullptr when none qualifies. */
const EscapeRoute* ChooseRoute(const std::vector<EscapeRoute>& ranked, bool may_steer);

/** The braking model of the escape routes (Params::latency_s, jerk_mps3). */
struct BrakeModel {
  double latency_s{0.2};
  double jerk_mps3{30.0};
};

struct SpeedInputs {
  double speed_mps{0.0};  ///< the ego's speed now
  /** SUMO's own choice for the next step (its model, a route's stop, a speed a scenario
   *  forces); +inf when unknown. */
  double own_speed_mps{0.0};
  /** The followed route's target acceleration (EscapeRoute::profile_accel_mps2); >= 0: the
   *  route does not brake. */
  double route_accel_mps2{0.0};
  double emergency_decel_mps2{9.0};  ///< the vehicle type's emergencyDecel (> 0)
  double elapsed_s{0.0};             ///< since the engagement began
  /** The acceleration commanded at the previous step of this engagement (0 at its start). */
  double previous_accel_mps2{0.0};
  /** A speed of ours is already commanded in this engagement. */
  bool active{false};
};

struct SpeedCommand {
  bool command{false};  ///< false: leave the speed to SUMO (no braking of ours this step)
  double speed_mps{0.0};
  double accel_mps2{0.0};  ///< ours (before the minimum with SUMO's own choice)
};

/** The speed for the next step: min(SUMO's own choice, ours), ours = speed + a dt where a
 *  follows the route's acceleration, changing at most by the jerk limit per second and never
 *  below minus the emergency deceleration; and never below speed - emergencyDecel dt, also
 *  where SUMO's own choice is lower (its safe speed or a scenario's forced speed asking for
 *  more than the vehicle can brake: the vehicle brakes at its emergencyDecel then). Nothing is commanded before the first braking: until
 *  the route brakes and the brake latency has passed since the engagement began. Once active,
 *  a command every step until the engagement ends (a route that stops braking ramps the
 *  deceleration off, and one that accelerates lets SUMO's own choice win again), so the speed
 *  control does not switch back and forth within an engagement. */
SpeedCommand ClosedLoopSpeed(const SpeedInputs& in, const BrakeModel& model, double step_s);

}  // namespace criticality::plugin
