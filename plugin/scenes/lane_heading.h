#pragma once
// SUMO's heading of a vehicle that follows its lanes, and how fast it turns. SUMO points a
// vehicle from its back to its front, both on the centre lines of the lanes its body stands on
// (MSVehicle::computeAngle: getBackPosition to getPosition). Along a lane shape made of
// straight pieces (a junction's internal lane turns 20-30 degrees at each corner) that heading
// stays put while both ends are on one piece and turns while an end rounds a corner, so the
// heading change of one short step is 0 or a spike. The lanes give the turn it is in instead:
// the change of that chord's direction over a window around the front, at the vehicle's speed.
// Lane geometry and the body's length, which a map and a sensor give.
#include <optional>
#include <string>
#include <vector>

#include "criticality/scene.h"
#include "plugin/network/road_network.h"
#include "plugin/network/way_behind.h"

namespace criticality::plugin {

struct LaneHeading {
  double yaw_rad{0.0};         ///< the chord from the back to the front now (math yaw)
  double yaw_rate_radps{0.0};  ///< its change along the lanes around the front, at the speed
};

/** The heading of a body `length_m` long whose front is `way`'s front (`way` a centre line
 *  through the lanes behind it and ahead of it: ChordYaw), and its rate of change at
 *  `speed_mps` from up to `behind_m` behind the front to up to `ahead_m` ahead of it (less
 *  where the line ends, at least 0.5 m in all). nullopt where the line does not reach the back
 *  or is too short. */
std::optional<LaneHeading> HeadingAlong(const WayLine& way, double length_m, double speed_mps,
                                        double behind_m, double ahead_m);

/** The way a vehicle's body and its way ahead lie along: the lanes behind its front
 *  (LineBehind, `behind_m` of them) joined with `ahead`, a centre line that starts with the
 *  shape of `lane` (a LaneCorridor's). */
WayLine LineThrough(RoadNetwork& network, const std::string& lane, double lane_position_m,
                    double behind_m, const std::vector<std::string>& route, int route_index,
                    const std::vector<Point2>& ahead);

}  // namespace criticality::plugin
