#include "plugin/act_stage.h"

#include <algorithm>
#include <cstdio>

namespace criticality::plugin {

namespace {
std::string SpeedModeText(int user) {
  return "speed mode " + std::to_string(user) + " -> " + std::to_string(user & ~4) +
         ((user & 4) ? " (bit 2 cleared: up to emergencyDecel)" : " (unchanged)");
}
std::string Fixed(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%+.2f", x);
  return b;
}
// The object with the largest share of p_collision ("" when none has any).
std::string MainObjectId(const Result& r) {
  const ObjectResult* main = MainObject(r);
  return main ? main->id : "";
}

}  // namespace

ActStage::ActStage(const DriverOptions& options, SumoWorld* world)
    : options_(options), world_(world), dt_(world->StepLength()) {
  policy_config_.engage_threshold = options.brake_threshold;
  policy_config_.release_threshold =
      options.brake_release < 0.0 ? 0.5 * options.brake_threshold : options.brake_release;
  policy_config_.min_hold_s = options.act_hold_s;
  policy_config_.release_after_s = options.act_release_after_s;
  AvoidancePolicy check(policy_config_);  // throws for a config that cannot work
  brake_model_.latency_s = options.params.latency_s;
  brake_model_.jerk_mps3 = options.params.jerk_mps3;
}

ActStage::EgoState& ActStage::StateOf(const std::string& ego) {
  auto it = state_.find(ego);
  if (it == state_.end()) it = state_.emplace(ego, EgoState(policy_config_)).first;
  return it->second;
}

std::vector<std::string> ActStage::OpenEpisodes() const {
  std::vector<std::string> open;
  for (const auto& [ego, s] : state_) {
    if (s.warning) open.push_back(ego);
  }
  return open;
}

ActOutcome ActStage::Run(const Observation& obs, const SceneBatch& batch,
                         const std::vector<Result>& results) {
  const DriverOptions& o = options_;
  ActOutcome out;
  // An ego that left, or is teleported, ends its episode; braking is handed back when a
  // teleported ego returns (SUMO keeps a commanded speed).
  for (const EgoEvent& e : obs.ego_events) {
    if (e.kind == EgoEventKind::kTeleportEnd && release_after_teleport_.erase(e.ego)) {
      world_->ReleaseSpeed(e.ego);
    }
    if (e.kind != EgoEventKind::kArrive && e.kind != EgoEventKind::kVanish &&
        e.kind != EgoEventKind::kTeleportStart)
      continue;
    auto it = state_.find(e.ego);
    if (it == state_.end()) continue;
    if (it->second.warning)
      out.warnings.push_back({e.ego, WarningChange::kClose, 0.0, 0.0, 0.0, "", ""});
    if (it->second.commanding && e.kind == EgoEventKind::kTeleportStart)
      release_after_teleport_.insert(e.ego);
    if (e.kind != EgoEventKind::kTeleportStart) release_after_teleport_.erase(e.ego);
    state_.erase(it);
  }

  for (size_t k = 0; k < batch.scenes.size(); ++k) {
    const ObjectSnapshot& ego = *batch.egos[k];
    const Result& r = results[k];
    const double p = WarnValue(o.warn_on, r);
    EgoState& s = StateOf(ego.id);
    if (o.act != Act::kNone) {
      if (p >= o.warn_threshold && !s.warning) {
        s.warning = true;
        s.peak = p;
        out.warnings.push_back({ego.id, WarningChange::kOpen, p, ego.state.x_m, ego.state.y_m,
                                ego.edge, MainObjectId(r)});
      } else if (s.warning && p > s.peak) {
        s.peak = p;
        out.warnings.push_back({ego.id, WarningChange::kPeak, p, 0.0, 0.0, "", ""});
      }
      // The episode ends once p has stayed below the release level for --warn-release-after.
      if (s.warning && p >= o.warn_release) s.below_release_since = -1.0;
      if (s.warning && p < o.warn_release) {
        if (s.below_release_since < 0.0) s.below_release_since = obs.time_s;
        if (obs.time_s - s.below_release_since >= o.warn_release_after_s - 1e-9) {
          s.warning = false;
          s.below_release_since = -1.0;
          out.warnings.push_back({ego.id, WarningChange::kClose, p, 0.0, 0.0, "", ""});
        }
      }
      world_->Publish(ego.id, p, s.warning);
    }
    if (o.act == Act::kBrake) Avoid(obs.time_s, ego, batch.scenes[k], r, p, &s, &out);
    EgoStep step;
    step.ego = &ego;
    step.p_collision = r.p_collision;
    step.p_reference = r.p_reference;
    step.unavoidability = r.unavoidability;
    step.estimator_ms = r.times.total_ms;
    step.objects = static_cast<int>(r.objects.size());
    for (const ObjectResult& obj : r.objects) step.objects_in_reach += obj.out_of_reach ? 0 : 1;
    step.shortcut = o.estimator.reach_shortcut && step.objects_in_reach == 0;
    step.acting = s.policy.engaged();
    out.steps.push_back(step);
  }
  return out;
}

bool ActStage::Executable(const EscapeRoute& e, const VehicleControl& c) const {
  const int direction = LateralPlanOf(e, c.lane_width_m).direction;
  if (direction == 0) return true;
  if (options_.no_steer) return false;
  const int target = c.lane_index + direction;
  return target >= 0 && target < c.lanes;  // a lane of the same edge (not counter traffic)
}

bool ActStage::AnyNonBrakingRoute(const std::vector<EscapeRoute>& ranked,
                                  const VehicleControl& c) const {
  if (ranked.empty()) return true;  // nothing says braking is needed
  for (const EscapeRoute& e : ranked) {
    if (e.collision_probability > ranked.front().collision_probability + kSameRisk) break;
    if (e.profile_accel_mps2 >= -kBrakingAccel && Executable(e, c)) return true;
  }
  return false;
}

bool ActStage::HandBack(const std::string& ego, const VehicleControl& c, double v) {
  const double reach = v + c.accel_mps2 * dt_;
  if (c.forced && c.own_speed_mps > reach + kJumpMargin) {
    world_->CommandSpeed(ego, reach);
    return false;
  }
  world_->ReleaseSpeed(ego);
  return true;
}

void ActStage::Avoid(double t, const ObjectSnapshot& ego, const Scene& scene, const Result& r,
                     double p, EgoState* s, ActOutcome* out) {
  const double v = ego.state.speed_mps;
  if (!s->policy.engaged() && !s->handing_back && p < policy_config_.engage_threshold) return;
  const VehicleControl c = world_->ReadControl(ego.id);
  // The release waits, unless the engagement's lane change is done, while every escape route
  // as safe as the best one that the closed loop can execute brakes (p, computed
  // with the ego braking, says little about handing back), and at a standstill while SUMO's own
  // choice is a speed the scenario forces (its driver would drive on into what stopped it: an
  // emergency brake holds the vehicle then).
  const bool changed_lane = s->steered && !s->steer_pending;  // the old lane's danger is gone
  const bool still_braking = !changed_lane && !AnyNonBrakingRoute(r.escape_routes, c);
  const bool held_stopped = s->commanding && v < kStandstill && c.forced &&
                            c.own_speed_mps > v + c.accel_mps2 * dt_ + kJumpMargin;
  const AvoidanceDecision d = s->policy.Step(t, p, !still_braking && !held_stopped);
  auto row = [&](const std::string& kind, const EscapeRoute* route) {
    ActionEvent a;
    a.ego = ego.id;
    a.kind = kind;
    a.speed_mps = a.speed_after_mps = v;
    a.p_collision = p;
    a.lane_before = a.lane_after = c.lane;
    if (route) {
      a.route = route->ego_trajectory;
      a.route_collision_probability = route->collision_probability;
      a.route_probability = route->probability;
    }
    return a;
  };
  if (d == AvoidanceDecision::kIdle) {  // only while handing back
    if (HandBack(ego.id, c, v)) s->handing_back = s->commanding = false;
    return;
  }
  if (d == AvoidanceDecision::kRelease) {
    // An engagement in which SUMO's own speed stayed the lower and nothing was steered did
    // nothing to release: no row.
    const bool acted = s->commanding || s->steered;
    ActionEvent a = row("release", nullptr);
    a.detail = "control handed back";
    if (s->commanding) {
      a.speed_after_mps = c.own_speed_mps;
      if (HandBack(ego.id, c, v)) {
        s->commanding = false;
        a.detail += ": speed mode " + std::to_string(c.speed_mode) + " restored, " +
                    (c.forced ? "the scenario's speed" : "setSpeed(-1)");
      } else {
        s->handing_back = true;
        a.speed_after_mps = v + c.accel_mps2 * dt_;
        a.detail += " at the type's accel " + Fixed(c.accel_mps2).substr(1) + " m/s^2 up to the " +
                    Fixed(c.own_speed_mps).substr(1) + " m/s the scenario forces (speed mode " +
                    std::to_string(c.speed_mode) + " then restored)";
      }
    }
    if (s->steer_pending) a.detail += "; the pending lane change dropped";
    if (acted) out->actions.push_back(a);
    s->braking = s->steer_pending = s->steered = false;
    s->previous_accel = 0.0;
    return;
  }
  if (d == AvoidanceDecision::kEngage) {
    s->handing_back = s->braking = false;
    s->previous_accel = 0.0;
    s->steered = s->steer_pending = false;
  }
  const double elapsed = t - s->policy.engaged_since_s();
  // A threat from behind (the object contributing most is behind the ego): braking of ours
  // would only raise its closing speed, so SUMO keeps the speed, and a lane change out of its
  // way starts at once instead of when the route crosses the boundary.
  const bool threat_behind = MainThreatBehind(scene, r);
  // The route: the best ranked one that can be executed; a lane change is decided once per
  // engagement (no lateral back and forth) and needs a lane of the same edge to go to.
  const LaneChanging lc = world_->LaneChangingModel();
  // The route's acceleration is followed after its lane change too (its lane change is not
  // repeated); only --no-steer restricts the choice to routes that keep their lane.
  const EscapeRoute* route = ChooseRoute(r.escape_routes, !options_.no_steer);
  LateralPlan plan;
  if (route) plan = LateralPlanOf(*route, c.lane_width_m);
  const int target = c.lane_index + plan.direction;
  if (plan.direction != 0 && !s->steered && !lc.sublane && (target < 0 || target >= c.lanes)) {
    route = ChooseRoute(r.escape_routes, false);  // no such lane (e.g. counter traffic)
    plan = route ? LateralPlanOf(*route, c.lane_width_m) : LateralPlan{};
  }
  if (plan.direction != 0 && route && !s->steered) {
    s->steered = true;
    ActionEvent a = row("steer", route);
    const std::string lcm = "lane-change mode " + std::to_string(c.lane_change_mode) + " kept";
    char b[200];
    if (lc.sublane) {
      world_->ChangeSublane(ego.id, plan.final_offset_m - c.lateral_offset_m);
      a.lane_after = c.lane + " " + Fixed(plan.final_offset_m) + " m";
      std::snprintf(b, sizeof b,
                    "sublane offset: the route's takes %.1f s, SUMO's moves at the type's "
                    "maxSpeedLat; ",
                    plan.duration_s);
      a.detail = b + lcm;
      out->actions.push_back(a);
    } else {
      // SUMO moves a changing vehicle over lanechange.duration (0: in one step): start so that
      // it crosses into the target lane when the route does.
      s->steer_pending = true;
      s->steer_at_s = threat_behind ? t : t + std::max(0.0, plan.cross_s - 0.5 * lc.duration_s);
      s->steer_lane = target;
      s->steer_hold_s = route->time_s.empty() ? 1.0 : route->time_s.back();
      a.lane_after = c.lane.substr(0, c.lane.rfind('_')) + "_" + std::to_string(target);
      std::snprintf(b, sizeof b,
                    "lane change: the route crosses at %.1f s, done at %.1f s; SUMO's takes "
                    "%.1f s (lanechange.duration); ",
                    plan.cross_s, plan.duration_s, lc.duration_s);
      a.detail = b + lcm;
      if (threat_behind) a.detail += "; the main threat comes from behind: at once, no braking";
      s->steer_row = a;
    }
  }
  if (s->steer_pending && t + 1e-9 >= s->steer_at_s) {
    s->steer_pending = false;
    world_->ChangeLane(ego.id, s->steer_lane, s->steer_hold_s);
    s->steer_row.speed_mps = s->steer_row.speed_after_mps = v;
    out->actions.push_back(s->steer_row);
  }
  // Mitigation: when even the followed route probably collides, the lowest impact speed is
  // what is left to reach: brake as hard as the type allows; not when the main threat comes
  // from behind (braking would only raise its closing speed).
  const bool mitigate = route && route->collision_probability >= kMitigation;
  SpeedInputs in;
  in.speed_mps = v;
  in.own_speed_mps = c.own_speed_mps;
  in.route_accel_mps2 = route && !mitigate ? route->profile_accel_mps2 : -c.emergency_decel_mps2;
  in.emergency_decel_mps2 = c.emergency_decel_mps2;
  in.elapsed_s = elapsed;
  in.previous_accel_mps2 = s->previous_accel;
  in.active = s->braking;
  const SpeedCommand cmd = threat_behind ? SpeedCommand{} : ClosedLoopSpeed(in, brake_model_, dt_);
  if (cmd.command) {
    world_->CommandSpeed(ego.id, cmd.speed_mps);
    s->previous_accel = cmd.accel_mps2;
    if (!s->braking) {
      ActionEvent a = row("brake", route);
      a.accel_mps2 = cmd.accel_mps2;
      a.speed_after_mps = cmd.speed_mps;
      a.detail = SpeedModeText(c.speed_mode);
      if (!route) a.detail += "; no escape route to follow: emergencyDecel";
      if (mitigate) a.detail += "; the route probably collides: emergencyDecel (mitigation)";
      if (threat_behind)
        a.detail +=
            "; the route probably collides, from behind: its own deceleration, no mitigation";
      if (c.forced)
        a.detail += "; the scenario forces " + Fixed(c.own_speed_mps).substr(1) + " m/s";
      out->actions.push_back(a);
    }
    s->braking = s->commanding = true;
  } else if (s->commanding) {
    if (HandBack(ego.id, c, v)) s->commanding = false;
  }
}

}  // namespace criticality::plugin
