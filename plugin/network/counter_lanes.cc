#include "plugin/network/counter_lanes.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "plugin/network/polyline.h"
#include "plugin/network/traffic_side.h"

namespace criticality::plugin {
namespace {

constexpr double kIndexCell = 25.0;  // m

unsigned long long CellKey(long long cx, long long cy) {
  return (static_cast<unsigned long long>(cx) << 32) ^
         (static_cast<unsigned long long>(cy) & 0xffffffffULL);
}

long long Cell(double v) { return static_cast<long long>(std::floor(v / kIndexCell)); }

}  // namespace

bool CounterLanes::LeftHand() {
  if (!left_hand_) left_hand_ = LeftHandTraffic(*network_);
  return *left_hand_;
}

std::optional<std::string> CounterLanes::Offside(const std::string& lane) {
  auto cached = cache_.find(lane);
  if (cached != cache_.end()) return cached->second;
  BuildIndex();
  const double side = LeftHand() ? -1.0 : 1.0;  // the offside: +1 left, -1 right
  const LaneInfo& own = network_->Lane(lane);
  const double length = PolylineLength(own.shape);
  std::map<std::string, int> votes;
  for (double f : {0.25, 0.5, 0.75}) {
    double heading = 0.0;
    const Point2 mid = PointAlong(own.shape, f * length, &heading);
    std::set<std::string> here;
    for (const OffsideSegment* seg : SegmentsNear(mid)) {
      if (seg->edge == own.edge || here.count(seg->lane)) continue;
      const double off = side * 0.5 * (own.width_m + network_->Lane(seg->lane).width_m);
      const Point2 q{mid.x - std::sin(heading) * off, mid.y + std::cos(heading) * off};
      const double dx = seg->b.x - seg->a.x, dy = seg->b.y - seg->a.y;
      const double len2 = dx * dx + dy * dy;
      if (len2 <= 0.0) continue;
      const double t =
          std::fmax(0.0, std::fmin(1.0, ((q.x - seg->a.x) * dx + (q.y - seg->a.y) * dy) / len2));
      const double px = seg->a.x + t * dx, py = seg->a.y + t * dy;
      const double cosang = (dx * std::cos(heading) + dy * std::sin(heading)) / std::sqrt(len2);
      if (std::hypot(q.x - px, q.y - py) < 0.5 && cosang < -0.9) here.insert(seg->lane);
    }
    for (const std::string& l : here) ++votes[l];
  }
  std::optional<std::string> found;
  int best = 1;  // at least two of the three points
  for (const auto& [l, n] : votes) {
    if (n > best) {
      best = n;
      found = l;
    }
  }
  cache_[lane] = found;
  return found;
}

void CounterLanes::BuildIndex() {
  if (index_built_) return;
  index_built_ = true;
  for (const std::string& edge : network_->Edges()) {
    if (IsInternal(edge)) continue;
    const std::string lane = edge + "_" + std::to_string(network_->LaneCount(edge) - 1);
    const std::vector<Point2>& shape = network_->Lane(lane).shape;
    for (size_t i = 1; i < shape.size(); ++i) {
      segments_.push_back(OffsideSegment{shape[i - 1], shape[i], edge, lane});
      const int id = static_cast<int>(segments_.size()) - 1;
      // Every cell the segment's bounding box touches.
      const long long x0 = Cell(std::min(shape[i - 1].x, shape[i].x));
      const long long x1 = Cell(std::max(shape[i - 1].x, shape[i].x));
      const long long y0 = Cell(std::min(shape[i - 1].y, shape[i].y));
      const long long y1 = Cell(std::max(shape[i - 1].y, shape[i].y));
      for (long long cx = x0; cx <= x1; ++cx) {
        for (long long cy = y0; cy <= y1; ++cy) grid_[CellKey(cx, cy)].push_back(id);
      }
    }
  }
}

std::vector<const CounterLanes::OffsideSegment*> CounterLanes::SegmentsNear(
    const Point2& p) const {
  std::vector<const OffsideSegment*> out;
  std::set<int> seen;
  const long long cx = Cell(p.x), cy = Cell(p.y);
  for (long long x = cx - 1; x <= cx + 1; ++x) {
    for (long long y = cy - 1; y <= cy + 1; ++y) {
      auto it = grid_.find(CellKey(x, y));
      if (it == grid_.end()) continue;
      for (int id : it->second) {
        if (seen.insert(id).second) out.push_back(&segments_[id]);
      }
    }
  }
  return out;
}

}  // namespace criticality::plugin
