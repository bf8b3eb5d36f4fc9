#pragma once
// The way a vehicle came by: from the lane its front is on back along its route, through every
// internal lane of the junctions it crossed (both parts of a turn that an internal junction
// splits), as SUMO keeps the lanes a vehicle's body still stands on (MSVehicle's further lanes).
// Where the back of a body is (SUMO's getBackPosition) follows from it.
#include <optional>
#include <string>
#include <vector>

#include "plugin/network/road_network.h"

namespace criticality::plugin {

/** The lanes behind a front on `lane`, nearest first (`lane` itself not included), until their
 *  lengths add up to `metres` or the way behind is not known: the route starts there, or no
 *  link of the previous route edge leads to the lane. `route_index` is SUMO's (the route edge
 *  the vehicle is on; on a junction the edge before it). */
std::vector<std::string> LanesBehind(RoadNetwork& network, const std::string& lane,
                                     const std::vector<std::string>& route, int route_index,
                                     double metres);

/** The point on the lanes' centre lines `distance_m` behind lane position `lane_position_m` of
 *  `lane` (SUMO's lane positions, scaled onto each shape as SUMO does): on the lane itself or on
 *  the lanes behind it (LanesBehind). nullopt when the way behind ends first. */
std::optional<Point2> PointBehind(RoadNetwork& network, const std::string& lane,
                                  double lane_position_m, double distance_m,
                                  const std::vector<std::string>& route, int route_index);

/** The centre line a vehicle's body lies along, from `metres` behind its front (or as far back
 *  as the way is known) over its own lane's shape: the lanes behind it (LanesBehind), each moved
 *  sideways onto the next where they do not meet (the vehicle changed lanes since it left the
 *  junction; SUMO leaves its back on the old lane, the body is taken to have turned into its
 *  lane). */
struct WayLine {
  std::vector<Point2> line;
  double front_m{0.0};  ///< arc length of the front along `line`
  /** The largest sideways move of a lane behind onto the next: millimetres where netconvert's
   *  joints meet, a lane's spacing where the vehicle changed lanes since those lanes. */
  double shifted_m{0.0};
};
WayLine LineBehind(RoadNetwork& network, const std::string& lane, double lane_position_m,
                   double metres, const std::vector<std::string>& route, int route_index);

/** The point `metres` behind the front along `way` (ahead where negative, extrapolated past
 *  its end); nullopt beyond its known start. */
std::optional<Point2> PointOnWay(const WayLine& way, double metres);

/** SUMO's heading of a body `length_m` long along `way` (MSVehicle::computeAngle: from its back
 *  to its front, both on the way), its front `ahead_m` ahead of the way's front (behind where
 *  negative); nullopt where the way is not known that far back (or the two points meet). */
std::optional<double> ChordYaw(const WayLine& way, double length_m, double ahead_m = 0.0);

}  // namespace criticality::plugin
