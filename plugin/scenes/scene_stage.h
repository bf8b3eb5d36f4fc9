#pragma once
// Stage 2 of a step: the step's objects as the estimator sees them (object_reading.h: lanes from
// each object's view, stop lines, what each driver is expected to do, footway) and one Scene per
// ego (scene_building.h). Objects with invalid values are left out, counted, and reported once
// per run on standard error. Reads the network and asks SUMO about leaders and signals only
// through RoadNetwork and TrafficView.
#include <string>
#include <vector>

#include "criticality/scene.h"
#include "plugin/network/road_network.h"
#include "plugin/network/traffic_view.h"
#include "plugin/observe/observation.h"
#include "plugin/scenes/object_reading.h"
#include "plugin/scenes/object_snapshot.h"
#include "plugin/scenes/scene_building.h"
#include "plugin/scenes/scene_config.h"

namespace criticality::plugin {

struct SceneBatch {
  /** Every object of the step (same order as the observation's objects). */
  std::vector<ObjectSnapshot> objects;
  std::vector<Scene> scenes;
  /** scenes[k]'s ego: an index into objects. */
  std::vector<int> egos;
  const ObjectSnapshot& EgoOf(size_t k) const { return objects[egos[k]]; }
};

class SceneStage {
 public:
  /** @param step_s the simulation's step length.
   *  @param euler_update SUMO moves vehicles by its Euler update (its default; not under
   *  --step-method.ballistic): every scene says so (Scene::euler_update_step_s = step_s). */
  SceneStage(const SceneConfig& config, double step_s, bool euler_update, RoadNetwork* network,
             TrafficView* traffic);
  SceneBatch Run(const Observation& obs);
  /** SUMO switched to its ballistic update (SumoWorld::BallisticUpdate): scenes from now on
   *  say continuous motion (Scene::euler_update_step_s = 0). */
  void SwitchToBallistic() { euler_update_step_s_ = 0.0; }
  /** Object reads left out of scenes so far (an object is counted once per step) for values
   *  the estimator cannot use. */
  long long invalid_objects() const { return invalid_objects_; }
  /** Object reads whose yaw rate or acceleration was made plausible (object_reading.h). */
  long long conditioned_states() const { return reader_.conditioned(); }
  /** Vehicle reads left out as parked beside the road, and as no road user (ships, aircraft). */
  long long parked_objects() const { return parked_objects_; }
  long long other_class_objects() const { return other_class_objects_; }
  /** Ego reads not estimated because the ego was parked. */
  long long parked_egos() const { return parked_egos_; }

 private:
  /** Whether an ego of the observation is estimated: no parked vehicle, no vehicle that is no
   *  road user, and with --all-vehicles only the --ego-classes. */
  bool Estimated(const ObjectSnapshot& ego);
  void Count(const SceneBatch& batch);
  void Report(const Observation& obs, const std::vector<LeftOutObject>& left_out);

  SceneConfig config_;
  double euler_update_step_s_;
  ObjectReader reader_;
  long long invalid_objects_{0};
  long long parked_objects_{0}, other_class_objects_{0}, parked_egos_{0};
  bool reported_{false};
};

}  // namespace criticality::plugin
