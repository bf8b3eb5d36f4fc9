#include "plugin/network/traffic_side.h"

#include <cmath>
#include <string>

#include "plugin/network/polyline.h"

namespace criticality::plugin {

namespace {

// Which side of lane 0 lane 1 lies on, at lane 0's middle: +1 left, -1 right, 0 unknown.
int SideOfSecondLane(const LaneInfo& first, const LaneInfo& second) {
  if (first.shape.size() < 2 || second.shape.size() < 2) return 0;
  double heading = 0.0;
  const Point2 mid = PointAlong(first.shape, 0.5 * PolylineLength(first.shape), &heading);
  // The nearest point of lane 1's centre line.
  double best = INFINITY, side = 0.0;
  for (size_t i = 1; i < second.shape.size(); ++i) {
    const Point2& a = second.shape[i - 1];
    const Point2& b = second.shape[i];
    const double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
    const double along = (mid.x - a.x) * dx + (mid.y - a.y) * dy;
    const double t = len2 > 0.0 ? std::fmax(0.0, std::fmin(1.0, along / len2)) : 0.0;
    const double px = a.x + t * dx - mid.x, py = a.y + t * dy - mid.y;
    const double d = std::hypot(px, py);
    if (d < best) {
      best = d;
      side = std::cos(heading) * py - std::sin(heading) * px;  // > 0: left of lane 0
    }
  }
  return side > 0.0 ? 1 : (side < 0.0 ? -1 : 0);
}

}  // namespace

bool LeftHandTraffic(RoadNetwork& network) {
  // A vote of the first kVotes edges with two lanes or more (one odd edge does not decide).
  constexpr int kVotes = 25;
  int left = 0, right = 0;
  for (const std::string& edge : network.Edges()) {
    if (IsInternal(edge) || network.LaneCount(edge) < 2) continue;
    const int side = SideOfSecondLane(network.Lane(edge + "_0"), network.Lane(edge + "_1"));
    left += side > 0;
    right += side < 0;
    if (left + right >= kVotes) break;
  }
  return right > left;
}

}  // namespace criticality::plugin
