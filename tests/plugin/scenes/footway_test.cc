// Where a walking person is in SUMO's pedestrian network (plugin/footway.h).
#include "plugin/scenes/footway.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace criticality::plugin {
namespace {

TEST(Footway, PlacesFromSumoEdgeIds) {
  EXPECT_EQ(WalkingPlaceOf("E3D3", true), WalkingPlace::kSidewalk);
  EXPECT_EQ(WalkingPlaceOf(":D3_w1", true), WalkingPlace::kWalkingArea);
  EXPECT_EQ(WalkingPlaceOf(":D3_c0", true), WalkingPlace::kCrossing);
  // Junction IDs with underscores and letters; only the last part counts.
  EXPECT_EQ(WalkingPlaceOf(":cluster_c1_w2_c12", true), WalkingPlace::kCrossing);
  EXPECT_EQ(WalkingPlaceOf(":cluster_c1_w2", true), WalkingPlace::kWalkingArea);
  // A vehicles' internal lane, a normal edge named like a crossing, a letter without digits.
  EXPECT_EQ(WalkingPlaceOf(":D3_12", true), WalkingPlace::kSidewalk);
  EXPECT_EQ(WalkingPlaceOf("road_c1", true), WalkingPlace::kSidewalk);
  EXPECT_EQ(WalkingPlaceOf(":D3_c", true), WalkingPlace::kSidewalk);
  EXPECT_EQ(WalkingPlaceOf(":D3_c1x", true), WalkingPlace::kSidewalk);
  // Lanes that vehicles may use are road, whatever their name.
  EXPECT_EQ(WalkingPlaceOf("E3D3", false), WalkingPlace::kRoad);
  EXPECT_EQ(WalkingPlaceOf(":D3_c0", false), WalkingPlace::kRoad);
  EXPECT_EQ(WalkingPlaceOf("", false), WalkingPlace::kRoad);
}

TEST(Footway, StaysOnFootwayOnlyWhenNeitherHereNorNextIsRoadOrCrossing) {
  using P = WalkingPlace;
  EXPECT_TRUE(StaysOnFootway(P::kSidewalk, P::kWalkingArea));
  EXPECT_TRUE(StaysOnFootway(P::kWalkingArea, P::kSidewalk));
  EXPECT_TRUE(StaysOnFootway(P::kSidewalk, P::kSidewalk));
  EXPECT_FALSE(StaysOnFootway(P::kWalkingArea, P::kCrossing));  // about to cross
  EXPECT_FALSE(StaysOnFootway(P::kSidewalk, P::kRoad));
  EXPECT_FALSE(StaysOnFootway(P::kCrossing, P::kWalkingArea));  // crossing now
  EXPECT_FALSE(StaysOnFootway(P::kRoad, P::kSidewalk));
}

TEST(Footway, AWalkerWaitsAtACrossingItMayNotEnterYet) {
  const std::string crossing = ":J_c0_0";
  auto links = [&](std::string state, bool foe) {
    return std::vector<LaneLink>{LaneLink{":J_w1_0", "", "G", true, "s"},  // another way on
                                 LaneLink{crossing, "", state, foe, "s"}};
  };
  // Red, red-yellow, yellow: wait, whoever approaches.
  for (const char* st : {"r", "u", "y"})
    EXPECT_TRUE(WaitsAtCrossing(links(st, false), crossing)) << st;
  // No priority: wait while a vehicle approaches, else go.
  for (const char* st : {"s", "w", "m", "=", "g"}) {
    EXPECT_TRUE(WaitsAtCrossing(links(st, true), crossing)) << st;
    EXPECT_FALSE(WaitsAtCrossing(links(st, false), crossing)) << st;
  }
  // Priority (a zebra, a green light): it may cross.
  EXPECT_FALSE(WaitsAtCrossing(links("M", true), crossing));
  EXPECT_FALSE(WaitsAtCrossing(links("G", true), crossing));
  // Only the link into the crossing counts; none: no obligation known.
  EXPECT_FALSE(WaitsAtCrossing({LaneLink{":J_w1_0", "", "r", true, "s"}}, crossing));
  EXPECT_FALSE(WaitsAtCrossing({}, crossing));
}

TEST(Footway, AWaitingWalkerStopsWhereItsCrossingBegins) {
  // The crossing runs from (10, 0) to (10, 8); a walk onto it begins at the nearer end.
  LaneInfo crossing;
  crossing.shape = {{10.0, 0.0}, {10.0, 8.0}};
  EXPECT_DOUBLE_EQ(DistanceToCrossing(crossing, 7.0, -4.0), 5.0);
  EXPECT_DOUBLE_EQ(DistanceToCrossing(crossing, 10.0, 11.0), 3.0);  // from the other side
  EXPECT_TRUE(std::isinf(DistanceToCrossing(LaneInfo{}, 0.0, 0.0)));
  // v^2 / (2 d): 1.2 m/s within 0.3 m.
  EXPECT_DOUBLE_EQ(CrossingStopDecel(1.2, 0.3), -2.4);
  EXPECT_DOUBLE_EQ(CrossingStopDecel(1.0, 5.0), -0.1);
  // Already there, or nearer than its hardest stop: the hardest stop.
  EXPECT_DOUBLE_EQ(CrossingStopDecel(1.2, 0.0), -kCrossingStopMaxDecel);
  EXPECT_DOUBLE_EQ(CrossingStopDecel(2.0, 0.1), -kCrossingStopMaxDecel);
  // Standing, or nowhere known to stop: nothing expected.
  EXPECT_DOUBLE_EQ(CrossingStopDecel(0.0, 0.3), 0.0);
  EXPECT_DOUBLE_EQ(CrossingStopDecel(1.2, std::numeric_limits<double>::infinity()), 0.0);
}

}  // namespace
}  // namespace criticality::plugin
