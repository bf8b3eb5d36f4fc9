#pragma once
// Stage 2 of a step: one Scene per ego from the step's snapshots (scene_building.h). Objects
// with invalid values are left out, counted, and reported once per run on standard error.
#include <string>
#include <vector>

#include "criticality/scene.h"
#include "plugin/driver_options.h"
#include "plugin/observe_stage.h"

namespace criticality::plugin {

struct SceneBatch {
  std::vector<Scene> scenes;
  /** scenes[k]'s ego as SUMO reported it (points into the step's Observation). */
  std::vector<const ObjectSnapshot*> egos;
};

class SceneStage {
 public:
  /** @param euler_update_step_s SUMO's step when it moves vehicles by the Euler update (its
   *  default), 0 under --step-method.ballistic: goes into every scene
   *  (Scene::euler_update_step_s). */
  SceneStage(const DriverOptions& options, double euler_update_step_s);
  SceneBatch Run(const Observation& obs);
  /** Object reads left out of scenes so far (an object is counted once per step). */
  long long invalid_objects() const { return invalid_objects_; }

 private:
  double range_m_;
  double euler_update_step_s_;
  long long invalid_objects_{0};
  bool reported_{false};
};

}  // namespace criticality::plugin
