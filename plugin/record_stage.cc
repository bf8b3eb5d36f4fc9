#include "plugin/record_stage.h"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "criticality/scene_io.h"

namespace fs = std::filesystem;

namespace criticality::plugin {

RecordStage::RecordStage(const DriverOptions& options, ResultsDb* db)
    : options_(options), db_(db) {}

void RecordStage::CloseEpisode(const std::string& ego, double time_s) {
  auto it = open_episode_.find(ego);
  if (it == open_episode_.end()) return;
  db_->CloseWarning(it->second, time_s);
  open_episode_.erase(it);
}

void RecordStage::Run(const Observation& obs, const SceneBatch& batch, const ActOutcome& acted) {
  const double t = obs.time_s;
  for (const SumoCollision& c : obs.collisions) {
    db_->AddCollision(CollisionRow{t, c.collider, c.victim, c.collider_type, c.victim_type, c.type,
                                   c.lane, c.collider_speed, c.victim_speed, c.pos});
  }
  if (!options_.record_scenes.empty()) {
    for (size_t k = 0; k < batch.scenes.size(); ++k) {
      char name[64];
      std::snprintf(name, sizeof name, "t%010.3f_", t);
      const fs::path file = fs::path(options_.record_scenes) / (name + batch.egos[k] + ".scene");
      std::ofstream out(file);
      WriteScene(out, batch.scenes[k]);
      if (!out) throw ResultsError("cannot write scene file '" + file.string() + "'");
    }
  }
  for (const WarningEvent& w : acted.warnings) {
    switch (w.change) {
      case WarningChange::kOpen:
        open_episode_[w.ego] = db_->OpenWarning(w.ego, t, w.p_collision);
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
    db_->AddAction(t, a.ego, a.kind, a.accel_mps2, a.speed_mps, a.p_collision);
  }
  for (const EgoStep& s : acted.steps) {
    db_->AddStep(t, s.ego, s.p_collision, s.estimator_ms, s.objects, s.speed_mps, s.acting);
  }
  db_->Commit();
}

}  // namespace criticality::plugin
