#include "plugin/scenes/junction_way.h"

#include <algorithm>
#include <cmath>

#include "plugin/network/polyline.h"
#include "plugin/network/way_behind.h"
#include "plugin/scenes/lane_heading.h"

namespace criticality::plugin {

bool BodyInJunction(RoadNetwork& network, const std::string& lane, double lane_position_m,
                    double length_m, const std::vector<std::string>& route, int route_index) {
  if (lane.empty()) return false;
  if (IsInternal(lane)) return true;
  if (lane_position_m >= length_m) return false;
  for (const std::string& behind :
       LanesBehind(network, lane, route, route_index, length_m - lane_position_m)) {
    if (IsInternal(behind)) return true;
  }
  return false;
}

std::optional<Way> WayOf(RoadNetwork& network, const std::string& lane, double lane_position_m,
                         double length_m, const std::vector<std::string>& route, int route_index,
                         const std::vector<Point2>& ahead, const Pose2& X_WV) {
  const WayLine line = LineThrough(network, lane, lane_position_m, length_m + kWayBehindBackM,
                                   route, route_index, ahead);
  if (line.line.size() < 2 || line.front_m - length_m < 0.0) return std::nullopt;
  // From the back's margin to the end, in arc lengths along the line.
  const double start = std::max(0.0, line.front_m - length_m - kWayBehindBackM);
  const double end = PolylineLength(line.line);
  if (!(end > line.front_m)) return std::nullopt;
  std::vector<double> at;  // arc lengths of the points kept
  {
    double s = 0.0;
    at.push_back(start);
    for (std::size_t k = 1; k < line.line.size(); ++k) {
      s += std::hypot(line.line[k].x - line.line[k - 1].x, line.line[k].y - line.line[k - 1].y);
      if (s > start + kMinWayPointSpacingM && s < end - kMinWayPointSpacingM &&
          s > at.back() + kMinWayPointSpacingM)
        at.push_back(s);
    }
    at.push_back(end);
  }
  if (at.size() > static_cast<std::size_t>(kMaxWayPoints)) {  // evenly, the ends kept
    const int n = kMaxWayPoints;
    at.resize(n);
    for (int k = 0; k < n; ++k) at[k] = start + (end - start) * k / (n - 1);
  }
  // The points in the vehicle's frame; one too close to the point before it (a line folding
  // back on itself at a U-turn's apex) is left out, its arc length with it, the end kept.
  Way way;
  std::vector<double> used;
  for (double s : at) {
    double heading = 0.0;
    const Point2 w = PointAlong(line.line, s, &heading);
    Point2 p;
    WorldToLocal(X_WV, w.x, w.y, &p.x, &p.y);
    if (!way.points.empty() && std::hypot(p.x - way.points.back().x,
                                          p.y - way.points.back().y) < kMinWayPointSpacingM) {
      if (s != at.back() || way.points.size() < 2) continue;
      way.points.pop_back();  // the end replaces the point just before it
      used.pop_back();
    }
    way.points.push_back(p);
    used.push_back(s);
  }
  if (way.points.size() < 2) return std::nullopt;
  at = used;
  // Arc lengths along the kept points (shorter than the line's where it was resampled).
  std::vector<double> kept(way.points.size(), 0.0);
  for (std::size_t k = 1; k < kept.size(); ++k)
    kept[k] = kept[k - 1] + std::hypot(way.points[k].x - way.points[k - 1].x,
                                       way.points[k].y - way.points[k - 1].y);
  // The front and the back where the line has them, mapped piece by piece.
  auto map = [&](double s) {
    const auto it = std::upper_bound(at.begin(), at.end(), s);
    const std::size_t hi = std::clamp<std::size_t>(it - at.begin(), 1, at.size() - 1);
    const double u = (s - at[hi - 1]) / (at[hi] - at[hi - 1]);
    return kept[hi - 1] + u * (kept[hi] - kept[hi - 1]);
  };
  way.front_m = map(line.front_m);
  way.back_m = std::max(0.0, map(line.front_m - length_m));
  if (!(way.front_m > way.back_m) || !(way.front_m <= kept.back())) return std::nullopt;
  return way;
}

}  // namespace criticality::plugin
