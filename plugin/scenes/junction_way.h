#pragma once
// The way a vehicle's body moves along in a junction (the estimator's Vehicle::way): SUMO keeps
// the middle of a vehicle's front and back on the centre lines of its lanes, through a junction
// along its internal lanes, which turn tighter than a car steers (a right turn of 1.6 m radius)
// and than the paper's parabola lanes can carry. Sent for a vehicle whose front or back is on
// an internal lane (SceneConfig::junction_ways); the estimator then moves its box as SUMO does
// (Params::bodies_on_way). Reads which internal lane the vehicle is on and its way out of the
// junction (the lane it leads to, then its corridor): a map gives that from its place and
// blinker, SUMO from its route.
#include <optional>
#include <string>
#include <vector>

#include "criticality/geometry.h"
#include "criticality/scene.h"
#include "plugin/network/road_network.h"

namespace criticality::plugin {

/** Whether a body `length_m` long whose front is at `lane_position_m` on `lane` stands in a
 *  junction: its front on an internal lane, or its back still on one behind it (LanesBehind). */
bool BodyInJunction(RoadNetwork& network, const std::string& lane, double lane_position_m,
                    double length_m, const std::vector<std::string>& route, int route_index);

/** The way, in the frame X_WV, of a body `length_m` long (SUMO's length, front to back along
 *  its lanes) whose front is at `lane_position_m` on `lane`: the lanes behind it back to just
 *  behind its back, then `ahead` (a corridor's centre line, starting with `lane`'s shape) as far
 *  as it goes; at most kMaxWayPoints points (resampled evenly where the lanes have more),
 *  at least kMinWayPointSpacingM apart. nullopt where the way behind does not reach its back. */
std::optional<Way> WayOf(RoadNetwork& network, const std::string& lane, double lane_position_m,
                         double length_m, const std::vector<std::string>& route, int route_index,
                         const std::vector<Point2>& ahead, const Pose2& X_WV);

inline constexpr double kMinWayPointSpacingM = 0.02;
/** The way starts this far behind the back (the back's piece of the way is then known). */
inline constexpr double kWayBehindBackM = 1.0;

}  // namespace criticality::plugin
