#pragma once
// Where a walking person is in SUMO's pedestrian network, and whether its walk goes on along
// the footway (Pedestrian::stays_on_footway). SUMO's netconvert names a junction's crossings
// ":JUNCTION_cN" and its walking areas ":JUNCTION_wN"; a sidewalk is a lane of a normal edge
// that only pedestrians may use.
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "plugin/network/road_network.h"

namespace criticality::plugin {

enum class WalkingPlace {
  kRoad,         ///< a lane that vehicles may use too (a network without sidewalks), or none
  kSidewalk,     ///< a pedestrian-only lane of a normal edge
  kWalkingArea,  ///< a junction's walking area (its corners)
  kCrossing      ///< a junction's crossing
};

/** The place of a lane from its edge ID and whether only pedestrians may use it. */
WalkingPlace WalkingPlaceOf(const std::string& edge, bool pedestrians_only);

/** Whether a person at `here`, whose next edge is at `next`, keeps to the footway: it is on a
 *  sidewalk or walking area and its next edge is no crossing and no road (a walk that ends
 *  here has a sidewalk as next). */
bool StaysOnFootway(WalkingPlace here, WalkingPlace next);

/** Whether a link state is a traffic light's (green, green without priority, yellow, red,
 *  red-yellow, off): the states SUMO's netconvert gives only to links a light controls. */
bool SignalState(const std::string& state);

/** Whether a person must wait now at `entry`, the link it obeys to enter a crossing
 *  (CrossingEntries): it shows red, red-yellow or yellow, or gives the crossing no priority
 *  (stop 's', all-way stop 'w', minor 'm', equal '=', green without priority 'g') while SUMO
 *  has a foe vehicle approaching it (`has_foe`). SUMO's persons keep these obligations: such a
 *  person stays on the footway until it may cross. */
bool MustWaitAt(const LaneLink& entry);

/** The links persons obey to enter crossings, found as SUMO's pedestrian model finds them
 *  (MSPModel_Striping::getNextLane). netconvert links a crossing one way only: from the
 *  walking area at one end into it, and from it into the walking area at the other. A person
 *  walking it that way obeys the first; one walking it the other way obeys the crossing's link
 *  into its own walking area where a traffic light controls that link (the light's second
 *  index for the crossing), else the link into the crossing from the walking area at its other
 *  end. Remembers each junction's walking areas (read once from the network's edges). */
class CrossingEntries {
 public:
  explicit CrossingEntries(RoadNetwork* network) : network_(network) {}
  /** The link a person on walking-area lane `walking_lane` obeys to enter the crossing
   *  `crossing_edge` (its one lane), with this step's state and has_foe (LinksNow); nullopt
   *  when the network has none. */
  std::optional<LaneLink> EntryLink(const std::string& walking_lane,
                                    const std::string& crossing_edge);

 private:
  /** The walking areas' lanes of the junction of the crossing `crossing_edge`. */
  const std::vector<std::string>& WalkingAreasBeside(const std::string& crossing_edge);

  RoadNetwork* network_;
  bool scanned_{false};
  /** junction prefix (":J") -> lane 0 of each of its walking areas. */
  std::unordered_map<std::string, std::vector<std::string>> walking_areas_;
};

/** Where a person waiting for `crossing` stops: the distance (m) from (x, y) to the nearer end
 *  of the crossing lane's centre line, where SUMO's walk onto it begins. Infinite for a
 *  crossing without a shape. */
double DistanceToCrossing(const LaneInfo& crossing, double x_m, double y_m);

/** The deceleration (m/s^2, <= 0) that stops a person walking at `speed_mps` within
 *  `distance_m`: -v^2 / (2 d), at most kCrossingStopMaxDecel (a person that is already there,
 *  d = 0, gets that); 0 for a person standing or with no distance known (infinite). */
double CrossingStopDecel(double speed_mps, double distance_m);
/** How hard a walking person stops at most (m/s^2): within one stride from walking speed. */
constexpr double kCrossingStopMaxDecel = 6.0;

}  // namespace criticality::plugin
