// Where a walking person is in SUMO's pedestrian network (plugin/footway.h).
#include "plugin/scenes/footway.h"

#include <gtest/gtest.h>

#include "../fake_sumo_world.h"

#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace criticality::plugin {
namespace {

using testing::FakeSumoWorld;

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
  auto link = [](std::string state, bool foe) {
    return LaneLink{":J_c0_0", "", std::move(state), foe, "s"};
  };
  // Red, red-yellow, yellow: wait, whoever approaches.
  for (const char* st : {"r", "u", "y", "Y"}) EXPECT_TRUE(MustWaitAt(link(st, false))) << st;
  // No priority: wait while a vehicle approaches, else go.
  for (const char* st : {"s", "w", "m", "=", "g"}) {
    EXPECT_TRUE(MustWaitAt(link(st, true))) << st;
    EXPECT_FALSE(MustWaitAt(link(st, false))) << st;
  }
  // Priority (a zebra, a green light): it may cross.
  EXPECT_FALSE(MustWaitAt(link("M", true)));
  EXPECT_FALSE(MustWaitAt(link("G", true)));
  // A light's states, and none of the others.
  for (const char* st : {"G", "g", "y", "Y", "r", "u", "o", "O"}) {
    EXPECT_TRUE(SignalState(st)) << st;
  }
  for (const char* st : {"M", "m", "=", "s", "w", "Z", ""}) EXPECT_FALSE(SignalState(st)) << st;
}

// Junction J: a crossing without a light, netconvert's links :J_w0 -> :J_c0 (no priority, a
// vehicle approaching) and :J_c0 -> :J_w1. Junction K: a crossing with a light, red for the
// way from :K_w1 (the crossing's link into it), green the other way. Junction J_1 (a name
// that extends J's) has a walking area that leads nowhere.
FakeSumoWorld TwoCrossings() {
  FakeSumoWorld w;
  const std::vector<std::string> walkers = {"pedestrian"};
  for (const char* j : {":J", ":K", ":J_1"}) {
    const std::string s = j;
    w.AddEdge(s + "_w0", 0, -3, 3, -3, 1, 3.0, walkers);
    w.AddEdge(s + "_c0", 5, -3, 5, 10, 1, 3.0, walkers);
    w.AddEdge(s + "_w1", 0, 12, 3, 12, 1, 3.0, walkers);
  }
  w.AddLink(":J_w0_0", ":J_c0_0", "m", true);
  w.AddLink(":J_c0_0", ":J_w1_0", "M", false);
  w.AddLink(":K_w0_0", ":K_c0_0", "G", true);
  w.AddLink(":K_c0_0", ":K_w1_0", "r", true);
  return w;
}

TEST(Footway, AWalkerObeysTheLinkSumosPersonsObeyWhicheverWayItCrosses) {
  FakeSumoWorld w = TwoCrossings();
  CrossingEntries entries(&w);
  // Its way: the link from its walking area into the crossing.
  std::optional<LaneLink> e = entries.EntryLink(":J_w0_0", ":J_c0");
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->state, "m");
  EXPECT_TRUE(MustWaitAt(*e));
  // The other way, no light: the link into the crossing from the walking area at its other end
  // (the crossing's own link into this walking area, 'M', would let it go).
  e = entries.EntryLink(":J_w1_0", ":J_c0");
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->lane, ":J_c0_0");
  EXPECT_EQ(e->state, "m");
  EXPECT_TRUE(MustWaitAt(*e));
  // With a light: its way green, the other way the crossing's link into the walking area, red.
  e = entries.EntryLink(":K_w0_0", ":K_c0");
  ASSERT_TRUE(e.has_value());
  EXPECT_FALSE(MustWaitAt(*e));
  e = entries.EntryLink(":K_w1_0", ":K_c0");
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->lane, ":K_w1_0");
  EXPECT_TRUE(MustWaitAt(*e));
  // No link into J_1's crossing from either end (J's walking areas are another junction's);
  // an unknown crossing: none.
  EXPECT_FALSE(entries.EntryLink(":J_1_w1_0", ":J_1_c0").has_value());
  EXPECT_FALSE(entries.EntryLink(":J_w1_0", ":X_c9").has_value());
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
