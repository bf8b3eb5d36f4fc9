#include "plugin/scenes/footway.h"

#include <cctype>

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

}  // namespace criticality::plugin
