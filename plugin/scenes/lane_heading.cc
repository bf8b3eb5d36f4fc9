#include "plugin/scenes/lane_heading.h"

#include <algorithm>
#include <cmath>

#include "criticality/geometry.h"
#include "plugin/network/polyline.h"

namespace criticality::plugin {

namespace {

constexpr double kMinWindowM = 0.5;

}  // namespace

std::optional<LaneHeading> HeadingAlong(const WayLine& way, double length_m, double speed_mps,
                                        double behind_m, double ahead_m) {
  if (way.line.size() < 2 || !(length_m > 0.0) || way.front_m - length_m < -1e-9)
    return std::nullopt;
  const double end = PolylineLength(way.line);
  const double behind = std::clamp(way.front_m - length_m, 0.0, std::fmax(0.0, behind_m));
  const double ahead = std::clamp(end - way.front_m, 0.0, std::fmax(0.0, ahead_m));
  if (behind + ahead < kMinWindowM) return std::nullopt;
  const std::optional<double> now = ChordYaw(way, length_m);
  const std::optional<double> from = ChordYaw(way, length_m, -behind);
  const std::optional<double> to = ChordYaw(way, length_m, ahead);
  if (!now || !from || !to) return std::nullopt;
  return LaneHeading{*now, speed_mps * WrapAngle(*to - *from) / (behind + ahead)};
}

WayLine LineThrough(RoadNetwork& network, const std::string& lane, double lane_position_m,
                    double behind_m, const std::vector<std::string>& route, int route_index,
                    const std::vector<Point2>& ahead) {
  WayLine way = LineBehind(network, lane, lane_position_m, behind_m, route, route_index);
  // `ahead` starts with the lane's own shape, which ends `way.line`.
  const std::size_t own = network.Lane(lane).shape.size();
  for (std::size_t i = own; i < ahead.size(); ++i) {
    const Point2& last = way.line.back();
    if (std::hypot(ahead[i].x - last.x, ahead[i].y - last.y) > 1e-3) way.line.push_back(ahead[i]);
  }
  return way;
}

}  // namespace criticality::plugin
