#include "plugin/network/road_network.h"

#include <algorithm>
#include <cmath>

#include "plugin/network/polyline.h"

namespace criticality::plugin {

double OnShape(const LaneInfo& lane, double lane_position_m) {
  return lane.length_m > 0.0 ? lane_position_m * PolylineLength(lane.shape) / lane.length_m
                             : lane_position_m;
}

LanesOffShape LanesWithLengthOffShape(RoadNetwork& network) {
  LanesOffShape out;
  double worst_off = 0.0;
  for (const std::string& edge : network.Edges()) {
    if (IsInternal(edge)) continue;
    for (int k = 0; k < network.LaneCount(edge); ++k) {
      const std::string id = edge + "_" + std::to_string(k);
      const LaneInfo& lane = network.Lane(id);
      const double shape = PolylineLength(lane.shape);
      if (!(shape > 0.0) || !(lane.length_m > 0.0)) continue;
      const double off = std::fabs(std::log(lane.length_m / shape));
      if (std::fabs(lane.length_m - shape) <= 1.0 || off <= std::log1p(kLengthOffShapeShare))
        continue;
      ++out.lanes;
      if (off > worst_off) {
        worst_off = off;
        out.worst = id;
        out.worst_length_m = lane.length_m;
        out.worst_shape_m = shape;
      }
    }
  }
  return out;
}

bool Allows(RoadNetwork& network, const std::string& lane, const std::string& vclass) {
  const std::vector<std::string>& allowed = network.AllowedClasses(lane);
  return allowed.empty() || std::find(allowed.begin(), allowed.end(), vclass) != allowed.end();
}

bool PedestriansOnly(RoadNetwork& network, const std::string& lane) {
  const std::vector<std::string>& allowed = network.AllowedClasses(lane);
  return allowed.size() == 1 && allowed[0] == "pedestrian";
}

std::vector<std::string> InternalChain(RoadNetwork& network, const LaneLink& link) {
  std::vector<std::string> chain;
  std::string lane = link.internal;
  for (int hop = 0; hop < 8 && IsInternal(lane); ++hop) {
    chain.push_back(lane);
    const std::vector<LaneLink>& on = network.Links(lane);
    if (on.empty()) break;
    lane = IsInternal(on.front().internal) ? on.front().internal : on.front().lane;
  }
  return chain;
}

std::vector<std::string> InternalLanesBetween(RoadNetwork& network, const std::string& from,
                                              const std::string& to) {
  for (const LaneLink& l : network.Links(from)) {
    if (l.lane == to) return InternalChain(network, l);
  }
  return {};
}

std::string NextLaneOnRoute(RoadNetwork& network, const std::string& lane,
                            const std::vector<std::string>& route, int* route_index) {
  const std::vector<LaneLink>& links = network.Links(lane);
  const std::string edge = network.Lane(lane).edge;
  if (IsInternal(edge)) {  // inside a junction: the internal lane leads to exactly one lane
    return links.empty() ? "" : links.front().lane;
  }
  int k = *route_index;
  while (k < static_cast<int>(route.size()) && route[k] != edge) ++k;
  if (k + 1 >= static_cast<int>(route.size())) return "";
  for (const LaneLink& l : links) {
    if (network.Lane(l.lane).edge == route[k + 1]) {
      *route_index = k + 1;
      return l.lane;
    }
  }
  return "";
}

std::string NextLaneSeen(RoadNetwork& network, const std::string& lane, const std::string& vclass,
                         Blinker blinker) {
  const std::vector<LaneLink>& links = network.Links(lane);
  if (IsInternal(network.Lane(lane).edge)) return links.empty() ? "" : links.front().lane;
  std::vector<const char*> order;
  switch (blinker) {
    case Blinker::kLeft:
      order = {"l", "L", "t"};
      break;
    case Blinker::kRight:
      order = {"r", "R"};
      break;
    case Blinker::kNone:
      break;
  }
  for (const char* d : {"s", "L", "R"}) order.push_back(d);
  for (const char* d : order) {
    for (const LaneLink& l : links) {
      if (l.direction == d && Allows(network, l.lane, vclass)) return l.lane;
    }
  }
  for (const LaneLink& l : links) {
    if (Allows(network, l.lane, vclass)) return l.lane;
  }
  return "";
}

}  // namespace criticality::plugin
