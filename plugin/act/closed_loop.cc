#include "plugin/act/closed_loop.h"

#include <algorithm>
#include <cstdio>
#include <utility>

namespace criticality::plugin {
namespace {

std::string SpeedModeText(int user) {
  return "speed mode " + std::to_string(user) + " kept" +
         ((user & 4) ? " (bit 2: decel raised to emergencyDecel while braking)"
                     : " (bit 2 off: decelerations unbounded by SUMO)");
}

std::string Fixed(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%+.2f", x);
  return b;
}

}  // namespace

ClosedLoop::ClosedLoop(const ClosedLoopConfig& config, SumoWorld* world, double step_s,
                       SceneRisk hand_back_risk)
    : config_(config), hand_back_risk_(std::move(hand_back_risk)), world_(world), dt_(step_s) {
  AvoidancePolicy check(config_.policy);  // throws for a config that cannot work
}

ClosedLoop::Engagement& ClosedLoop::StateOf(const std::string& ego) {
  auto it = egos_.find(ego);
  if (it == egos_.end()) it = egos_.emplace(ego, Engagement(config_.policy)).first;
  return it->second;
}

bool ClosedLoop::Acting(const std::string& ego) const {
  auto it = egos_.find(ego);
  return it != egos_.end() && it->second.policy.engaged();
}

ClosedLoop::Phase ClosedLoop::PhaseOf(const std::string& ego) const {
  auto it = egos_.find(ego);
  return it == egos_.end() ? Phase::kIdle : it->second.phase;
}

ClosedLoop::LaneChange ClosedLoop::LaneChangeOf(const std::string& ego) const {
  auto it = egos_.find(ego);
  return it == egos_.end() ? LaneChange::kNone : it->second.lane_change;
}

void ClosedLoop::Leave(const std::string& ego, bool teleport) {
  auto it = egos_.find(ego);
  if (teleport && it != egos_.end() && it->second.speed_in_force) {
    release_after_teleport_.insert(ego);
  }
  if (!teleport) release_after_teleport_.erase(ego);
  if (it != egos_.end()) egos_.erase(it);
}

void ClosedLoop::TeleportEnded(const std::string& ego) {
  if (release_after_teleport_.erase(ego)) world_->ReleaseSpeed(ego);
}

void ClosedLoop::Step(double t, const ObjectSnapshot& ego, const Scene& scene, const Result& r,
                      double p, std::vector<ActionEvent>* actions) {
  Engagement& s = StateOf(ego.id);
  if (s.phase == Phase::kIdle && p < config_.policy.engage_threshold) return;
  Now n;
  n.t = t;
  n.ego = &ego;
  n.scene = &scene;
  n.result = &r;
  n.p = p;
  n.control = world_->ReadControl(ego.id);
  switch (s.policy.Step(t, p, MayRelease(n, &s))) {
    case AvoidanceDecision::kIdle:  // only while handing back
      if (HandBack(ego.id, n.control, n.v())) {
        s.phase = Phase::kIdle;
        s.speed_in_force = false;
      }
      return;
    case AvoidanceDecision::kRelease:
      Release(n, &s, actions);
      return;
    case AvoidanceDecision::kEngage:
      Engage(&s);
      s.engaged_p = p;
      Control(n, &s, actions);
      return;
    case AvoidanceDecision::kHold:
      Control(n, &s, actions);
      return;
  }
}

bool ClosedLoop::MayRelease(const Now& n, Engagement* s) const {
  // The release waits, unless the engagement's lane change is done (the old lane's danger is
  // gone), while every escape route as safe as the best one that the closed loop can execute
  // brakes (p, computed with the ego braking, says little about handing back), and at a
  // standstill while SUMO's own choice is a speed the scenario forces (its driver would drive
  // on into what stopped it: an emergency brake holds the vehicle then). Where the release
  // could come (p below its threshold), it also waits while handing back would be critical
  // again (HandBackRisk at or above the release threshold).
  const VehicleControl& c = n.control;
  s->hand_back_p = -1.0;  // this step's estimate only (the release row reports it)
  const bool changed_lane = s->lane_change == LaneChange::kDone;
  const bool still_braking = !changed_lane && !AnyNonBrakingRoute(n.result->escape_routes, c);
  const bool held_stopped = s->speed_in_force && n.v() < kStandstill && c.forced &&
                            c.own_speed_mps > n.v() + c.accel_mps2 * dt_ + kJumpMargin;
  if (still_braking || held_stopped) return false;
  if (!config_.hand_back_check || !hand_back_risk_ || !s->speed_in_force ||
      n.p >= config_.policy.release_threshold)
    return true;
  s->hand_back_p = HandBackRisk(n);
  return s->hand_back_p < config_.policy.release_threshold;
}

double ClosedLoop::HandBackRisk(const Now& n) const {
  // SUMO's own choice of speed (its model, or the speed the scenario forces), reached no
  // faster than the hand-back ramp.
  const VehicleControl& c = n.control;
  const double lowest = std::max(0.0, n.v() - c.emergency_decel_mps2 * dt_);
  const double next = std::max(lowest, std::min(c.resume_speed_mps, HandBackSpeed(c, n.v())));
  const double accel = (next - n.v()) / dt_;
  Scene handed_back = *n.scene;
  // What the driver's expected acceleration says (a leader, a stop line) still holds where it
  // asks for less (ObjectState::expected_accel_mps2).
  handed_back.ego.state.accel_mps2 = accel;
  return hand_back_risk_(handed_back);
}

void ClosedLoop::Engage(Engagement* s) const {
  // A speed of ours still ramping up from the previous engagement stays in force.
  s->phase = Phase::kEngaged;
  s->braking_started = false;
  s->previous_accel = 0.0;
  s->lane_change = LaneChange::kNone;
}

ActionEvent ClosedLoop::Row(const Now& n, const std::string& kind,
                            const EscapeRoute* route) const {
  ActionEvent a;
  a.ego = n.ego->id;
  a.kind = kind;
  a.speed_mps = a.speed_after_mps = n.v();
  a.p_collision = n.p;
  a.lane_before = a.lane_after = n.control.lane;
  if (route) {
    a.route = route->ego_trajectory;
    a.route_collision_probability = route->collision_probability;
    a.route_probability = route->probability;
  }
  return a;
}

void ClosedLoop::Release(const Now& n, Engagement* s, std::vector<ActionEvent>* actions) {
  const VehicleControl& c = n.control;
  // An engagement in which SUMO's own speed stayed the lower and nothing was steered did
  // nothing to release: no row.
  const bool acted = s->speed_in_force || s->lane_change != LaneChange::kNone;
  ActionEvent a = Row(n, "release", nullptr);
  a.detail = "control handed back";
  s->phase = Phase::kIdle;
  if (s->speed_in_force) {
    a.speed_after_mps = c.own_speed_mps;
    if (HandBack(n.ego->id, c, n.v())) {
      s->speed_in_force = false;
      a.detail += ": speed mode " + std::to_string(c.speed_mode) + " restored, " +
                  (c.forced ? "the scenario's speed" : "setSpeed(-1)");
    } else {
      s->phase = Phase::kHandingBack;
      a.speed_after_mps = HandBackSpeed(c, n.v());
      a.detail += " at the type's accel " + Fixed(c.accel_mps2).substr(1) + " m/s^2 up to the " +
                  Fixed(c.own_speed_mps).substr(1) +
                  " m/s the scenario forces, no faster than SUMO's car following (speed mode " +
                  std::to_string(c.speed_mode) + " then restored)";
    }
  }
  if (s->lane_change == LaneChange::kPending) a.detail += "; the pending lane change dropped";
  if (s->hand_back_p >= 0.0) {
    char b[64];
    std::snprintf(b, sizeof b, "; estimate if handed back %.3f", s->hand_back_p);
    a.detail += b;
  }
  s->hand_back_p = -1.0;
  if (acted) actions->push_back(a);
  s->braking_started = false;
  s->lane_change = LaneChange::kNone;
  s->previous_accel = 0.0;
}

const EscapeRoute* ClosedLoop::Route(const Now& n, const Engagement& s, const LaneChanging& lc,
                                     LateralPlan* plan) const {
  const VehicleControl& c = n.control;
  const std::vector<EscapeRoute>& routes = n.result->escape_routes;
  // The route's acceleration is followed after its lane change too (its lane change is not
  // repeated); only --no-steer restricts the choice to routes that keep their lane.
  const EscapeRoute* route = ChooseRoute(routes, !config_.no_steer);
  *plan = route ? LateralPlanOf(*route, c.lane_width_m) : LateralPlan{};
  const int target = c.lane_index + plan->direction;
  if (plan->direction != 0 && s.lane_change == LaneChange::kNone && !lc.sublane &&
      (target < 0 || target >= c.lanes)) {
    route = ChooseRoute(routes, false);  // no such lane (e.g. counter traffic)
    *plan = route ? LateralPlanOf(*route, c.lane_width_m) : LateralPlan{};
  }
  return route;
}

void ClosedLoop::Control(const Now& n, Engagement* s, std::vector<ActionEvent>* actions) {
  // A threat from behind (the object contributing most is behind the ego): braking of ours
  // would only raise its closing speed, so SUMO keeps the speed, and a lane change out of its
  // way starts at once instead of when the route crosses the boundary.
  const bool threat_behind = MainThreatBehind(*n.scene, *n.result);
  const LaneChanging lc = world_->LaneChangingModel();
  LateralPlan plan;
  const EscapeRoute* route = Route(n, *s, lc, &plan);
  // A lateral manoeuvre answers a threat the estimate still sees: none starts while the loop
  // only waits to hand back (p below the release threshold during the hold).
  if (route && plan.direction != 0 && s->lane_change == LaneChange::kNone && ThreatSeen(n))
    Steer(n, *route, plan, lc, threat_behind, s, actions);
  if (s->lane_change == LaneChange::kPending && n.t + 1e-9 >= s->pending.at_s) {
    s->lane_change = LaneChange::kDone;
    world_->ChangeLane(n.ego->id, s->pending.lane, s->pending.hold_s);
    s->pending.row.speed_mps = s->pending.row.speed_after_mps = n.v();
    actions->push_back(s->pending.row);
  }
  CommandSpeed(n, route, threat_behind, s, actions);
}

void ClosedLoop::Steer(const Now& n, const EscapeRoute& route, const LateralPlan& plan,
                       const LaneChanging& lc, bool threat_behind, Engagement* s,
                       std::vector<ActionEvent>* actions) {
  const VehicleControl& c = n.control;
  ActionEvent a = Row(n, "steer", &route);
  const std::string lcm = "lane-change mode " + std::to_string(c.lane_change_mode) + " kept";
  char b[200];
  if (lc.sublane) {
    world_->ChangeSublane(n.ego->id, plan.final_offset_m - c.lateral_offset_m);
    s->lane_change = LaneChange::kDone;
    a.lane_after = c.lane + " " + Fixed(plan.final_offset_m) + " m";
    std::snprintf(b, sizeof b,
                  "sublane offset: the route's takes %.1f s, SUMO's moves at the type's "
                  "maxSpeedLat; ",
                  plan.duration_s);
    a.detail = b + lcm;
    actions->push_back(a);
    return;
  }
  // SUMO moves a changing vehicle over lanechange.duration (0: in one step): start so that it
  // crosses into the target lane when the route does.
  const int target = c.lane_index + plan.direction;
  s->lane_change = LaneChange::kPending;
  s->pending.at_s = threat_behind ? n.t : n.t + std::max(0.0, plan.cross_s - 0.5 * lc.duration_s);
  s->pending.lane = target;
  s->pending.hold_s = route.time_s.empty() ? 1.0 : route.time_s.back();
  a.lane_after = c.lane.substr(0, c.lane.rfind('_')) + "_" + std::to_string(target);
  std::snprintf(b, sizeof b,
                "lane change: the route crosses at %.1f s, done at %.1f s; SUMO's takes "
                "%.1f s (lanechange.duration); ",
                plan.cross_s, plan.duration_s, lc.duration_s);
  a.detail = b + lcm;
  if (threat_behind) a.detail += "; the main threat comes from behind: at once, no braking";
  s->pending.row = a;
}

void ClosedLoop::CommandSpeed(const Now& n, const EscapeRoute* route, bool threat_behind,
                              Engagement* s, std::vector<ActionEvent>* actions) {
  const VehicleControl& c = n.control;
  // Mitigation: when even the followed route probably collides, the lowest impact speed is
  // what is left to reach: brake as hard as the type allows; not when the main threat comes
  // from behind (braking would only raise its closing speed).
  const bool mitigate = route && route->collision_probability >= kMitigation;
  SpeedInputs in;
  in.speed_mps = n.v();
  in.own_speed_mps = c.own_speed_mps;
  in.route_accel_mps2 = route && !mitigate ? route->profile_accel_mps2 : -c.emergency_decel_mps2;
  in.emergency_decel_mps2 = c.emergency_decel_mps2;
  in.elapsed_s = n.t - s->policy.engaged_since_s();
  in.previous_accel_mps2 = s->previous_accel;
  in.active = s->braking_started;
  // Braking answers a threat the estimate still sees: it starts (after the latency) only while
  // p is at or above the release threshold, as a lateral manoeuvre does. At 1 s steps the
  // latency ends a whole step after the decision, and brakes began at p 0.000 there, stopping
  // a car from up to 9 m/s for a threat gone (bench/RESULTS.md, twenty-second stop).
  const SpeedCommand cmd = threat_behind || (!s->braking_started && !ThreatSeen(n))
                               ? SpeedCommand{}
                               : ClosedLoopSpeed(in, config_.brake, dt_);
  if (!cmd.command) {
    if (s->speed_in_force && HandBack(n.ego->id, c, n.v())) s->speed_in_force = false;
    return;
  }
  world_->CommandSpeed(n.ego->id, cmd.speed_mps);
  s->previous_accel = cmd.accel_mps2;
  if (!s->braking_started) {
    ActionEvent a = Row(n, "brake", route);
    a.accel_mps2 = cmd.accel_mps2;
    a.speed_after_mps = cmd.speed_mps;
    a.detail = SpeedModeText(c.speed_mode);
    if (!route) a.detail += "; no escape route to follow: emergencyDecel";
    if (mitigate) a.detail += "; the route probably collides: emergencyDecel (mitigation)";
    if (threat_behind)
      a.detail += "; the route probably collides, from behind: its own deceleration, no mitigation";
    if (c.forced) a.detail += "; the scenario forces " + Fixed(c.own_speed_mps).substr(1) + " m/s";
    // The row comes when the brake acts (after the latency, at the first step of the jerk
    // ramp): which step took control, and at what estimate.
    char b[96];
    std::snprintf(b, sizeof b, "; control taken at %.2f s at %.3f, the route's target %+.1f m/s^2",
                  s->policy.engaged_since_s(), s->engaged_p, in.route_accel_mps2);
    a.detail += b;
    actions->push_back(a);
  }
  s->braking_started = s->speed_in_force = true;
}

bool ClosedLoop::Executable(const EscapeRoute& e, const VehicleControl& c) const {
  const int direction = LateralPlanOf(e, c.lane_width_m).direction;
  if (direction == 0) return true;
  if (config_.no_steer) return false;
  const int target = c.lane_index + direction;
  return target >= 0 && target < c.lanes;  // a lane of the same edge (not counter traffic)
}

bool ClosedLoop::AnyNonBrakingRoute(const std::vector<EscapeRoute>& ranked,
                                    const VehicleControl& c) const {
  if (ranked.empty()) return true;  // nothing says braking is needed
  for (const EscapeRoute& e : ranked) {
    if (e.collision_probability > ranked.front().collision_probability + kSameRisk) break;
    if (e.profile_accel_mps2 >= -kBrakingAccel && Executable(e, c)) return true;
  }
  return false;
}

double ClosedLoop::HandBackSpeed(const VehicleControl& c, double v) const {
  // The ramp at the type's accel, no faster than SUMO's car following behind its leader: the
  // speeds of the ramp are ours, and a driver who takes the car back resumes behind it.
  const double lowest = std::max(0.0, v - c.emergency_decel_mps2 * dt_);
  return std::max(lowest, std::min(v + c.accel_mps2 * dt_, c.follow_speed_mps));
}

bool ClosedLoop::HandBack(const std::string& ego, const VehicleControl& c, double v) {
  if (c.forced) {
    const double ours = HandBackSpeed(c, v);
    if (c.own_speed_mps > ours + kJumpMargin) {
      world_->CommandSpeed(ego, ours);
      return false;
    }
  }
  world_->ReleaseSpeed(ego);
  return true;
}

}  // namespace criticality::plugin
