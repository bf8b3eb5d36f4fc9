#include "plugin/scene_stage.h"

#include <cstdio>
#include <set>

#include "plugin/scene_building.h"

namespace criticality::plugin {

SceneStage::SceneStage(const DriverOptions& o, double euler_update_step_s)
    : range_m_(o.range_m), euler_update_step_s_(euler_update_step_s) {}

SceneBatch SceneStage::Run(const Observation& obs) {
  SceneBatch batch;
  const Surroundings& s = obs.surroundings;
  std::vector<LeftOutObject> left_out;
  for (const Surroundings::Ego& e : s.egos) {
    const ObjectSnapshot& ego = s.objects[e.self];
    const std::string why = InvalidValues(ego);
    if (!why.empty()) {  // no estimate for this ego at this step
      left_out.push_back(LeftOutObject{ego.id, false, why});
      continue;
    }
    std::vector<const ObjectSnapshot*> nearby;
    nearby.reserve(e.nearby.size());
    for (int k : e.nearby) nearby.push_back(&s.objects[k]);
    batch.scenes.push_back(BuildScene(ego, nearby, range_m_, &left_out));
    batch.scenes.back().euler_update_step_s = euler_update_step_s_;
    batch.egos.push_back(&ego);
  }
  if (left_out.empty()) return batch;
  std::set<std::pair<bool, std::string>> distinct;
  for (const LeftOutObject& o : left_out) distinct.insert({o.person, o.id});
  invalid_objects_ += static_cast<long long>(distinct.size());
  if (!reported_) {
    reported_ = true;
    const LeftOutObject& o = left_out.front();
    std::fprintf(stderr,
                 "sumo-criticality: warning: %s '%s' at t = %.2f s has invalid values from SUMO "
                 "(%s) and is left out of the scenes; such objects are counted in the summary "
                 "(invalid_objects), reported only this once\n",
                 o.person ? "person" : "vehicle", o.id.c_str(), obs.time_s, o.why.c_str());
  }
  return batch;
}

}  // namespace criticality::plugin
