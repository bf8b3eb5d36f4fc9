#include "plugin/pose_conversion.h"

#include <cmath>

namespace criticality::plugin {

double NavigationDegToYaw(double angle_deg) {
  return core::WrapAngle((90.0 - angle_deg) * core::kPi / 180.0);
}

double YawToNavigationDeg(double yaw) {
  double deg = 90.0 - yaw * 180.0 / core::kPi;
  deg = std::fmod(deg, 360.0);
  return deg < 0.0 ? deg + 360.0 : deg;
}

core::Pose2 FrontBumperToCentre(double front_x, double front_y, double angle_deg, double length) {
  const double yaw = NavigationDegToYaw(angle_deg);
  return core::Pose2{front_x - 0.5 * length * std::cos(yaw), front_y - 0.5 * length * std::sin(yaw),
                     yaw};
}

}  // namespace criticality::plugin
