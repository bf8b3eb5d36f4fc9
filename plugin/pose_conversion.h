#pragma once
// SUMO reports a vehicle's FRONT BUMPER centre and a NAVIGATION angle (degrees, 0 = north,
// clockwise). The estimator wants the centre of gravity (we use the rectangle's centre) and the
// math yaw (radians, counter-clockwise from +x). This is the one place that converts.
#include "core/geometry.h"

namespace criticality::plugin {

/** Navigation degrees (0 = north, clockwise) -> math yaw in [-pi, pi). */
double NavigationDegToYaw(double angle_deg);

/** Math yaw -> navigation degrees in [0, 360). */
double YawToNavigationDeg(double yaw);

/** Front-bumper position + navigation angle + length -> centre pose with math yaw. */
core::Pose2 FrontBumperToCentre(double front_x, double front_y, double angle_deg, double length);

}  // namespace criticality::plugin
