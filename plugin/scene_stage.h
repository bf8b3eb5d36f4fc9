#pragma once
// Stage 2 of a step: one Scene per ego (its lanes, the vehicles and pedestrians around it).
#include <string>
#include <vector>

#include "criticality/scene.h"
#include "plugin/observe_stage.h"
#include "plugin/sumo_world.h"

namespace criticality::plugin {

struct SceneBatch {
  std::vector<std::string> egos;  ///< scenes[k] is egos[k]'s
  std::vector<Scene> scenes;
};

class SceneStage {
 public:
  SceneStage(const DriverOptions& options, SumoWorld* world);
  SceneBatch Run(const Observation& obs);

 private:
  ExtractionConfig config_;
  SumoWorld* world_;
};

}  // namespace criticality::plugin
