// A vehicle's way through a junction (plugin/scenes/junction_way.h): sent for a body whose front
// or back is on an internal lane, in the vehicle's frame, from behind its back to its corridor's
// end, with its front and back where SUMO has them.
#include "plugin/scenes/junction_way.h"

#include <gtest/gtest.h>

#include <cmath>

#include "../fake_sumo_world.h"
#include "plugin/network/polyline.h"

namespace criticality::plugin {
namespace {

using testing::FakeSumoWorld;

// The point of the way at arc length s (its own polyline).
Point2 At(const Way& w, double s) {
  double heading = 0.0;
  return PointAlong(w.points, s, &heading);
}

TEST(JunctionWay, ABodyIsInAJunctionWhileItsFrontOrItsBackIsOnAnInternalLane) {
  FakeSumoWorld w;
  testing::AddSquareRightTurn(w);
  const std::vector<std::string> route = {"N", "E"};
  EXPECT_FALSE(BodyInJunction(w, "N_0", 50.0, 4.5, route, 0));   // on its approach
  EXPECT_TRUE(BodyInJunction(w, ":J_0_0", 3.0, 4.5, route, 0));  // front in the turn
  EXPECT_TRUE(BodyInJunction(w, "E_0", 2.0, 4.5, route, 1));     // back still in it
  EXPECT_FALSE(BodyInJunction(w, "E_0", 30.0, 4.5, route, 1));   // out of it
  EXPECT_FALSE(BodyInJunction(w, "", 3.0, 4.5, route, 0));       // on no lane (parked off it)
}

TEST(JunctionWay, TheWayPutsTheFrontAndTheBackWhereSumoHasThemInTheVehiclesFrame) {
  FakeSumoWorld w;
  testing::AddSquareRightTurn(w);
  // Front 3 m into :J_0_0 at (0, 3), heading north; its back 4.5 m behind on the lanes: at
  // (0, -1.5) on N. The vehicle's frame: its centre (0, 0.75), heading north.
  const Pose2 X_WV{0.0, 0.75, 0.5 * 3.14159265358979323846};
  const std::vector<Point2> ahead = {{0, 0}, {0, 5}, {5, 5}, {40, 5}};  // :J_0_0, then E
  const std::optional<Way> way = WayOf(w, ":J_0_0", 3.0, 4.5, {"N", "E"}, 0, ahead, X_WV);
  ASSERT_TRUE(way.has_value());
  EXPECT_NEAR(way->front_m - way->back_m, 4.5, 1e-9);
  const Point2 front = At(*way, way->front_m), back = At(*way, way->back_m);
  EXPECT_NEAR(front.x, 2.25, 1e-9);  // ahead of the centre, on its heading
  EXPECT_NEAR(front.y, 0.0, 1e-9);
  EXPECT_NEAR(back.x, -2.25, 1e-9);
  EXPECT_NEAR(back.y, 0.0, 1e-9);
  // It starts about kWayBehindBackM behind the back and follows the turn to the corridor's end:
  // the corner (0, 5) is 2 m ahead of the front, then east to x = 40 (to the right: -y).
  EXPECT_NEAR(way->back_m, kWayBehindBackM, 1e-9);
  const Point2 corner = At(*way, way->front_m + 2.0);
  EXPECT_NEAR(corner.x, 4.25, 1e-9);
  EXPECT_NEAR(corner.y, 0.0, 1e-9);
  EXPECT_NEAR(way->points.back().x, 4.25, 1e-9);
  EXPECT_NEAR(way->points.back().y, -40.0, 1e-9);
  EXPECT_LE(way->points.size(), static_cast<size_t>(kMaxWayPoints));
}

TEST(JunctionWay, ALongCorridorIsResampledToTheEstimatorsPointsWithItsEndsKept) {
  FakeSumoWorld w;
  testing::AddSquareRightTurn(w);
  std::vector<Point2> ahead = {{0, 0}, {0, 5}};
  for (int k = 1; k <= 100; ++k) ahead.push_back(Point2{5.0 + 0.5 * k, 5.0 + 0.01 * (k % 2)});
  const Pose2 X_WV{0.0, 0.75, 0.5 * 3.14159265358979323846};
  const std::optional<Way> way = WayOf(w, ":J_0_0", 3.0, 4.5, {"N", "E"}, 0, ahead, X_WV);
  ASSERT_TRUE(way.has_value());
  EXPECT_EQ(way->points.size(), static_cast<size_t>(kMaxWayPoints));
  EXPECT_NEAR(way->points.back().y, -55.0, 0.02);  // the corridor's end: (55, 5)
  const Point2 front = At(*way, way->front_m);
  EXPECT_NEAR(front.x, 2.25, 0.05);
  EXPECT_NEAR(front.y, 0.0, 0.05);
}

TEST(JunctionWay, ALineFoldingBackOnItselfGivesNoPointsTheEstimatorWouldRefuse) {
  // After the turn the corridor goes 1.5 cm on east and back to within 1.4 mm of the corner
  // (netconvert's shapes can fold like this at a U-turn's apex): that point is more than 2 cm
  // on along the line but not 1 cm from the corner, which Vehicle::way must not hold.
  FakeSumoWorld w;
  testing::AddSquareRightTurn(w);
  const std::vector<Point2> ahead = {{0, 0},         {0, 5},         {5, 5},
                                     {5.015, 5.0}, {5.001, 5.001}, {5.001, 40}};
  const Pose2 X_WV{0.0, 0.75, 0.5 * 3.14159265358979323846};
  const std::optional<Way> way = WayOf(w, ":J_0_0", 3.0, 4.5, {"N", "E"}, 0, ahead, X_WV);
  ASSERT_TRUE(way.has_value());
  for (size_t k = 1; k < way->points.size(); ++k) {
    EXPECT_GE(std::hypot(way->points[k].x - way->points[k - 1].x,
                         way->points[k].y - way->points[k - 1].y),
              0.01)
        << k;
  }
  EXPECT_NEAR(At(*way, way->front_m).x, 2.25, 1e-9);
  EXPECT_NEAR(At(*way, way->back_m).x, -2.25, 1e-9);
}

}  // namespace
}  // namespace criticality::plugin
