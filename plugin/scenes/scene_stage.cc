#include "plugin/scenes/scene_stage.h"

#include <cstdio>
#include <set>

#include "plugin/scenes/expected_accel.h"
#include "plugin/scenes/scene_building.h"

namespace criticality::plugin {

SceneStage::SceneStage(const SceneConfig& config, double step_s, bool euler_update,
                       RoadNetwork* network, TrafficView* traffic)
    : config_(config),
      euler_update_step_s_(euler_update ? step_s : 0.0),
      reader_(config, step_s, network, traffic) {}

SceneBatch SceneStage::Run(const Observation& obs) {
  for (const std::string& id : obs.left) reader_.Forget(id);
  for (const std::string& id : obs.teleported) reader_.Forget(id);
  SceneBatch batch;
  const SumoSurroundings& s = obs.surroundings;
  batch.objects = reader_.Read(s.objects, obs.sumo_time_s);
  ExpectCarFollowing(&batch.objects, kNormalFollowingDecelMps2);
  Count(batch);
  std::vector<LeftOutObject> left_out;
  for (const SumoSurroundings::Ego& e : s.egos) {
    const ObjectSnapshot& ego = batch.objects[e.self];
    if (!Estimated(ego)) continue;
    const std::string why = InvalidValues(ego);
    if (!why.empty()) {  // no estimate for this ego at this step
      left_out.push_back(LeftOutObject{ego.id, false, why});
      continue;
    }
    std::vector<const ObjectSnapshot*> nearby;
    nearby.reserve(e.nearby.size());
    for (int k : e.nearby) nearby.push_back(&batch.objects[k]);
    batch.scenes.push_back(BuildScene(ego, nearby, config_.range_m, &left_out));
    batch.scenes.back().euler_update_step_s = euler_update_step_s_;
    batch.scenes.back().bodies_on_path = config_.bodies_on_path;
    batch.egos.push_back(e.self);
  }
  if (!left_out.empty()) Report(obs, left_out);
  return batch;
}

bool SceneStage::Estimated(const ObjectSnapshot& ego) {
  if (ego.not_a_road_user) return false;
  if (ego.parked) {  // it stands until it leaves its parking place
    ++parked_egos_;
    return false;
  }
  return !config_.all_vehicles || config_.ego_classes.Includes(ego.vehicle_class);
}

void SceneStage::Count(const SceneBatch& batch) {
  for (const ObjectSnapshot& o : batch.objects) {
    if (o.not_a_road_user) ++other_class_objects_;
    if (o.off_road) ++parked_objects_;
  }
}

void SceneStage::Report(const Observation& obs, const std::vector<LeftOutObject>& left_out) {
  std::set<std::pair<bool, std::string>> distinct;
  for (const LeftOutObject& o : left_out) distinct.insert({o.person, o.id});
  invalid_objects_ += static_cast<long long>(distinct.size());
  if (reported_) return;
  reported_ = true;
  const LeftOutObject& o = left_out.front();
  std::fprintf(stderr,
               "sumo-criticality: warning: %s '%s' at t = %.2f s has invalid values from SUMO "
               "(%s) and is left out of the scenes; such objects are counted in the summary "
               "(invalid_objects), reported only this once\n",
               o.person ? "person" : "vehicle", o.id.c_str(), obs.time_s, o.why.c_str());
}

}  // namespace criticality::plugin
