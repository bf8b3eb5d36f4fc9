// Collision recognition's primitive: exact rectangle overlap by separating axes, checked against
// an independent method (edge intersection + point in polygon) on seeded random pairs.
#include "core/oriented_box.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include "core/geometry.h"

namespace criticality::core {
namespace {

using Corners = std::array<std::array<double, 2>, 4>;

Corners CornersOf(const OrientedBox<double>& b) {
  Corners c;
  const double sx[4] = {1, -1, -1, 1}, sy[4] = {1, 1, -1, -1};
  for (int k = 0; k < 4; ++k) {
    const double lx = sx[k] * b.hl, ly = sy[k] * b.hw;
    c[k] = {b.cx + b.c * lx - b.s * ly, b.cy + b.s * lx + b.c * ly};
  }
  return c;
}

double Cross(const std::array<double, 2>& o, const std::array<double, 2>& a,
             const std::array<double, 2>& b) {
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

bool SegmentsIntersect(const std::array<double, 2>& p1, const std::array<double, 2>& p2,
                       const std::array<double, 2>& q1, const std::array<double, 2>& q2) {
  const double d1 = Cross(q1, q2, p1), d2 = Cross(q1, q2, p2);
  const double d3 = Cross(p1, p2, q1), d4 = Cross(p1, p2, q2);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0));
}

// Crossing-number point-in-polygon test (Shimrat 1962; the paper's method).
bool PointInPolygon(const std::array<double, 2>& p, const Corners& poly) {
  bool inside = false;
  for (int i = 0, j = 3; i < 4; j = i++) {
    const auto& a = poly[i];
    const auto& b = poly[j];
    if ((a[1] > p[1]) != (b[1] > p[1]) &&
        p[0] < (b[0] - a[0]) * (p[1] - a[1]) / (b[1] - a[1]) + a[0]) {
      inside = !inside;
    }
  }
  return inside;
}

bool AnyCornerInside(const Corners& a, const Corners& b) {
  for (const auto& p : a) {
    if (PointInPolygon(p, b)) return true;
  }
  return false;
}

// The independent method: polygons overlap iff an edge pair crosses or one holds the other.
bool OverlapByEdgesAndContainment(const OrientedBox<double>& a, const OrientedBox<double>& b) {
  const Corners ca = CornersOf(a), cb = CornersOf(b);
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      if (SegmentsIntersect(ca[i], ca[(i + 1) % 4], cb[j], cb[(j + 1) % 4])) return true;
    }
  }
  return PointInPolygon(ca[0], cb) || PointInPolygon(cb[0], ca);
}

TEST(OrientedBox, CrossingRectanglesWithNoCornerInsideOverlap) {
  // A plus sign: neither rectangle has a corner inside the other, yet they overlap. The paper's
  // vertex-in-polygon test misses this case; separating axes do not.
  const auto horizontal = MakeBox(0.0, 0.0, 0.0, 3.0, 0.5);
  const auto vertical = MakeBox(0.0, 0.0, kPi / 2, 3.0, 0.5);
  EXPECT_FALSE(AnyCornerInside(CornersOf(horizontal), CornersOf(vertical)));
  EXPECT_FALSE(AnyCornerInside(CornersOf(vertical), CornersOf(horizontal)));
  EXPECT_TRUE(BoxesOverlap(horizontal, vertical));
  EXPECT_TRUE(OverlapByEdgesAndContainment(horizontal, vertical));
}

TEST(OrientedBox, SimpleCases) {
  const auto a = MakeBox(0.0, 0.0, 0.0, 2.25, 0.9);
  EXPECT_TRUE(BoxesOverlap(a, MakeBox(4.0, 0.0, 0.0, 2.25, 0.9)));   // bumpers overlap
  EXPECT_FALSE(BoxesOverlap(a, MakeBox(4.6, 0.0, 0.0, 2.25, 0.9)));  // 10 cm gap
  EXPECT_FALSE(BoxesOverlap(a, MakeBox(0.0, 1.9, 0.0, 2.25, 0.9)));  // side by side
  EXPECT_TRUE(BoxesOverlap(a, MakeBox(0.0, 0.0, 1.0, 0.1, 0.1)));    // contained
  EXPECT_TRUE(BoxesOverlap(MakeBox(0.0, 0.0, 1.0, 0.1, 0.1), a));    // symmetric
  // Diagonal corner-to-corner gap that only a rotated axis separates.
  const auto r = MakeBox(0.0, 0.0, kPi / 4, 1.0, 1.0);
  EXPECT_FALSE(BoxesOverlap(r, MakeBox(2.0, 0.0, kPi / 4, 0.3, 0.3)));
}

TEST(OrientedBox, AgreesWithIndependentMethodOnSeededRandomPairs) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> pos(-4.0, 4.0), yaw(-kPi, kPi), half(0.1, 3.0);
  int overlapping = 0, crossing_without_corners = 0;
  const int kPairs = 20000;
  for (int k = 0; k < kPairs; ++k) {
    const auto a = MakeBox(pos(rng), pos(rng), yaw(rng), half(rng), half(rng));
    const auto b = MakeBox(pos(rng), pos(rng), yaw(rng), half(rng), half(rng));
    const bool expected = OverlapByEdgesAndContainment(a, b);
    ASSERT_EQ(BoxesOverlap(a, b), expected) << "pair " << k;
    overlapping += expected;
    if (expected && !AnyCornerInside(CornersOf(a), CornersOf(b)) &&
        !AnyCornerInside(CornersOf(b), CornersOf(a))) {
      ++crossing_without_corners;
    }
  }
  // The random family exercises both outcomes and the case the paper's test misses.
  EXPECT_GT(overlapping, kPairs / 5);
  EXPECT_LT(overlapping, kPairs * 4 / 5);
  EXPECT_GT(crossing_without_corners, 50);
}

TEST(OrientedBox, FloatAndDoubleAgreeAwayFromTouching) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> pos(-4.0, 4.0), yaw(-kPi, kPi), half(0.2, 3.0);
  for (int k = 0; k < 5000; ++k) {
    const double v[10] = {pos(rng), pos(rng), yaw(rng), half(rng), half(rng),
                          pos(rng), pos(rng), yaw(rng), half(rng), half(rng)};
    const auto a = MakeBox(v[0], v[1], v[2], v[3], v[4]);
    const auto b = MakeBox(v[5], v[6], v[7], v[8], v[9]);
    // Skip pairs within 1 mm of touching: grow/shrink b and see whether the answer changes.
    const auto grown = MakeBox(v[5], v[6], v[7], v[8] + 1e-3, v[9] + 1e-3);
    const auto shrunk = MakeBox(v[5], v[6], v[7], v[8] - 1e-3, v[9] - 1e-3);
    if (BoxesOverlap(a, grown) != BoxesOverlap(a, shrunk)) continue;
    const auto af = MakeBox<float>(v[0], v[1], v[2], v[3], v[4]);
    const auto bf = MakeBox<float>(v[5], v[6], v[7], v[8], v[9]);
    ASSERT_EQ(BoxesOverlap(af, bf), BoxesOverlap(a, b)) << "pair " << k;
  }
}

}  // namespace
}  // namespace criticality::core
