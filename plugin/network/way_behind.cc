#include "plugin/network/way_behind.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "plugin/network/polyline.h"

namespace criticality::plugin {
namespace {

// The lanes from the previous route edge's lane to `lane`, that lane first and `lane` not
// included; empty when not known. Moves *route_index to that edge. A vehicle that changed lanes
// since it left the junction came by a link to a lane beside `lane` (its body's back is still
// behind that lane, as SUMO keeps it): the link to the nearest lane of `lane`'s edge.
std::vector<std::string> StepBack(RoadNetwork& network, const std::string& lane,
                                  const std::vector<std::string>& route, int* route_index) {
  const int n = static_cast<int>(route.size());
  const bool internal = IsInternal(lane);
  // On a junction the route index is already the edge before it.
  const int previous = internal ? *route_index : *route_index - 1;
  if (previous < 0 || previous >= n) return {};
  const std::string& edge = route[previous];
  const LaneInfo& here = network.Lane(lane);
  std::vector<std::string> best;
  int best_offset = 1 << 20;
  for (int k = 0; k < network.LaneCount(edge); ++k) {
    const std::string from = edge + "_" + std::to_string(k);
    for (const LaneLink& link : network.Links(from)) {
      const std::vector<std::string> chain = InternalChain(network, link);
      std::vector<std::string> way{from};
      int offset = -1;
      if (internal) {
        for (const std::string& c : chain) {
          if (c == lane) {
            offset = 0;
            break;
          }
          way.push_back(c);
        }
      } else {
        way.insert(way.end(), chain.begin(), chain.end());
        const LaneInfo& to = network.Lane(link.lane);
        if (to.edge == here.edge) offset = std::abs(to.index - here.index);
      }
      if (offset < 0 || offset >= best_offset) continue;
      best = std::move(way);
      best_offset = offset;
      if (offset == 0) break;
    }
    if (best_offset == 0) break;
  }
  if (!best.empty()) *route_index = previous;
  return best;
}

}  // namespace

std::vector<std::string> LanesBehind(RoadNetwork& network, const std::string& lane,
                                     const std::vector<std::string>& route, int route_index,
                                     double metres) {
  std::vector<std::string> out;
  std::string at = lane;
  double covered = 0.0;
  for (int hop = 0; hop < 64 && covered < metres; ++hop) {
    const std::vector<std::string> way = StepBack(network, at, route, &route_index);
    if (way.empty()) break;
    for (auto it = way.rbegin(); it != way.rend() && covered < metres; ++it) {
      out.push_back(*it);
      covered += network.Lane(*it).length_m;
    }
    at = way.front();
  }
  return out;
}

std::optional<Point2> PointBehind(RoadNetwork& network, const std::string& lane,
                                  double lane_position_m, double distance_m,
                                  const std::vector<std::string>& route, int route_index) {
  double s = lane_position_m - distance_m;
  if (s >= 0.0) {
    const LaneInfo& l = network.Lane(lane);
    if (l.shape.size() < 2) return std::nullopt;
    return PointAlong(l.shape, OnShape(l, s), nullptr);
  }
  for (const std::string& behind : LanesBehind(network, lane, route, route_index, -s)) {
    const LaneInfo& l = network.Lane(behind);
    if (l.shape.size() < 2) return std::nullopt;
    s += l.length_m;
    if (s >= 0.0) return PointAlong(l.shape, OnShape(l, s), nullptr);
  }
  return std::nullopt;
}

WayLine LineBehind(RoadNetwork& network, const std::string& lane, double lane_position_m,
                   double metres, const std::vector<std::string>& route, int route_index) {
  const LaneInfo& own = network.Lane(lane);
  WayLine way;
  way.line = own.shape;
  way.front_m = OnShape(own, lane_position_m);
  if (way.line.size() < 2) return way;
  for (const std::string& behind :
       LanesBehind(network, lane, route, route_index, metres - lane_position_m)) {
    std::vector<Point2> shape = network.Lane(behind).shape;
    if (shape.size() < 2) break;
    // Moved onto the line's start: exactly where netconvert's joints meet (millimetres), by
    // the lanes' spacing after a lane change.
    const double dx = way.line.front().x - shape.back().x;
    const double dy = way.line.front().y - shape.back().y;
    for (Point2& p : shape) p = Point2{p.x + dx, p.y + dy};
    way.shifted_m = std::max(way.shifted_m, std::hypot(dx, dy));
    way.front_m += PolylineLength(shape);
    shape.insert(shape.end(), way.line.begin() + 1, way.line.end());
    way.line.swap(shape);
  }
  return way;
}

std::optional<double> ChordYaw(const WayLine& way, double length_m, double ahead_m) {
  const std::optional<Point2> back = PointOnWay(way, length_m - ahead_m);
  const std::optional<Point2> front = PointOnWay(way, -ahead_m);
  if (!back || !front || std::hypot(front->x - back->x, front->y - back->y) < 1e-6)
    return std::nullopt;
  return std::atan2(front->y - back->y, front->x - back->x);
}

std::optional<Point2> PointOnWay(const WayLine& way, double metres) {
  const double s = way.front_m - metres;
  if (s < -1e-9 || way.line.size() < 2) return std::nullopt;
  return PointAlong(way.line, std::max(0.0, s), nullptr);
}

}  // namespace criticality::plugin
