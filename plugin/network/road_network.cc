#include "plugin/network/road_network.h"

#include <algorithm>

#include "plugin/network/polyline.h"

namespace criticality::plugin {

double OnShape(const LaneInfo& lane, double lane_position_m) {
  return lane.length_m > 0.0 ? lane_position_m * PolylineLength(lane.shape) / lane.length_m
                             : lane_position_m;
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
