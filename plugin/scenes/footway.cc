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

bool SignalState(const std::string& state) {
  return state == "G" || state == "g" || state == "y" || state == "Y" || state == "r" ||
         state == "u" || state == "o" || state == "O";
}

bool MustWaitAt(const LaneLink& entry) {
  const std::string& st = entry.state;
  if (st == "r" || st == "u" || st == "y" || st == "Y") return true;
  const bool no_priority = st == "s" || st == "w" || st == "m" || st == "=" || st == "g";
  return no_priority && entry.has_foe;
}

namespace {

// The link of `links` that leads to `lane` (directly or through it as its internal lane).
std::optional<LaneLink> LinkTo(const std::vector<LaneLink>& links, const std::string& lane) {
  for (const LaneLink& l : links) {
    if (l.lane == lane || l.internal == lane) return l;
  }
  return std::nullopt;
}

// ":J_c0" -> ":J": the junction of one of its crossings' or walking areas' edge IDs.
std::string JunctionOf(const std::string& edge) { return edge.substr(0, edge.rfind('_')); }

}  // namespace

std::optional<LaneLink> CrossingEntries::EntryLink(const std::string& walking_lane,
                                                   const std::string& crossing_edge) {
  const std::string crossing_lane = crossing_edge + "_0";  // a crossing has one lane
  // Walking the crossing its way: the link from the walking area into it.
  if (auto forward = LinkTo(network_->LinksNow(walking_lane), crossing_lane)) return forward;
  // The other way: the crossing's link into this walking area where a light controls it.
  if (auto back = LinkTo(network_->LinksNow(crossing_lane), walking_lane)) {
    if (SignalState(back->state)) return back;
  }
  // Else the link into the crossing from the walking area at its other end.
  for (const std::string& other : WalkingAreasBeside(crossing_edge)) {
    if (other == walking_lane || !LinkTo(network_->Links(other), crossing_lane)) continue;
    return LinkTo(network_->LinksNow(other), crossing_lane);
  }
  return std::nullopt;
}

const std::vector<std::string>& CrossingEntries::WalkingAreasBeside(
    const std::string& crossing_edge) {
  if (!scanned_) {
    for (const std::string& edge : network_->Edges()) {
      if (JunctionPart(edge, 'w')) walking_areas_[JunctionOf(edge)].push_back(edge + "_0");
    }
    scanned_ = true;
  }
  static const std::vector<std::string> kNone;
  const auto it = walking_areas_.find(JunctionOf(crossing_edge));
  return it == walking_areas_.end() ? kNone : it->second;
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
