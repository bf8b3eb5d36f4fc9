#include "plugin/record_stage.h"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "criticality/scene_io.h"

namespace fs = std::filesystem;

namespace criticality::plugin {

RecordStage::RecordStage(const DriverOptions& options, ResultsDb* db)
    : options_(options), db_(db) {}

std::string RecordStage::SceneFileName(double time_s, const std::string& ego) {
  char stamp[64];
  std::snprintf(stamp, sizeof stamp, "t%010.3f_", time_s);
  std::string name = stamp;
  for (unsigned char c : ego) {
    if (std::isalnum(c) || c == '.' || c == '_' || c == '-' || c == '#' || c == ':') {
      name += static_cast<char>(c);
    } else {
      char hex[4];
      std::snprintf(hex, sizeof hex, "%%%02X", c);
      name += hex;
    }
  }
  return name + ".scene";
}

void RecordStage::CloseEpisode(const std::string& ego, double time_s) {
  auto it = open_episode_.find(ego);
  if (it == open_episode_.end()) return;
  db_->CloseWarning(it->second, time_s);
  open_episode_.erase(it);
}

void RecordStage::Run(const Observation& obs, const SceneBatch& batch, const ActOutcome& acted) {
  const double t = obs.time_s;
  for (const EgoEvent& e : obs.ego_events) {
    db_->AddEgoEvent(t, e.ego, EgoEventName(e.kind), e.detail);
  }
  // Collisions before this step's warnings: an episode that opens at the impact does not
  // anticipate it.
  for (const CollisionEvent& ce : obs.collisions) {
    const SumoCollision& c = ce.sumo;
    CollisionRow row;
    row.time_s = t;
    row.collider = c.collider;
    row.victim = c.victim;
    row.collider_type = c.collider_type;
    row.victim_type = c.victim_type;
    row.type = c.type;
    row.lane = c.lane;
    row.pos_m = c.pos_m;
    row.x_m = c.x_m;
    row.y_m = c.y_m;
    row.collider_speed_mps = c.collider_speed_mps;
    row.victim_speed_mps = c.victim_speed_mps;
    row.involves_ego = ce.involves_ego;
    db_->AddCollision(row);
  }
  for (const CriticalEvent& e : obs.critical_events) {
    db_->AddCriticalEvent(t, e.ego, CriticalEventName(e.kind), e.other, e.value);
  }
  if (!options_.record_scenes.empty()) {
    for (size_t k = 0; k < batch.scenes.size(); ++k) {
      const fs::path file =
          fs::path(options_.record_scenes) / SceneFileName(t, batch.scenes[k].ego.id);
      std::ofstream out(file);
      WriteScene(out, batch.scenes[k]);
      if (!out) throw ResultsError("cannot write scene file '" + file.string() + "'");
    }
  }
  for (const WarningEvent& w : acted.warnings) {
    switch (w.change) {
      case WarningChange::kOpen:
        open_episode_[w.ego] =
            db_->OpenWarning(w.ego, t, w.p_collision, w.x_m, w.y_m, w.edge, w.object);
        break;
      case WarningChange::kPeak:
        db_->UpdateWarningPeak(open_episode_.at(w.ego), w.p_collision);
        break;
      case WarningChange::kClose:
        CloseEpisode(w.ego, t);
        break;
    }
  }
  for (const ActionEvent& a : acted.actions) {
    ActionRow row;
    row.time_s = t;
    row.ego = a.ego;
    row.kind = a.kind;
    row.accel_mps2 = a.accel_mps2;
    row.speed_mps = a.speed_mps;
    row.p_collision = a.p_collision;
    row.speed_after_mps = a.speed_after_mps;
    row.lane_before = a.lane_before;
    row.lane_after = a.lane_after;
    row.route = a.route;
    row.route_collision_probability = a.route_collision_probability;
    row.route_probability = a.route_probability;
    row.detail = a.detail;
    db_->AddAction(row);
  }
  for (const EgoStep& s : acted.steps) {
    StepRow row;
    row.time_s = t;
    row.ego = s.ego->id;
    row.p_collision = s.p_collision;
    row.p_reference = s.p_reference;
    row.unavoidability = s.unavoidability;
    row.estimator_ms = s.estimator_ms;
    row.objects = s.objects;
    row.objects_in_reach = s.objects_in_reach;
    row.speed_mps = s.ego->state.speed_mps;
    row.acting = s.acting;
    db_->AddStep(row);
  }
}

void RecordStage::Commit(const StepTimeRow& times) {
  db_->AddStepTime(times);
  db_->Commit();
}

}  // namespace criticality::plugin
