#pragma once
// Positions along a polyline (a lane's centre line): its length, and the point and direction
// at an arc length. Network coordinates; no SUMO types.
#include <vector>

#include "criticality/scene.h"

namespace criticality::plugin {

/** Polyline length. */
double PolylineLength(const std::vector<Point2>& line);

/** The point at arc length s (extrapolated along the end segments beyond the ends) and the
 *  direction of travel there (math yaw). */
Point2 PointAlong(const std::vector<Point2>& line, double s, double* heading);

}  // namespace criticality::plugin
