#pragma once
// SUMO reports a vehicle's FRONT BUMPER centre and a NAVIGATION angle (degrees, 0 = north,
// clockwise). The estimator wants the centre of gravity (we use the rectangle's centre) and the
// math yaw (radians, counter-clockwise from +x). This is the one place that converts.
#include "criticality/geometry.h"
#include "plugin/sumo/sumo_reports.h"

namespace criticality::plugin {

/** Navigation degrees (0 = north, clockwise) -> math yaw in [-pi, pi). */
double NavigationDegToYaw(double angle_deg);

/** Math yaw -> navigation degrees in [0, 360). */
double YawToNavigationDeg(double yaw);

/** Front-bumper position + navigation angle + length -> centre pose with math yaw. */
Pose2 FrontBumperToCentre(double front_x, double front_y, double angle_deg, double length);

/** The length of a vehicle's box: its body's chord where measured (SumoObject::body_length_m),
 *  else its length. */
double BodyLengthOf(const SumoObject& o);

/** An object's centre pose: a vehicle's the centre of its box (BodyLengthOf behind its front
 *  bumper), a person's position as it is. */
Pose2 CentreOf(const SumoObject& o);

}  // namespace criticality::plugin
