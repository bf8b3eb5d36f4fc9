// Longitudinal hypotheses (paper Sec. IV-B-2a).
#include "core/profiles.h"

#include <gtest/gtest.h>

namespace criticality::core {
namespace {

TEST(Profiles, SixVehicleProfilesAreMaxMinZeroAndNegativeSpread) {
  const double expected[6] = {-9.7, -7.275, -4.85, -2.425, 0.0, 9.7};
  for (int k = 0; k < 6; ++k)
    EXPECT_NEAR(VehicleProfileTarget(k, 6, -9.7, 9.7), expected[k], 1e-12);
}

TEST(Profiles, FiveAndThreeProfiles) {
  const double five[5] = {-9.7, -9.7 * 2 / 3, -9.7 / 3, 0.0, 9.7};
  for (int k = 0; k < 5; ++k) EXPECT_NEAR(VehicleProfileTarget(k, 5, -9.7, 9.7), five[k], 1e-12);
  EXPECT_EQ(VehicleProfileTarget(0, 3, -0.1, 0.1), -0.1);
  EXPECT_EQ(VehicleProfileTarget(1, 3, -0.1, 0.1), 0.0);
  EXPECT_EQ(VehicleProfileTarget(2, 3, -0.1, 0.1), 0.1);
}

TEST(Profiles, PedestrianAccelerationsAreEquallySpaced) {
  EXPECT_EQ(EquallySpaced(0, 6, -12.0, 12.0), -12.0);
  EXPECT_NEAR(EquallySpaced(1, 6, -12.0, 12.0), -7.2, 1e-12);
  EXPECT_EQ(EquallySpaced(5, 6, -12.0, 12.0), 12.0);
}

TEST(Profiles, LatencyThenJerkLimitedRamp) {
  // Start at -1, target -9.7, 0.2 s latency, 30 m/s^3.
  EXPECT_EQ(RampedValue(0.0, -1.0, -9.7, 0.2, 30.0), -1.0);
  EXPECT_EQ(RampedValue(0.2, -1.0, -9.7, 0.2, 30.0), -1.0);
  EXPECT_NEAR(RampedValue(0.3, -1.0, -9.7, 0.2, 30.0), -4.0, 1e-12);
  EXPECT_EQ(RampedValue(1.0, -1.0, -9.7, 0.2, 30.0), -9.7);
  // Never overshoots, in both directions.
  for (double t = 0.0; t < 2.0; t += 0.01) {
    const double up = RampedValue(t, -1.0, 9.7, 0.2, 30.0);
    EXPECT_LE(up, 9.7);
    EXPECT_GE(up, -1.0);
  }
}

}  // namespace
}  // namespace criticality::core
