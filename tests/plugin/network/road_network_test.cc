// Lanes whose SUMO length differs from their drawn shape (plugin/network/road_network.h,
// LanesWithLengthOffShape): a network built with explicit edge lengths, where SUMO moves
// vehicles by the length and the estimator predicts in the drawn coordinates.
#include "plugin/network/road_network.h"

#include <gtest/gtest.h>

#include "../fake_sumo_world.h"

namespace criticality::plugin {
namespace {

using testing::FakeSumoWorld;

TEST(RoadNetwork, LanesWhoseLengthIsNotTheirDrawnShapeAreFound) {
  FakeSumoWorld w;
  w.AddEdge("A", 0, 0, 100, 0, 2);    // drawn 100 m, length 100 m
  w.AddEdge("B", 100, 0, 200, 0, 1);  // drawn 100 m
  w.AddEdge(":J_0", 100, 0, 100, 5, 1);
  EXPECT_EQ(LanesWithLengthOffShape(w).lanes, 0);
  // Netconvert's smoothing: a few percent, or less than a metre on a short lane: not counted.
  w.SetLaneLength("A_0", 104.0);
  w.SetLaneLength(":J_0_0", 9.0);  // internal lanes are never counted
  EXPECT_EQ(LanesWithLengthOffShape(w).lanes, 0);
  // Explicit lengths: 8.7 times the drawing, and 0.8 of it.
  w.SetLaneLength("B_0", 870.0);
  w.SetLaneLength("A_1", 80.0);
  const LanesOffShape off = LanesWithLengthOffShape(w);
  EXPECT_EQ(off.lanes, 2);
  EXPECT_EQ(off.worst, "B_0");
  EXPECT_DOUBLE_EQ(off.worst_length_m, 870.0);
  EXPECT_NEAR(off.worst_shape_m, 100.0, 1e-9);
}

}  // namespace
}  // namespace criticality::plugin
