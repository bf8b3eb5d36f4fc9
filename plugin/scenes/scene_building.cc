#include "plugin/scenes/scene_building.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace criticality::plugin {
namespace {

bool LaneSetFinite(const LaneSet& set) {
  for (const std::optional<Lane>* lane : {&set.own, &set.left, &set.right}) {
    if (!*lane) continue;
    for (const LaneDivider* d : {&(*lane)->left, &(*lane)->right}) {
      for (const Point2& p : d->points) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y)) return false;
      }
    }
  }
  return true;
}

// Whether the centre of any box of o's body lies within range_m of the ego's centre.
bool InRange(const ObjectSnapshot& o, const ObjectSnapshot& ego, double range_m) {
  auto near = [&](double x, double y) {
    return std::hypot(x - ego.state.x_m, y - ego.state.y_m) <= range_m;
  };
  if (near(o.state.x_m, o.state.y_m)) return true;
  for (const Carriage& c : o.carriages) {
    if (near(c.x_m, c.y_m)) return true;
  }
  return false;
}

}  // namespace

std::string InvalidValues(const ObjectSnapshot& o) {
  const std::pair<const char*, double> values[] = {{"state.x_m", o.state.x_m},
                                                   {"state.y_m", o.state.y_m},
                                                   {"state.yaw_rad", o.state.yaw_rad},
                                                   {"state.speed_mps", o.state.speed_mps},
                                                   {"state.accel_mps2", o.state.accel_mps2},
                                                   {"state.yaw_rate_radps", o.state.yaw_rate_radps},
                                                   {"length_m", o.length_m},
                                                   {"width_m", o.width_m}};
  for (const auto& [name, v] : values) {
    if (!std::isfinite(v)) {
      std::ostringstream msg;
      msg << name << " = " << v;
      return msg.str();
    }
  }
  if (!(o.length_m > 0.0) || !(o.width_m > 0.0)) {
    std::ostringstream msg;
    msg << "size " << o.length_m << " x " << o.width_m << " m";
    return msg.str();
  }
  if (!LaneSetFinite(o.lanes)) return "lanes with non-finite points";
  for (const Carriage& c : o.carriages) {
    if (!std::isfinite(c.x_m) || !std::isfinite(c.y_m) || !std::isfinite(c.yaw_rad) ||
        !std::isfinite(c.yaw_rate_radps) || (c.lanes && !LaneSetFinite(*c.lanes)))
      return "a carriage with non-finite values";
  }
  if (o.stop_line && !(o.stop_line->distance_m >= 0.0 && std::isfinite(o.stop_line->distance_m))) {
    std::ostringstream msg;
    msg << "stop_line.distance_m = " << o.stop_line->distance_m;
    return msg.str();
  }
  return "";
}

Scene BuildScene(const ObjectSnapshot& ego, const std::vector<const ObjectSnapshot*>& nearby,
                 double range_m, std::vector<LeftOutObject>* left_out) {
  Scene scene;
  scene.ego.id = ego.id;
  scene.ego.state = ego.state;
  scene.ego.length_m = ego.length_m;
  scene.ego.width_m = ego.width_m;
  scene.ego.height_m = ego.height_m;
  scene.ego.lanes = ego.lanes;
  scene.ego.type = ego.type;
  scene.ego.stop_line = ego.stop_line;  // used with Params::ego_stop_obligations
  scene.ego.way = ego.way;              // used with Params::ego_on_way
  std::vector<const ObjectSnapshot*> sorted = nearby;
  std::sort(sorted.begin(), sorted.end(),
            [](const ObjectSnapshot* a, const ObjectSnapshot* b) { return a->id < b->id; });
  for (const ObjectSnapshot* o : sorted) {
    if (o->id == ego.id && !o->person) continue;
    if (o->not_a_road_user || o->off_road) continue;  // nobody's obstacle (counted when read)
    const std::string why = InvalidValues(*o);
    if (!why.empty()) {
      if (left_out) left_out->push_back(LeftOutObject{o->id, o->person, why});
      continue;
    }
    if (!InRange(*o, ego, range_m)) continue;
    if (o->person) {
      Pedestrian p;
      p.id = o->id;
      p.state = o->state;
      p.length_m = o->length_m;
      p.width_m = o->width_m;
      p.stays_on_footway = o->stays_on_footway;
      scene.pedestrians.push_back(std::move(p));
    } else {
      Vehicle v;
      v.id = o->id;
      v.state = o->state;
      v.length_m = o->length_m;
      v.width_m = o->width_m;
      v.height_m = o->height_m;
      v.lanes = o->lanes;
      v.stop_line = o->stop_line;
      v.type = o->type;
      v.carriages = o->carriages;
      v.way = o->way;
      scene.vehicles.push_back(std::move(v));
    }
  }
  return scene;
}

}  // namespace criticality::plugin
