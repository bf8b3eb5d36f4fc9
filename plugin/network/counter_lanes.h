#pragma once
// Which lane carries traffic the other way beside a lane on its offside (the driver's left in
// right-hand traffic, the right in a left-hand network: traffic_side.h): the highest-index lane
// of another edge whose centre line runs anti-parallel one half-width pair to that side, at a
// quarter, half and three quarters of the lane's length (at least two of the three points
// agree). A road of two one-way edges, as SUMO's netconvert builds two-way streets, has no other
// link between its directions. Candidates come from a grid over every edge's highest-index
// lane, built at the first question; answers are cached per lane (memory grows with the lanes
// asked about, not time).
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "plugin/network/road_network.h"

namespace criticality::plugin {

class CounterLanes {
 public:
  explicit CounterLanes(RoadNetwork* network) : network_(network) {}
  /** The adjacent lane of the opposite direction on the offside of `lane`, if any. */
  std::optional<std::string> Offside(const std::string& lane);
  /** Whether the network drives on the left (LeftHandTraffic, read at the first question). */
  bool LeftHand();

 private:
  struct OffsideSegment {
    Point2 a, b;
    std::string edge, lane;
  };
  void BuildIndex();
  std::vector<const OffsideSegment*> SegmentsNear(const Point2& p) const;

  RoadNetwork* network_;
  std::optional<bool> left_hand_;
  std::unordered_map<std::string, std::optional<std::string>> cache_;
  bool index_built_{false};
  std::vector<OffsideSegment> segments_;
  std::unordered_map<unsigned long long, std::vector<int>> grid_;
};

}  // namespace criticality::plugin
