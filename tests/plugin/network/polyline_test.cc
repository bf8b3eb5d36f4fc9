// Positions along a lane's centre line.
#include "plugin/network/polyline.h"

#include <gtest/gtest.h>

#include "criticality/geometry.h"

namespace criticality::plugin {
namespace {

TEST(Polyline, PointAlongWalksAndExtrapolates) {
  const std::vector<Point2> line{{0, 0}, {10, 0}, {10, 10}};
  double h = 0.0;
  Point2 p = PointAlong(line, 5.0, &h);
  EXPECT_NEAR(p.x, 5.0, 1e-12);
  EXPECT_NEAR(h, 0.0, 1e-12);
  p = PointAlong(line, 15.0, &h);
  EXPECT_NEAR(p.x, 10.0, 1e-12);
  EXPECT_NEAR(p.y, 5.0, 1e-12);
  EXPECT_NEAR(h, kPi / 2, 1e-12);
  p = PointAlong(line, 25.0, &h);  // past the end: extended
  EXPECT_NEAR(p.y, 15.0, 1e-12);
  p = PointAlong(line, -3.0, &h);  // before the start: extended backwards
  EXPECT_NEAR(p.x, -3.0, 1e-12);
  EXPECT_NEAR(PolylineLength(line), 20.0, 1e-12);
}

}  // namespace
}  // namespace criticality::plugin
