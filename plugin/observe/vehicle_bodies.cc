#include "plugin/observe/vehicle_bodies.h"

#include <algorithm>
#include <cmath>

#include "plugin/network/way_behind.h"

namespace criticality::plugin {
namespace {

constexpr int kParkingBit = 2;    // SUMO's getStopState: parking
constexpr double kMinBoxM = 0.1;  // a box, however folded its way

}  // namespace

double MeasuredBodyLength(RoadNetwork& network, const SumoObject& v) {
  if (v.person || v.lane.empty() || (v.stop_state & kParkingBit) || !(v.length_m > 0.0))
    return v.length_m;
  const std::optional<Point2> back =
      PointBehind(network, v.lane, v.lane_position_m, v.length_m, v.route, v.route_index);
  if (!back) return v.length_m;
  const double chord = std::hypot(v.x_m - back->x, v.y_m - back->y);
  if (!std::isfinite(chord)) return v.length_m;
  return std::clamp(chord, std::min(kMinBoxM, v.length_m), v.length_m);
}

void MeasureBodies(RoadNetwork& network, SumoSurroundings* s) {
  for (SumoObject& o : s->objects) {
    if (!o.person) o.body_length_m = MeasuredBodyLength(network, o);
  }
}

}  // namespace criticality::plugin
