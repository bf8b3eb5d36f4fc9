// SUMO's heading along a vehicle's lanes (the chord from its back to its front) and how fast it
// turns around the front.
#include "plugin/scenes/lane_heading.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace criticality::plugin {
namespace {

constexpr double kPi = 3.14159265358979323846;

// East 20 m, then a corner and north 20 m: SUMO's heading of a 4 m body stays 0 while both
// ends are on the first piece, turns while the front rounds the corner, and is 90 degrees once
// the back has rounded it too.
const std::vector<Point2> kCorner = {{0.0, 0.0}, {20.0, 0.0}, {20.0, 20.0}};

TEST(LaneHeading, AStraightPieceGivesNoTurnAndItsDirection) {
  const auto h = HeadingAlong(WayLine{kCorner, 10.0}, 4.0, 10.0, 2.0, 2.0);
  ASSERT_TRUE(h.has_value());
  EXPECT_NEAR(h->yaw_rad, 0.0, 1e-12);
  EXPECT_NEAR(h->yaw_rate_radps, 0.0, 1e-12);
}

TEST(LaneHeading, AFrontApproachingACornerTurnsWithinTheWindowThoughItsChordHasNotYet) {
  // Front 1 m before the corner: the chord is still east (a one-step heading change reads 0),
  // but 2 m on the front is 1 m up the north piece and the body turns left.
  const auto h = HeadingAlong(WayLine{kCorner, 19.0}, 4.0, 10.0, 2.0, 2.0);
  ASSERT_TRUE(h.has_value());
  EXPECT_NEAR(h->yaw_rad, 0.0, 1e-12);
  const double to = std::atan2(1.0, 3.0);  // back at (17, 0), front at (20, 1)
  EXPECT_NEAR(h->yaw_rate_radps, 10.0 * to / 4.0, 1e-9);
  EXPECT_GT(h->yaw_rate_radps, 0.0);  // left turn: counter-clockwise, math yaw
}

TEST(LaneHeading, AWindowOnlyAheadReadsTheTurnTheFrontIsEntering) {
  // From the front now (chord east) to 2 m on (back at (17, 0), front at (20, 1)).
  const auto h = HeadingAlong(WayLine{kCorner, 19.0}, 4.0, 10.0, 0.0, 2.0);
  ASSERT_TRUE(h.has_value());
  EXPECT_NEAR(h->yaw_rate_radps, 10.0 * std::atan2(1.0, 3.0) / 2.0, 1e-9);
  // Only behind: both ends were on the east piece; no turn.
  const auto back = HeadingAlong(WayLine{kCorner, 19.0}, 4.0, 10.0, 2.0, 0.0);
  ASSERT_TRUE(back.has_value());
  EXPECT_NEAR(back->yaw_rate_radps, 0.0, 1e-12);
}

TEST(LaneHeading, APolygonOfACircleTurnsAtSpeedOverRadius) {
  // A right-hand circle of radius 25 m in 5-degree pieces, as a lane: v / R, clockwise.
  std::vector<Point2> circle;
  const double r = 25.0;
  for (int i = 0; i <= 36; ++i) {
    const double a = kPi / 2.0 - i * 5.0 * kPi / 180.0;
    circle.push_back({r * std::cos(a), r * std::sin(a)});
  }
  const auto h = HeadingAlong(WayLine{circle, 30.0}, 4.5, 12.0, 3.0, 3.0);
  ASSERT_TRUE(h.has_value());
  EXPECT_NEAR(h->yaw_rate_radps, -12.0 / r, 0.02 * 12.0 / r);
}

TEST(LaneHeading, TheWindowShrinksAtTheLinesEndAndFailsWhereTheBackIsNotOnIt) {
  // At the line's end only the window behind is left: the front rounds the corner over it.
  const auto end = HeadingAlong(WayLine{kCorner, 40.0}, 4.0, 10.0, 2.0, 2.0);
  ASSERT_TRUE(end.has_value());
  EXPECT_NEAR(end->yaw_rad, kPi / 2.0, 1e-12);
  EXPECT_NEAR(end->yaw_rate_radps, 0.0, 1e-12);  // both ends on the north piece throughout
  EXPECT_FALSE(HeadingAlong(WayLine{kCorner, 3.0}, 4.0, 10.0, 2.0, 2.0).has_value());  // back before start
  EXPECT_FALSE(HeadingAlong(WayLine{{{0.0, 0.0}}, 3.0}, 1.0, 10.0, 2.0, 2.0).has_value());
}

}  // namespace
}  // namespace criticality::plugin
