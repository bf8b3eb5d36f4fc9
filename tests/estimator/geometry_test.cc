// The public geometry (criticality/geometry.h) on values worked out by hand, and bit for bit
// what the estimator's own core functions give.
#include "criticality/geometry.h"

#include <gtest/gtest.h>

#include <random>

#include "core/geometry.h"
#include "core/oriented_box.h"

namespace criticality {
namespace {

TEST(Geometry, WrapAngleFoldsIntoMinusPiToPi) {
  // 3.5 pi = 4 pi - pi / 2.
  EXPECT_NEAR(WrapAngle(3.5 * kPi), -0.5 * kPi, 1e-12);
  EXPECT_NEAR(WrapAngle(-3.5 * kPi), 0.5 * kPi, 1e-12);
  // The interval is half open: pi is -pi, -pi stays; angles inside are returned as they are.
  EXPECT_EQ(WrapAngle(kPi), -kPi);
  EXPECT_EQ(WrapAngle(-kPi), -kPi);
  EXPECT_EQ(WrapAngle(0.25), 0.25);
  EXPECT_EQ(kPi, 3.14159265358979323846);
}

TEST(Geometry, PointGoesToTheWorldAndBack) {
  // Frame L at (10, 5), turned a quarter to the left: its x axis is the world's +y, its y axis
  // the world's -x, so the local point (2, 1) is 2 m up and 1 m left of the origin: (9, 7).
  const Pose2 X_WL{10.0, 5.0, 0.5 * kPi};
  double xw, yw;
  LocalToWorld(X_WL, 2.0, 1.0, &xw, &yw);
  EXPECT_NEAR(xw, 9.0, 1e-12);
  EXPECT_NEAR(yw, 7.0, 1e-12);
  double xl, yl;
  WorldToLocal(X_WL, xw, yw, &xl, &yl);
  EXPECT_NEAR(xl, 2.0, 1e-12);
  EXPECT_NEAR(yl, 1.0, 1e-12);
  // A frame's own origin is its pose's position.
  WorldToLocal(X_WL, 10.0, 5.0, &xl, &yl);
  EXPECT_EQ(xl, 0.0);
  EXPECT_EQ(yl, 0.0);
}

TEST(Geometry, CrossingRectanglesWithNoCornerInsideOverlap) {
  // A plus sign: two 10 m x 2 m rectangles on the same centre, one turned a quarter against the
  // other. Every corner lies 5 m along one and 1 m across, outside the other's 1 m half width,
  // so a corner-in-polygon test would miss it; the rectangles cross all the same.
  const Pose2 a{3.0, -2.0, 0.3};
  const Pose2 b{3.0, -2.0, 0.3 + 0.5 * kPi};
  EXPECT_TRUE(RectanglesOverlap(a, 5.0, 1.0, b, 5.0, 1.0));
  EXPECT_TRUE(RectanglesOverlap(b, 5.0, 1.0, a, 5.0, 1.0));
}

TEST(Geometry, RectanglesOneCentimetreApartDoNotOverlapAndTouchingOnesDo) {
  // Two 4 m x 2 m rectangles nose to tail on the x axis: the first ends at x = 2, the second
  // starts at 2.01.
  const Pose2 a{0.0, 0.0, 0.0};
  EXPECT_FALSE(RectanglesOverlap(a, 2.0, 1.0, Pose2{4.01, 0.0, 0.0}, 2.0, 1.0));
  EXPECT_FALSE(RectanglesOverlap(a, 2.0, 1.0, Pose2{0.0, -2.01, 0.0}, 2.0, 1.0));  // side by side
  // Touching counts (x = 2 exactly on both).
  EXPECT_TRUE(RectanglesOverlap(a, 2.0, 1.0, Pose2{4.0, 0.0, 0.0}, 2.0, 1.0));
  // Turned a quarter, 1 cm beyond the first one's left side (y = 1): its near side is at 1.01.
  EXPECT_FALSE(RectanglesOverlap(a, 2.0, 1.0, Pose2{0.0, 3.01, 0.5 * kPi}, 2.0, 1.0));
  EXPECT_TRUE(RectanglesOverlap(a, 2.0, 1.0, Pose2{0.0, 2.99, 0.5 * kPi}, 2.0, 1.0));
}

TEST(Geometry, ResultsAreTheCoreFunctionsBitForBit) {
  // Seeded poses, overlapping and apart: the public functions must give exactly what
  // the estimator computes inside, or a caller's judgement (the driver's critical events)
  // could disagree with the estimator's on a touching pair.
  std::mt19937_64 rng(7);
  auto uni = [&](double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
  };
  int overlaps = 0;
  for (int k = 0; k < 20000; ++k) {
    const double angle = uni(-40.0, 40.0);
    EXPECT_EQ(WrapAngle(angle), core::WrapAngle(angle));
    const Pose2 a{uni(-5.0, 5.0), uni(-5.0, 5.0), uni(-4.0, 4.0)};
    const Pose2 b{uni(-5.0, 5.0), uni(-5.0, 5.0), uni(-4.0, 4.0)};
    const double hla = uni(0.2, 3.0), hwa = uni(0.2, 1.2), hlb = uni(0.2, 3.0), hwb = uni(0.2, 1.2);
    const bool core_overlap = core::BoxesOverlap(core::MakeBox(a.x, a.y, a.yaw, hla, hwa),
                                                 core::MakeBox(b.x, b.y, b.yaw, hlb, hwb));
    ASSERT_EQ(RectanglesOverlap(a, hla, hwa, b, hlb, hwb), core_overlap) << k;
    overlaps += core_overlap ? 1 : 0;
    const core::Pose2 c{a.x, a.y, a.yaw};
    double x1, y1, x2, y2;
    WorldToLocal(a, b.x, b.y, &x1, &y1);
    core::WorldToLocal(c, b.x, b.y, &x2, &y2);
    ASSERT_EQ(x1, x2);
    ASSERT_EQ(y1, y2);
    LocalToWorld(a, b.x, b.y, &x1, &y1);
    core::LocalToWorld(c, b.x, b.y, &x2, &y2);
    ASSERT_EQ(x1, x2);
    ASSERT_EQ(y1, y2);
  }
  // Both answers occur, so the comparison says something about each.
  EXPECT_GT(overlaps, 2000);
  EXPECT_LT(overlaps, 18000);
}

}  // namespace
}  // namespace criticality
