#include "plugin/scenes/lane_heading.h"

#include <algorithm>
#include <cmath>

#include "criticality/geometry.h"
#include "plugin/network/polyline.h"
#include "plugin/network/way_behind.h"

namespace criticality::plugin {

namespace {

// The direction from the point `length_m` behind `front_m` along `line` to the point there.
std::optional<double> ChordAt(const std::vector<Point2>& line, double front_m, double length_m) {
  const Point2 back = PointAlong(line, front_m - length_m, nullptr);
  const Point2 front = PointAlong(line, front_m, nullptr);
  if (std::hypot(front.x - back.x, front.y - back.y) < 1e-6) return std::nullopt;
  return std::atan2(front.y - back.y, front.x - back.x);
}

constexpr double kMinWindowM = 0.5;

}  // namespace

std::optional<LaneHeading> HeadingAlong(const std::vector<Point2>& line, double front_m,
                                        double length_m, double speed_mps, double behind_m,
                                        double ahead_m) {
  if (line.size() < 2 || !(length_m > 0.0) || front_m - length_m < -1e-9) return std::nullopt;
  const double end = PolylineLength(line);
  const double behind = std::clamp(front_m - length_m, 0.0, std::fmax(0.0, behind_m));
  const double ahead = std::clamp(end - front_m, 0.0, std::fmax(0.0, ahead_m));
  if (behind + ahead < kMinWindowM) return std::nullopt;
  const std::optional<double> now = ChordAt(line, front_m, length_m);
  const std::optional<double> from = ChordAt(line, front_m - behind, length_m);
  const std::optional<double> to = ChordAt(line, front_m + ahead, length_m);
  if (!now || !from || !to) return std::nullopt;
  return LaneHeading{*now, speed_mps * WrapAngle(*to - *from) / (behind + ahead)};
}

std::vector<Point2> LineThrough(RoadNetwork& network, const std::string& lane,
                                double lane_position_m, double behind_m,
                                const std::vector<std::string>& route, int route_index,
                                const std::vector<Point2>& ahead, double* front_m) {
  WayLine way = LineBehind(network, lane, lane_position_m, behind_m, route, route_index);
  *front_m = way.front_m;
  // `ahead` starts with the lane's own shape, which ends `way.line`.
  const std::size_t own = network.Lane(lane).shape.size();
  for (std::size_t i = own; i < ahead.size(); ++i) {
    const Point2& last = way.line.back();
    if (std::hypot(ahead[i].x - last.x, ahead[i].y - last.y) > 1e-3) way.line.push_back(ahead[i]);
  }
  return std::move(way.line);
}

}  // namespace criticality::plugin
