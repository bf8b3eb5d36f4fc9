#pragma once
// Where a vehicle must stop within its reach (ReachAhead: v T + a_max T^2 / 2), as SUMO knows
// it now: its next traffic light (the distance from its front bumper to the stop line) showing
// red, red-yellow or yellow; otherwise the link from its lane to the next lane of its route (at
// the lane's end): a stop sign or all-way stop ('s', 'w'), or a link that must yield ('m'
// minor, 'g' green without priority, '=' equal) while SUMO has a foe approaching it (the
// link's has_foe, read this step). Whether the vehicle will comply is the estimator's question
// (Params::stop_obligations). With VehicleOnLane::observable_only the signal is the one of the
// link it is seen to take (NextLaneSeen) at its lane's end, as SUMO's link state shows it (no
// getNextTLS along the route).
#include <optional>

#include "criticality/scene.h"
#include "plugin/network/road_network.h"
#include "plugin/network/traffic_view.h"
#include "plugin/scenes/object_lanes.h"

namespace criticality::plugin {

std::optional<StopLine> StopLineOf(const VehicleOnLane& v, const std::string& id,
                                   const SceneConfig& config, RoadNetwork* network,
                                   TrafficView* traffic);

/** Whether the link from the vehicle's lane to its next lane (its route's, or the one it is
 *  seen to take) lies within its reach and has no priority ('m', '=', 'g', 's', 'w'), with or
 *  without a foe approaching now: a vehicle there may brake to yield for reasons the scene does
 *  not hold (SUMO slows its vehicles before such links), so its braking is not read as having
 *  no cause (ObjectState::braking_causes_known). */
bool MayYieldAhead(const VehicleOnLane& v, const SceneConfig& config, RoadNetwork* network);

}  // namespace criticality::plugin
