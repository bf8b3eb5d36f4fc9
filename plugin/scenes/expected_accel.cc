#include "plugin/scenes/expected_accel.h"

#include <string>
#include <unordered_map>

namespace criticality::plugin {

void ExpectCarFollowing(std::vector<ObjectSnapshot>* objects, double normal_decel_mps2) {
  std::unordered_map<std::string, const ObjectSnapshot*> vehicles;
  for (const ObjectSnapshot& o : *objects) {
    if (!o.person) vehicles.emplace(o.id, &o);
  }
  for (ObjectSnapshot& o : *objects) {
    if (o.person || !o.leader) continue;
    Leader leader = *o.leader;
    const auto it = vehicles.find(leader.id);
    if (it != vehicles.end() && it->second->stop_line)
      leader.stop_distance_m = it->second->stop_line->distance_m;
    o.state.expected_accel_mps2 = CarFollowingAccel(o.state.speed_mps, leader, normal_decel_mps2);
  }
}


}  // namespace criticality::plugin
