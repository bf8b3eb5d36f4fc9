#include "plugin/act_stage.h"

#include <algorithm>

namespace criticality::plugin {

ActStage::ActStage(const DriverOptions& options, SumoWorld* world)
    : options_(options), world_(world), dt_(world->StepLength()) {}

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
    if (it->second.warning) out.warnings.push_back({e.ego, WarningChange::kClose, 0.0, 0.0, 0.0, ""});
    if (it->second.braking && e.kind == EgoEventKind::kTeleportStart)
      release_after_teleport_.insert(e.ego);
    if (e.kind != EgoEventKind::kTeleportStart) release_after_teleport_.erase(e.ego);
    state_.erase(it);
  }

  for (size_t k = 0; k < batch.scenes.size(); ++k) {
    const ObjectSnapshot& ego = *batch.egos[k];
    const Result& r = results[k];
    const double p = WarnValue(o.warn_on, r);
    EgoState& s = state_[ego.id];
    if (o.act != Act::kNone) {
      if (p >= o.warn_threshold && !s.warning) {
        s.warning = true;
        s.peak = p;
        out.warnings.push_back(
            {ego.id, WarningChange::kOpen, p, ego.state.x_m, ego.state.y_m, ego.edge});
      } else if (s.warning && p > s.peak) {
        s.peak = p;
        out.warnings.push_back({ego.id, WarningChange::kPeak, p, 0.0, 0.0, ""});
      } else if (s.warning && p < o.warn_release) {
        s.warning = false;
        out.warnings.push_back({ego.id, WarningChange::kClose, p, 0.0, 0.0, ""});
      }
      world_->Publish(ego.id, p, s.warning);
    }
    const double speed = ego.state.speed_mps;
    if (o.act == Act::kBrake) {
      if (p >= o.brake_threshold) {
        // Follow the best escape route's acceleration when one exists and it slows down;
        // otherwise brake as hard as the vehicle can.
        double accel = -world_->EmergencyDecel(ego.id);
        if (!r.escape_routes.empty())
          accel = std::min(r.escape_routes.front().profile_accel_mps2, 0.0);
        if (accel >= 0.0) accel = -world_->EmergencyDecel(ego.id);
        world_->CommandSpeed(ego.id, std::max(0.0, speed + accel * dt_));
        if (!s.braking) out.actions.push_back({ego.id, "brake", accel, speed, p});
        s.braking = true;
      } else if (s.braking) {
        world_->ReleaseSpeed(ego.id);
        out.actions.push_back({ego.id, "release", 0.0, speed, p});
        s.braking = false;
      }
    }
    EgoStep step;
    step.ego = &ego;
    step.p_collision = r.p_collision;
    step.p_reference = r.p_reference;
    step.unavoidability = r.unavoidability;
    step.estimator_ms = r.times.total_ms;
    step.objects = static_cast<int>(r.objects.size());
    for (const ObjectResult& obj : r.objects) step.objects_in_reach += obj.out_of_reach ? 0 : 1;
    step.shortcut = o.estimator.reach_shortcut && step.objects_in_reach == 0;
    step.acting = s.braking;
    out.steps.push_back(step);
  }
  return out;
}

}  // namespace criticality::plugin
