// SUMO's front bumper + navigation angle -> centre of gravity + math yaw.
#include "plugin/sumo/sumo_conventions.h"

#include <gtest/gtest.h>

#include <cmath>

namespace criticality::plugin {
namespace {

TEST(SumoConventions, CardinalDirections) {
  // East (navigation 90 deg): yaw 0, centre behind the front along -x.
  Pose2 c = FrontBumperToCentre(100.0, 50.0, 90.0, 5.0);
  EXPECT_NEAR(c.x, 97.5, 1e-12);
  EXPECT_NEAR(c.y, 50.0, 1e-12);
  EXPECT_NEAR(c.yaw, 0.0, 1e-12);
  // North (0 deg): yaw pi/2, centre below the front.
  c = FrontBumperToCentre(100.0, 50.0, 0.0, 5.0);
  EXPECT_NEAR(c.x, 100.0, 1e-12);
  EXPECT_NEAR(c.y, 47.5, 1e-12);
  EXPECT_NEAR(c.yaw, kPi / 2, 1e-12);
  // South (180) and west (270).
  EXPECT_NEAR(NavigationDegToYaw(180.0), -kPi / 2, 1e-12);
  EXPECT_NEAR(std::fabs(NavigationDegToYaw(270.0)), kPi, 1e-12);
  c = FrontBumperToCentre(0.0, 0.0, 270.0, 4.0);
  EXPECT_NEAR(c.x, 2.0, 1e-12);
}

TEST(SumoConventions, RoundTripsOverTheCircle) {
  for (double deg = 0.0; deg < 360.0; deg += 7.5) {
    EXPECT_NEAR(YawToNavigationDeg(NavigationDegToYaw(deg)), deg, 1e-9) << deg;
    // The centre is always `length / 2` behind the front along the heading.
    const Pose2 c = FrontBumperToCentre(10.0, -3.0, deg, 4.6);
    EXPECT_NEAR(std::hypot(c.x - 10.0, c.y + 3.0), 2.3, 1e-12);
    EXPECT_NEAR(10.0 - c.x, 2.3 * std::cos(c.yaw), 1e-12);
  }
}

}  // namespace
}  // namespace criticality::plugin
