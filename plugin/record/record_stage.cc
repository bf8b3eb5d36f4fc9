#include "plugin/record/record_stage.h"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "criticality/scene_io.h"

namespace fs = std::filesystem;

namespace criticality::plugin {

RecordStage::RecordStage(const RecordConfig& config, ResultsDb* db) : config_(config), db_(db) {}

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
  for (const CollisionEvent& c : obs.collisions) db_->AddCollision(t, c.sumo, c.involves_ego);
  for (const CriticalEvent& e : obs.critical_events) {
    db_->AddCriticalEvent(t, e.ego, CriticalEventName(e.kind), e.other, e.value);
  }
  Scenes(t, batch);
  Egos(t, obs, batch);
  Warnings(t, acted.warnings, batch);
  for (const ActionEvent& a : acted.actions) db_->AddAction(t, a);
  for (const EgoStep& s : acted.steps) db_->AddStep(t, s);
}

void RecordStage::Egos(double t, const Observation& obs, const SceneBatch& batch) {
  for (const EgoEvent& e : obs.ego_events) {
    if (e.kind == EgoEventKind::kArrive || e.kind == EgoEventKind::kVanish) recorded_.erase(e.ego);
  }
  for (size_t k = 0; k < batch.scenes.size(); ++k) {
    const ObjectSnapshot& ego = batch.EgoOf(k);
    if (!recorded_.insert(ego.id).second) continue;
    db_->AddEgo(t, ego.id, ego.vehicle_class, ego.vehicle_type, ego.length_m, ego.width_m);
    ++egos_estimated_;
  }
}

void RecordStage::Scenes(double t, const SceneBatch& batch) {
  if (config_.scene_folder.empty()) return;
  for (const Scene& scene : batch.scenes) {
    const fs::path file = fs::path(config_.scene_folder) / SceneFileName(t, scene.ego.id);
    std::ofstream out(file);
    WriteScene(out, scene);
    if (!out) throw ResultsError("cannot write scene file '" + file.string() + "'");
  }
}

void RecordStage::Warnings(double t, const std::vector<WarningEvent>& warnings,
                           const SceneBatch& batch) {
  for (const WarningEvent& w : warnings) {
    switch (w.change) {
      case WarningChange::kOpen:
        open_episode_[w.ego] =
            db_->OpenWarning(w.ego, t, w.p_collision, w.x_m, w.y_m, w.edge, w.object);
        StoreScene(t, open_episode_[w.ego], w.ego, batch);
        break;
      case WarningChange::kPeak:
        db_->UpdateWarningPeak(open_episode_.at(w.ego), w.p_collision);
        break;
      case WarningChange::kClose:
        CloseEpisode(w.ego, t);
        break;
    }
  }
}

void RecordStage::StoreScene(double t, long long warning, const std::string& ego,
                             const SceneBatch& batch) {
  for (const Scene& scene : batch.scenes) {
    if (scene.ego.id != ego) continue;
    std::ostringstream text;
    WriteScene(text, scene);
    db_->AddWarningScene(warning, ego, t, text.str());
    return;
  }
}

void RecordStage::Commit(const StepTimeRow& times) {
  db_->AddStepTime(times);
  db_->Commit();
}

}  // namespace criticality::plugin
