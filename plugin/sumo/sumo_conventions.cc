#include "plugin/sumo/sumo_conventions.h"

#include <cmath>

namespace criticality::plugin {

double NavigationDegToYaw(double angle_deg) {
  return WrapAngle((90.0 - angle_deg) * kPi / 180.0);
}

double YawToNavigationDeg(double yaw) {
  double deg = 90.0 - yaw * 180.0 / kPi;
  deg = std::fmod(deg, 360.0);
  return deg < 0.0 ? deg + 360.0 : deg;
}

Pose2 FrontBumperToCentre(double front_x, double front_y, double angle_deg, double length) {
  const double yaw = NavigationDegToYaw(angle_deg);
  return Pose2{front_x - 0.5 * length * std::cos(yaw), front_y - 0.5 * length * std::sin(yaw), yaw};
}

double BodyLengthOf(const SumoObject& o) {
  return o.body_length_m > 0.0 ? o.body_length_m : o.length_m;
}

Pose2 CentreOf(const SumoObject& o) {
  if (o.person) return Pose2{o.x_m, o.y_m, NavigationDegToYaw(o.angle_deg)};
  return FrontBumperToCentre(o.x_m, o.y_m, o.angle_deg, BodyLengthOf(o));
}

}  // namespace criticality::plugin
