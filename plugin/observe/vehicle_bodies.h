#pragma once
// Where a vehicle's body is, as SUMO sees it. SUMO reports a vehicle's front bumper and an angle
// that points from its back to its front (MSVehicle::computeAngle), its back being `length`
// behind the front along the lanes it came by (getBackPosition). In a turn the way between
// them bends, so the body's box (getBoundingBox, which SUMO's junction collision check uses) is
// the chord from back to front, shorter than the vehicle: a 7.1 m truck in a U-turn is a box
// of about 4 m. A box of the full length along that angle would reach back beyond the vehicle's
// back, into the lane beside it (bench/RESULTS.md, the grid's bus and truck false alarms).
// For the vehicles SUMO draws as one body; the box of a rail, trailer or flexible-bus shape
// SUMO bends along its further lanes, which this does not.
#include "plugin/network/road_network.h"
#include "plugin/sumo/sumo_reports.h"

namespace criticality::plugin {

/** SUMO's box length of the vehicle: the distance from its front bumper to the point its length
 *  behind its front along the lanes it came by (PointBehind), at most its length. Its length when
 *  that way is not known (its route starts within its length, it stands off any lane) or when
 *  it is parked (SUMO then turns it along its lane, not towards its back). */
double MeasuredBodyLength(RoadNetwork& network, const SumoObject& vehicle);

/** Sets body_length_m of every vehicle in `s` (persons keep 0). */
void MeasureBodies(RoadNetwork& network, SumoSurroundings* s);

}  // namespace criticality::plugin
