// Rates per exposure with their 95 % intervals (tools/campaign/rates.h), against values worked
// out by hand and published quantiles.
#include "tools/campaign/rates.h"

#include <gtest/gtest.h>

#include <cmath>

namespace criticality::campaign {
namespace {

TEST(Quantiles, MatchPublishedTables) {
  EXPECT_NEAR(StudentT975(1), 12.706, 1e-3);
  EXPECT_NEAR(StudentT975(2), 4.303, 1e-3);
  EXPECT_NEAR(StudentT975(10), 2.228, 1e-3);
  EXPECT_NEAR(StudentT975(11), 2.201, 3e-3);  // between the table's points
  EXPECT_NEAR(StudentT975(1000), 1.962, 2e-3);
  EXPECT_NEAR(ChiSquareQuantile(0.975, 2), 7.3778, 1e-3);
  EXPECT_NEAR(ChiSquareQuantile(0.025, 2), 0.050636, 1e-5);
  EXPECT_NEAR(ChiSquareQuantile(0.025, 8), 2.1797, 1e-3);
  EXPECT_NEAR(ChiSquareQuantile(0.975, 10), 20.483, 1e-2);
  EXPECT_NEAR(ChiSquareQuantile(0.5, 100), 99.334, 1e-2);
}

TEST(RateOf, PooledRateWithItsSpreadAcrossRuns) {
  // Events 2, 4, 6 over exposures 1, 1, 2: rate 12 / 4 = 3; residuals -1, 1, 0; SE^2 =
  // 3/2 * 2 / 16; half width t(2) * sqrt(3) / 4.
  const Rate r = RateOf({{2, 1}, {4, 1}, {6, 2}});
  ASSERT_TRUE(r.value && r.low && r.high);
  EXPECT_EQ(r.runs, 3u);
  EXPECT_DOUBLE_EQ(*r.value, 3.0);
  const double half = 4.303 * std::sqrt(3.0) / 4.0;
  EXPECT_NEAR(*r.low, 3.0 - half, 1e-3);
  EXPECT_NEAR(*r.high, 3.0 + half, 1e-3);
  EXPECT_EQ(r.interval, "runs");
}

TEST(RateOf, IdenticalRunsHaveNoSpread) {
  const Rate r = RateOf({{1, 0.5}, {1, 0.5}});
  EXPECT_DOUBLE_EQ(*r.value, 2.0);
  EXPECT_DOUBLE_EQ(*r.low, 2.0);
  EXPECT_DOUBLE_EQ(*r.high, 2.0);
}

TEST(RateOf, NoEventsGiveThePoissonUpperBound) {
  const Rate r = RateOf({{0, 1}, {0, 2}, {0, 1}});
  EXPECT_DOUBLE_EQ(*r.value, 0.0);
  EXPECT_DOUBLE_EQ(*r.low, 0.0);
  EXPECT_NEAR(*r.high, 3.6889 / 4.0, 1e-3);  // 3.69 events over 4 units of exposure
  EXPECT_EQ(r.interval, "poisson");
}

TEST(RateOf, OneRunGivesTheExactPoissonInterval) {
  const Rate r = RateOf({{4, 2}});
  EXPECT_DOUBLE_EQ(*r.value, 2.0);
  EXPECT_NEAR(*r.low, 2.1797 / 2 / 2, 1e-3);   // chi2(0.025, 8) / 2 / exposure
  EXPECT_NEAR(*r.high, 20.483 / 2 / 2, 1e-2);  // chi2(0.975, 10) / 2 / exposure
  EXPECT_EQ(r.interval, "poisson");
}

TEST(RateOf, NoExposureGivesNoRate) {
  const Rate r = RateOf({{3, 0}});
  EXPECT_FALSE(r.value.has_value());
  EXPECT_EQ(r.events, 3.0);
  EXPECT_FALSE(RateOf({}).value.has_value());
}

}  // namespace
}  // namespace criticality::campaign
