// The SIMD box test of a block (cpu/block_contact.h) against core::BoxesOverlap, step by step.
#include "cpu/block_contact.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/oriented_box.h"

namespace criticality {
namespace {

struct Track {
  std::vector<double> x, y, c, s;
  double hl, hw;
  internal::BoxTrack View() const { return {x.data(), y.data(), c.data(), s.data(), hl, hw}; }
  core::OrientedBox<double> Box(int n) const { return {x[n], y[n], c[n], s[n], hl, hw}; }
};

// n poses around the origin, close enough for about half of the pairs to touch.
Track RandomTrack(std::mt19937* rng, int n, double hl, double hw) {
  std::uniform_real_distribution<double> pos(-6.0, 6.0), yaw(-3.2, 3.2);
  Track t{{}, {}, {}, {}, hl, hw};
  for (int k = 0; k < n; ++k) {
    const double a = yaw(*rng);
    t.x.push_back(pos(*rng));
    t.y.push_back(pos(*rng));
    t.c.push_back(std::cos(a));
    t.s.push_back(std::sin(a));
  }
  return t;
}

// The squared sum of the bounding radii (as RecognizeCollisions gives it).
double Reach2(const Track& a, const Track& b) {
  const double r = core::BoundingRadius(a.hl, a.hw) + core::BoundingRadius(b.hl, b.hw) + 1e-9;
  return r * r;
}

// The first step the scalar test finds in [n0, n1), or -1.
int ScalarFirst(const Track& a, const Track& b, int n0, int n1) {
  for (int n = n0; n < n1; ++n)
    if (core::BoxesOverlap(a.Box(n), b.Box(n))) return n;
  return -1;
}

TEST(BlockContact, FindsTheSameFirstStepAsTheScalarTest) {
  std::mt19937 rng(7);
  const internal::FirstOverlapFn first = internal::FirstOverlapInBlock();
  int hits = 0, misses = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const int steps = 40;
    const Track a = RandomTrack(&rng, steps, 2.3, 0.9), b = RandomTrack(&rng, steps, 0.3, 0.3);
    for (int len : {1, 5, 9, 16}) {
      for (int n0 = 0; n0 + len <= steps; n0 += 7) {
        // readable: the whole track, or exactly up to the block's end (the last block of the
        // last trajectory: nothing may be read past it).
        for (long readable : {long{steps}, long{n0 + len}}) {
          const int want = ScalarFirst(a, b, n0, n0 + len);
          EXPECT_EQ(first(a.View(), b.View(), n0, n0 + len, Reach2(a, b), readable), want)
              << trial << " " << n0 << " " << len;
          (want >= 0 ? hits : misses)++;
        }
      }
    }
  }
  // Both outcomes were exercised, often.
  EXPECT_GT(hits, 1000);
  EXPECT_GT(misses, 1000);
}

// Boxes that only touch along an edge overlap for the scalar test: so for the lanes.
TEST(BlockContact, BoxesThatTouchExactlyOverlap) {
  const internal::FirstOverlapFn first = internal::FirstOverlapInBlock();
  Track a{{0, 0, 0}, {0, 0, 0}, {1, 1, 1}, {0, 0, 0}, 2.0, 1.0};
  Track b{{10, 4.0, 4.0}, {0, 0, 0}, {1, 1, 1}, {0, 0, 0}, 2.0, 1.0};  // step 1: edge to edge
  ASSERT_TRUE(core::BoxesOverlap(a.Box(1), b.Box(1)));
  ASSERT_FALSE(core::BoxesOverlap(a.Box(0), b.Box(0)));
  EXPECT_EQ(first(a.View(), b.View(), 0, 3, Reach2(a, b), 3), 1);
  b.x[1] = std::nextafter(4.0, 5.0);  // apart by one ulp at step 1: step 2 first
  EXPECT_EQ(first(a.View(), b.View(), 0, 3, Reach2(a, b), 3), 2);
  EXPECT_EQ(first(a.View(), b.View(), 0, 2, Reach2(a, b), 3), -1);  // step 2 is past the block
}

}  // namespace
}  // namespace criticality
