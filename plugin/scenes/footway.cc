#include "plugin/scenes/footway.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>

namespace criticality::plugin {
namespace {

// Whether an internal edge ID ends in "_<letter><digits>".
bool JunctionPart(const std::string& edge, char letter) {
  if (edge.empty() || edge[0] != ':') return false;
  const auto us = edge.rfind('_');
  // At least one digit after the letter.
  if (us == std::string::npos || us + 2 >= edge.size() || edge[us + 1] != letter) return false;
  for (size_t i = us + 2; i < edge.size(); ++i) {
    if (!std::isdigit(static_cast<unsigned char>(edge[i]))) return false;
  }
  return true;
}

}  // namespace

WalkingPlace WalkingPlaceOf(const std::string& edge, bool pedestrians_only) {
  if (!pedestrians_only) return WalkingPlace::kRoad;
  if (JunctionPart(edge, 'c')) return WalkingPlace::kCrossing;
  if (JunctionPart(edge, 'w')) return WalkingPlace::kWalkingArea;
  return WalkingPlace::kSidewalk;
}

bool StaysOnFootway(WalkingPlace here, WalkingPlace next) {
  const bool on_footway = here == WalkingPlace::kSidewalk || here == WalkingPlace::kWalkingArea;
  const bool next_on_footway = next == WalkingPlace::kSidewalk || next == WalkingPlace::kWalkingArea;
  return on_footway && next_on_footway;
}

bool WaitsAtCrossing(const std::vector<LaneLink>& links, const std::string& crossing_lane) {
  for (const LaneLink& l : links) {
    if (l.lane != crossing_lane && l.internal != crossing_lane) continue;
    const std::string& st = l.state;
    if (st == "r" || st == "u" || st == "y" || st == "Y") return true;
    const bool no_priority = st == "s" || st == "w" || st == "m" || st == "=" || st == "g";
    return no_priority && l.has_foe;
  }
  return false;
}

double DistanceToCrossing(const LaneInfo& crossing, double x_m, double y_m) {
  if (crossing.shape.empty()) return std::numeric_limits<double>::infinity();
  const Point2& a = crossing.shape.front();
  const Point2& b = crossing.shape.back();
  return std::min(std::hypot(a.x - x_m, a.y - y_m), std::hypot(b.x - x_m, b.y - y_m));
}

double CrossingStopDecel(double speed_mps, double distance_m) {
  if (!(speed_mps > 0.0) || !(distance_m >= 0.0) || std::isinf(distance_m)) return 0.0;
  if (distance_m <= 0.0) return -kCrossingStopMaxDecel;
  return -std::min(speed_mps * speed_mps / (2.0 * distance_m), kCrossingStopMaxDecel);
}

}  // namespace criticality::plugin
