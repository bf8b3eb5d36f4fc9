#pragma once
// Where a walking person is in SUMO's pedestrian network, and whether its walk goes on along
// the footway (Pedestrian::stays_on_footway). SUMO's netconvert names a junction's crossings
// ":JUNCTION_cN" and its walking areas ":JUNCTION_wN"; a sidewalk is a lane of a normal edge
// that only pedestrians may use.
#include <string>

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

}  // namespace criticality::plugin
