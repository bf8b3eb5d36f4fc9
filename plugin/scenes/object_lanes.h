#pragma once
// A vehicle's lanes from its own view: its lane corridor (its lane's centre line continued
// along its route, its width and its neighbours as the vehicle sees them) read from the road
// network and sampled into the estimator's LaneSet (lane_corridor.h).
//  - A neighbour is a lane of the same edge that the vehicle's class may use (a sidewalk never
//    is); beyond the highest-index lane, on its offside (left in right-hand traffic, right in a
//    left-hand network: plugin/network/traffic_side.h), the adjacent lane of the opposite
//    direction (plugin/network/counter_lanes.h), flagged as counter-traffic.
//  - Inside a junction the neighbours are those of the lane the internal lane leads to.
//  - When its route ends within the corridor, the distance its front still goes: SUMO removes a
//    vehicle whose front reaches the end of its route (its arrival position, by default the
//    last lane's end; an earlier arrivalPos in the route file is not read, so the vehicle is
//    taken to go on to the end).
#include <optional>
#include <string>
#include <vector>

#include "criticality/scene.h"
#include "plugin/network/counter_lanes.h"
#include "plugin/network/road_network.h"
#include "plugin/scenes/lane_heading.h"
#include "plugin/scenes/scene_config.h"

namespace criticality::plugin {

/** Where a vehicle is, as SUMO reports it, and how it is placed in the estimator's frame. */
struct VehicleOnLane {
  Pose2 centre;  ///< centre of gravity, math yaw
  Point2 front;  ///< the middle of its front bumper (SUMO's position)
  double speed_mps{0.0};
  double length_m{4.5};
  std::string lane;
  double lane_position_m{0.0};  ///< of its front bumper
  int lane_index{0};
  std::vector<std::string> route;
  int route_index{0};
  std::string vehicle_class;
  /** --observable-only: its way on is what can be seen (NextLaneSeen: its blinker, else
   *  straight on), never its route, and where its route ends is not known. */
  bool observable_only{false};
  Blinker blinker{Blinker::kNone};
  /** Its way through a junction follows the junction's internal lanes (SceneConfig::
   *  junction_shapes, the default); false: the chord from the lane's end to the next lane's start. */
  bool junction_shapes{true};
  /** SUMO's length of it, front to back along its lanes (its way's body; length_m is its box). */
  double way_length_m{4.5};
};

/** SceneConfig::lane_change_target: the lane of the same edge a vehicle is seen moving into
 *  (SUMO moves it there over time: lanechange.duration > 0 or the sublane model), or "" when
 *  it is not changing lanes. Changing lanes: its blinker points to that lane, which its class
 *  may use, and its front is at least kLaneChangeMinOffsetM off its lane's centre line that
 *  way, its heading turned that way from the lane's direction at its centre by at least
 *  kLaneChangeMinAngleRad. Past the middle of the change SUMO puts it on the new lane, where
 *  its front is off that lane's centre the other way: then "". Reads the blinker, the body's
 *  pose and the lane geometry, which sensors and a map give. In a left-hand network
 *  (`left_hand`, LeftHandTraffic) the lane to the left has the next lower index. */
std::string LaneChangeTarget(const VehicleOnLane& v, RoadNetwork* network, bool left_hand = false);

/** See LaneChangeTarget. Project choices (SUMO drives a vehicle exactly on its lane's centre
 *  line unless it is changing lanes; its continuous lane change turns the body by
 *  atan(offset / half its length): a 12 m bus is 0.16 m and 1.5 degrees out after 0.1 s). */
inline constexpr double kLaneChangeMinOffsetM = 0.1;
inline constexpr double kLaneChangeMinAngleRad = 0.0175;  // 1 degree

/** The lane the vehicle drives onto after `lane`: along its route (NextLaneOnRoute, advancing
 *  *route_index), or with observable_only as it is seen to go (NextLaneSeen). */
std::string NextLaneOf(const VehicleOnLane& v, const std::string& lane, RoadNetwork* network,
                       int* route_index);

/** See ObjectLanes::smooth_lane_yaw_rate_radps: netconvert's internal lanes turn 20-30 degrees
 *  at each corner, a few metres apart in a junction turn. */
inline constexpr double kCornerWindowM = 3.0;

struct ObjectLanes {
  LaneSet lanes;
  std::optional<double> route_end_m;  ///< ObjectState::route_end_m
  /** The yaw rate of following the corridor at its speed (LaneYawRate over half the distance
   *  of one step, at least 1 m each way). */
  double lane_yaw_rate_radps{0.0};
  /** The same over at least kCornerWindowM each way: SUMO's lane shapes in a junction are a
   *  few straight pieces, and a vehicle's heading jumps at their corners; this yaw rate
   *  averages over the corners around it. */
  double smooth_lane_yaw_rate_radps{0.0};
  /** With SceneConfig::lane_heading_yaw_rate at steps up to kLongStepS: SUMO's heading along
   *  the lanes (HeadingAlong, over kLaneHeadingWindowS of its speed each way of its front, at
   *  least 1 m); nullopt otherwise or where the way behind is not known. */
  std::optional<LaneHeading> lane_heading;
  /** With SceneConfig::lane_change_yaw_rate and continuous lane changes, where the vehicle's
   *  back is still on the lanes behind its normal lane: that lane's
   *  direction (math yaw) from its start to the front (at the middle between them); nullopt
   *  otherwise. SUMO measures a vehicle's heading from its back on the lanes behind, except
   *  while it moves the vehicle sideways (continuous lane changes): from the lane's start then
   *  (MSVehicle::getBackPosition), this direction turned by the sideways motion
   *  (ObjectReader::LaneYawRateOr). */
  std::optional<double> lane_start_yaw_rad;
  /** With SceneConfig::junction_ways, for a body in a junction (BodyInJunction): its way
   *  (WayOf, through its corridor); nullopt otherwise. */
  std::optional<Way> way;
};

/** See ObjectLanes::lane_heading: the heading's change over the half second around now (a
 *  window only ahead, the turn the front is entering, was tried: bench/RESULTS.md). */
inline constexpr double kLaneHeadingWindowS = 0.25;

/** Extends the corridor's centre line (starting with the vehicle's lane) along its way
 *  (NextLaneOf; with junction_shapes through a junction along its internal lanes), as far as
 *  it can get within `reach` of the corridor's position (at most 8 lanes on, and at least out
 *  of the junction it is in). Sets *beyond_junction to the first normal lane after an internal
 *  one, and *route_end to how far its front still goes when the route ends within the corridor
 *  (never with observable_only). */
void FollowRoute(const VehicleOnLane& v, double reach, RoadNetwork* network, LaneCorridor* c,
                 std::string* beyond_junction, std::optional<double>* route_end);

/** The vehicle's lanes, route end and lane yaw rate; `step_s` is the simulation's step. With
 *  SceneConfig::lane_change_target, a vehicle changing lanes (LaneChangeTarget) is taken as on
 *  the lane it moves into: its corridor and neighbours are that lane's. */
ObjectLanes LanesOf(const VehicleOnLane& v, const SceneConfig& config, double step_s,
                    RoadNetwork* network, CounterLanes* counter_lanes);

}  // namespace criticality::plugin
