#pragma once
// Which lane carries traffic the other way just left of a lane: the leftmost lane of another
// edge whose centre line runs anti-parallel one half-width pair to the left, at a quarter, half
// and three quarters of the lane's length (at least two of the three points agree). A road of
// two one-way edges, as SUMO's netconvert builds two-way streets, has no other link between its
// directions. Candidates come from a grid over every edge's leftmost lane, built at the first
// question; answers are cached per lane (memory grows with the lanes asked about, not time).
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "plugin/network/road_network.h"

namespace criticality::plugin {

class CounterLanes {
 public:
  explicit CounterLanes(RoadNetwork* network) : network_(network) {}
  /** The adjacent lane of the opposite direction left of `lane`, if any. */
  std::optional<std::string> LeftOf(const std::string& lane);

 private:
  struct LeftmostSegment {
    Point2 a, b;
    std::string edge, lane;
  };
  void BuildIndex();
  std::vector<const LeftmostSegment*> SegmentsNear(const Point2& p) const;

  RoadNetwork* network_;
  std::unordered_map<std::string, std::optional<std::string>> cache_;
  bool index_built_{false};
  std::vector<LeftmostSegment> segments_;
  std::unordered_map<unsigned long long, std::vector<int>> grid_;
};

}  // namespace criticality::plugin
