#include "plugin/scene_stage.h"

namespace criticality::plugin {

SceneStage::SceneStage(const DriverOptions& o, SumoWorld* world)
    : config_{o.range_m, o.params.horizon_s, o.params.vehicle_accel_max_mps2}, world_(world) {}

SceneBatch SceneStage::Run(const Observation& obs) {
  SceneBatch batch;
  for (const std::string& ego : obs.egos) {
    batch.egos.push_back(ego);
    batch.scenes.push_back(world_->ExtractScene(ego, config_));
  }
  return batch;
}

}  // namespace criticality::plugin
