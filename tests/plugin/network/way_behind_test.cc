// The way a vehicle came by (plugin/network/way_behind.h): the lanes behind its front through
// both parts of a junction turn that an internal junction splits, the point its length behind
// (SUMO's back position), the way of a vehicle that changed lanes since the junction, and where
// the way is not known.
#include "plugin/network/way_behind.h"

#include <gtest/gtest.h>

#include <cmath>

#include "../fake_sumo_world.h"
#include "criticality/geometry.h"
#include "plugin/network/polyline.h"

namespace criticality::plugin {
namespace {

using testing::FakeSumoWorld;

FakeSumoWorld UTurn() { return testing::SplitUTurn(); }

double LengthOf(FakeSumoWorld& w, const std::string& lane) { return w.Lane(lane).length_m; }

TEST(WayBehind, AUTurnsWayBackRunsThroughBothPartsOfItsInternalLane) {
  FakeSumoWorld w = UTurn();
  const std::vector<std::string> route{"N", "S"};
  EXPECT_EQ(LanesBehind(w, "S_0", route, 1, 10.0),
            (std::vector<std::string>{":J_28_0", ":J_14_0", "N_0"}));
  // From inside the junction (SUMO's route index is then the edge before it).
  EXPECT_EQ(LanesBehind(w, ":J_28_0", route, 0, 10.0),
            (std::vector<std::string>{":J_14_0", "N_0"}));
  EXPECT_EQ(LanesBehind(w, ":J_14_0", route, 0, 10.0), (std::vector<std::string>{"N_0"}));
  // Only as far as asked: the second part alone covers 2 m.
  EXPECT_EQ(LanesBehind(w, "S_0", route, 1, 2.0), (std::vector<std::string>{":J_28_0"}));
  // Where the route starts there is nothing behind.
  EXPECT_TRUE(LanesBehind(w, "S_0", {"S"}, 0, 10.0).empty());
}

TEST(WayBehind, TheBackOfATruckInAUTurnIsOnTheLaneItCameFrom) {
  FakeSumoWorld w = UTurn();
  const std::vector<std::string> route{"N", "S"};
  const double turn = LengthOf(w, ":J_14_0") + LengthOf(w, ":J_28_0");  // about 2 pi
  // A 7.1 m truck, its front 0.7 m into S: its back is on N, 7.1 - 0.7 - turn short of N's end.
  const std::optional<Point2> back = PointBehind(w, "S_0", 0.7, 7.1, route, 1);
  ASSERT_TRUE(back.has_value());
  EXPECT_NEAR(back->x, 0.0, 1e-9);
  EXPECT_NEAR(back->y, -(7.1 - 0.7 - turn), 1e-9);
  // On its own lane when it is far enough in.
  const std::optional<Point2> on_s = PointBehind(w, "S_0", 20.0, 7.1, route, 1);
  ASSERT_TRUE(on_s.has_value());
  EXPECT_NEAR(on_s->x, -4.0, 1e-9);
  EXPECT_NEAR(on_s->y, -12.9, 1e-9);
  // In the turn's second part: back through the first part onto N.
  const std::optional<Point2> inside = PointBehind(w, ":J_28_0", 1.0, 5.0, route, 0);
  ASSERT_TRUE(inside.has_value());
  EXPECT_NEAR(inside->x, 0.0, 1e-9);
  EXPECT_NEAR(inside->y, -(5.0 - 1.0 - LengthOf(w, ":J_14_0")), 1e-9);
  // Not known beyond the start of the route.
  EXPECT_FALSE(PointBehind(w, "S_0", 0.7, 7.1, {"S"}, 0).has_value());
}

TEST(WayBehind, AVehicleThatChangedLanesAfterTheJunctionCameByTheLinkBesideIt) {
  // N leads into E's lane 0 only; the vehicle is on E's lane 1 now (3.2 m left of lane 0).
  FakeSumoWorld w;
  w.AddEdge("N", 0, -100, 0, -10, 1);
  w.AddLaneShape(":J_0", {Point2{0, -10}, Point2{0, -1.6}});
  w.AddEdge("E", 0, 0, 100, 0, 2);  // lane 0 at y = -1.6, lane 1 at y = +1.6
  // (the internal lane is straight up to lane 0's start; enough for the way behind)
  w.AddLinkVia("N_0", "E_0", ":J_0_0");
  w.AddLink(":J_0_0", "E_0");
  const std::vector<std::string> route{"N", "E"};
  EXPECT_EQ(LanesBehind(w, "E_1", route, 1, 10.0), (std::vector<std::string>{":J_0_0", "N_0"}));
  // SUMO's back stays on the lanes it came by.
  const std::optional<Point2> back = PointBehind(w, "E_1", 2.0, 5.0, route, 1);
  ASSERT_TRUE(back.has_value());
  EXPECT_NEAR(back->x, 0.0, 1e-9);
  EXPECT_NEAR(back->y, -1.6 - 3.0, 1e-9);
  // The way the body lies along is moved sideways onto E_1: it meets E_1's start, no jump.
  const WayLine way = LineBehind(w, "E_1", 2.0, 5.0, route, 1);
  EXPECT_NEAR(way.front_m, 2.0 + 8.4, 1e-9);  // as far back as asked: the internal lane
  const std::optional<Point2> front = PointOnWay(way, 0.0);
  const std::optional<Point2> behind = PointOnWay(way, 5.0);
  ASSERT_TRUE(front && behind);
  EXPECT_NEAR(front->x, 2.0, 1e-9);
  EXPECT_NEAR(front->y, 1.6, 1e-9);
  EXPECT_NEAR(behind->x, 0.0, 1e-9);  // 3 m down the joined internal lane, 3.2 m to the left
  EXPECT_NEAR(behind->y, 1.6 - 3.0, 1e-9);
  // Just behind the joint the way runs on at x = 0 from E_1's start: unjoined, it would jump
  // 3.2 m to the internal lane's end at y = -1.6.
  const std::optional<Point2> past_joint = PointOnWay(way, 2.1);
  ASSERT_TRUE(past_joint.has_value());
  EXPECT_NEAR(past_joint->x, 0.0, 1e-9);
  EXPECT_NEAR(past_joint->y, 1.5, 1e-9);
  EXPECT_FALSE(PointOnWay(way, way.front_m + 1.0).has_value());
  // The lanes behind were moved by the lanes' spacing, which tells the lane change.
  EXPECT_NEAR(way.shifted_m, 3.2, 1e-9);
  // Where the vehicle kept its lane the lanes behind meet it: nothing moved.
  EXPECT_NEAR(LineBehind(w, "E_0", 2.0, 5.0, route, 1).shifted_m, 0.0, 1e-9);
}

}  // namespace
}  // namespace criticality::plugin
