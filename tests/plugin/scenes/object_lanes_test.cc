// The corridor ahead of a vehicle (plugin/scenes/object_lanes.h, FollowRoute): through a junction
// turn it follows both parts of the junction's internal lane with junction_shapes, and jumps
// along the chord between the lanes without.
#include "plugin/scenes/object_lanes.h"

#include <gtest/gtest.h>

#include <cmath>

#include "../fake_sumo_world.h"
#include "criticality/geometry.h"

namespace criticality::plugin {
namespace {

using testing::FakeSumoWorld;

FakeSumoWorld UTurn() { return testing::SplitUTurn(); }

// The corridor's largest distance north of y = 0 (how far it reaches into the turn).
double NorthMost(const LaneCorridor& c) {
  double y = -1e9;
  for (const Point2& p : c.centre) y = std::fmax(y, p.y);
  return y;
}

LaneCorridor CorridorOf(FakeSumoWorld& w, bool junction_shapes) {
  VehicleOnLane v;
  v.lane = "N_0";
  v.lane_position_m = 95.0;
  v.route = {"N", "S"};
  v.route_index = 0;
  v.junction_shapes = junction_shapes;
  LaneCorridor c;
  c.centre = w.Lane("N_0").shape;
  c.position_m = 92.5;
  std::string beyond;
  std::optional<double> route_end;
  FollowRoute(v, 30.0, &w, &c, &beyond, &route_end);
  EXPECT_EQ(beyond, "S_0");
  return c;
}

TEST(ObjectLanes, WithJunctionShapesTheCorridorFollowsBothPartsOfAUTurn) {
  FakeSumoWorld w = UTurn();
  const LaneCorridor c = CorridorOf(w, true);
  // The turn's apex (-2, 2) is on the centre line: the first part's end, the second's start.
  bool apex = false, second_part = false;
  for (const Point2& p : c.centre) {
    if (std::hypot(p.x + 2.0, p.y - 2.0) < 1e-9) apex = true;
    const double a = 0.75 * kPi;  // a point inside the second part only
    if (std::hypot(p.x - (-2.0 + 2.0 * std::cos(a)), p.y - 2.0 * std::sin(a)) < 1e-9)
      second_part = true;
  }
  EXPECT_TRUE(apex);
  EXPECT_TRUE(second_part);
  EXPECT_NEAR(NorthMost(c), 2.0, 1e-9);
  EXPECT_NEAR(c.centre.back().x, -4.0, 1e-9);
  EXPECT_NEAR(c.centre.back().y, -100.0, 1e-9);
}

TEST(ObjectLanes, WithoutJunctionShapesTheCorridorJumpsAlongTheChord) {
  FakeSumoWorld w = UTurn();
  const LaneCorridor c = CorridorOf(w, false);
  // From N's end (0, 0) straight to S's start (-4, 0): nothing north of the junction.
  EXPECT_NEAR(NorthMost(c), 0.0, 1e-9);
  EXPECT_NEAR(c.centre.back().x, -4.0, 1e-9);
}

}  // namespace
}  // namespace criticality::plugin
