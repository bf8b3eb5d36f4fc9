#include "plugin/act/present_contacts.h"

#include <algorithm>

#include "criticality/geometry.h"

namespace criticality::plugin {
namespace {

Pose2 PoseOf(const ObjectState& s) { return Pose2{s.x_m, s.y_m, s.yaw_rad}; }

}  // namespace

std::vector<std::string> ObjectsInContact(const Scene& scene) {
  const Pose2 ego = PoseOf(scene.ego.state);
  const double ego_hl = 0.5 * scene.ego.length_m, ego_hw = 0.5 * scene.ego.width_m;
  auto touches = [&](const Pose2& p, double length_m, double width_m) {
    return RectanglesOverlap(ego, ego_hl, ego_hw, p, 0.5 * length_m, 0.5 * width_m);
  };
  std::vector<std::string> ids;
  for (const Vehicle& v : scene.vehicles) {
    bool contact = touches(PoseOf(v.state), v.length_m, v.width_m);
    for (const Carriage& c : v.carriages) {
      if (contact) break;
      contact = touches(Pose2{c.x_m, c.y_m, c.yaw_rad}, c.length_m, c.width_m);
    }
    if (contact) ids.push_back(v.id);
  }
  for (const Pedestrian& p : scene.pedestrians) {
    if (touches(PoseOf(p.state), p.length_m, p.width_m)) ids.push_back(p.id);
  }
  return ids;
}

Scene WithoutObjects(const Scene& scene, const std::vector<std::string>& ids) {
  auto named = [&](const std::string& id) {
    return std::find(ids.begin(), ids.end(), id) != ids.end();
  };
  Scene out = scene;
  out.vehicles.erase(std::remove_if(out.vehicles.begin(), out.vehicles.end(),
                                    [&](const Vehicle& v) { return named(v.id); }),
                     out.vehicles.end());
  out.pedestrians.erase(std::remove_if(out.pedestrians.begin(), out.pedestrians.end(),
                                       [&](const Pedestrian& p) { return named(p.id); }),
                        out.pedestrians.end());
  return out;
}

}  // namespace criticality::plugin
