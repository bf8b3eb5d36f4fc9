// The paper's chronological approximation of conditional probabilities (Sec. IV-D-2).
#include "core/chronological_risk.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace criticality::core {
namespace {

TEST(ChronologicalRisk, HandComputedTwoObjectExample) {
  // Object A: trajectories 0, 1 with p = 0.3, 0.7. Object B: trajectories 2, 3 with p = 0.4,
  // 0.6. Along this ego trajectory B's trajectory 3 collides first (step 3), then A's
  // trajectory 0 (step 5); A's 1 and B's 2 never collide.
  const double p[4] = {0.3, 0.7, 0.4, 0.6};
  const int object_of[4] = {0, 0, 1, 1};
  const int events[2] = {3, 0};
  double mass[2] = {0.0, 0.0}, contribution[2];
  const double total =
      ChronologicalCollisionProbability(2, events, p, object_of, 2, mass, contribution);
  // First collision keeps its probability: P(B) = 0.6.
  EXPECT_DOUBLE_EQ(contribution[0], 0.6);
  // The next is scaled by the no-collision probability before it: P(A and not B) ~ P(not B) P(A)
  // = 0.4 * 0.3 = 0.12.
  EXPECT_DOUBLE_EQ(contribution[1], 0.4 * 0.3);
  EXPECT_DOUBLE_EQ(total, 0.72);
  // ... which is 1 - P(no A) P(no B) = 1 - 0.7 * 0.4.
  EXPECT_DOUBLE_EQ(total, 1.0 - 0.7 * 0.4);
}

TEST(ChronologicalRisk, ThreeObjectsFollowThePaperProducts) {
  // A then B then C, one trajectory each with p = a, b, c:
  // P(A), P(not A) P(B), P(not A) P(not B) P(C).
  const double p[3] = {0.5, 0.2, 0.9};
  const int object_of[3] = {0, 1, 2};
  const int events[3] = {0, 1, 2};
  double mass[3] = {0, 0, 0}, c[3];
  ChronologicalCollisionProbability(3, events, p, object_of, 3, mass, c);
  EXPECT_DOUBLE_EQ(c[0], 0.5);
  EXPECT_DOUBLE_EQ(c[1], 0.5 * 0.2);
  EXPECT_DOUBLE_EQ(c[2], 0.5 * 0.8 * 0.9);
}

TEST(ChronologicalRisk, TrajectoriesOfOneObjectAreExclusiveNotScaled) {
  const double p[3] = {0.2, 0.3, 0.5};
  const int object_of[3] = {0, 0, 0};
  const int events[3] = {2, 0, 1};
  double mass[1] = {0.0}, c[3];
  const double total = ChronologicalCollisionProbability(3, events, p, object_of, 1, mass, c);
  EXPECT_DOUBLE_EQ(total, 1.0);  // every hypothesis collides
  EXPECT_DOUBLE_EQ(c[0], 0.5);
  EXPECT_DOUBLE_EQ(c[1], 0.2);
}

TEST(ChronologicalRisk, TotalIsOneMinusProductOfMissesOnRandomInstances) {
  std::mt19937_64 rng(99);
  for (int trial = 0; trial < 500; ++trial) {
    const int n_obj = 1 + static_cast<int>(rng() % 5);
    std::vector<int> object_of;
    std::vector<double> p;
    for (int o = 0; o < n_obj; ++o) {
      const int n = 1 + static_cast<int>(rng() % 6);
      double sum = 0.0;
      const size_t first = p.size();
      for (int k = 0; k < n; ++k) {
        p.push_back(1.0 + static_cast<double>(rng() % 100));
        object_of.push_back(o);
        sum += p.back();
      }
      for (size_t k = first; k < p.size(); ++k) p[k] /= sum;
    }
    std::vector<int> events;
    std::vector<double> q(n_obj, 0.0);
    for (int j = 0; j < static_cast<int>(p.size()); ++j) {
      if (rng() % 2) {
        events.push_back(j);
        q[object_of[j]] += p[j];
      }
    }
    std::shuffle(events.begin(), events.end(), rng);  // any chronological order
    std::vector<double> mass(n_obj, 0.0), c(events.size());
    const double total =
        ChronologicalCollisionProbability(static_cast<int>(events.size()), events.data(), p.data(),
                                          object_of.data(), n_obj, mass.data(), c.data());
    double miss = 1.0;
    for (double qo : q) miss *= 1.0 - qo;
    EXPECT_NEAR(total, 1.0 - miss, 1e-12);
    EXPECT_LE(total, 1.0 + 1e-12);
  }
}

TEST(ChronologicalRisk, NoEventsNoRisk) {
  double mass[1] = {0.0};
  EXPECT_EQ(ChronologicalCollisionProbability(0, nullptr, nullptr, nullptr, 1, mass, nullptr), 0.0);
}

}  // namespace
}  // namespace criticality::core
