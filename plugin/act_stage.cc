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

ActOutcome ActStage::Run(const SceneBatch& batch, const std::vector<Result>& results) {
  const DriverOptions& o = options_;
  ActOutcome out;
  for (size_t k = 0; k < batch.egos.size(); ++k) {
    const std::string& ego = batch.egos[k];
    const Result& r = results[k];
    const double p = r.p_collision;
    EgoState& s = state_[ego];
    if (o.act != Act::kNone) {
      if (p >= o.warn_threshold && !s.warning) {
        s.warning = true;
        s.peak = p;
        out.warnings.push_back({ego, WarningChange::kOpen, p});
      } else if (s.warning && p > s.peak) {
        s.peak = p;
        out.warnings.push_back({ego, WarningChange::kPeak, p});
      } else if (s.warning && p < o.warn_release) {
        s.warning = false;
        out.warnings.push_back({ego, WarningChange::kClose, p});
      }
      world_->Publish(ego, p, s.warning);
    }
    const double speed = world_->Speed(ego);
    if (o.act == Act::kBrake) {
      if (p >= o.brake_threshold) {
        // Follow the best escape route's acceleration when one exists and it slows down;
        // otherwise brake as hard as the vehicle can.
        double accel = -world_->EmergencyDecel(ego);
        if (!r.escape_routes.empty())
          accel = std::min(r.escape_routes.front().profile_accel_mps2, 0.0);
        if (accel >= 0.0) accel = -world_->EmergencyDecel(ego);
        world_->CommandSpeed(ego, std::max(0.0, speed + accel * dt_));
        if (!s.braking) out.actions.push_back({ego, "brake", accel, speed, p});
        s.braking = true;
      } else if (s.braking) {
        world_->ReleaseSpeed(ego);
        out.actions.push_back({ego, "release", 0.0, speed, p});
        s.braking = false;
      }
    }
    out.steps.push_back(
        EgoStep{ego, p, r.times.total_ms, static_cast<int>(r.objects.size()), speed, s.braking});
  }
  return out;
}

}  // namespace criticality::plugin
