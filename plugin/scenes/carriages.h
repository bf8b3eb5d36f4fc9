#pragma once
// A long vehicle as a chain of boxes along its way, as SUMO draws trains and trams: carriages
// one behind the other along the lanes it came by, each with its own heading, yaw rate and lane.
// The estimator takes the first box as the vehicle and the others as its carriages
// (criticality::Carriage: one object, the vehicle's hypotheses).
#include <optional>
#include <vector>

#include "criticality/scene.h"
#include "plugin/network/road_network.h"
#include "plugin/network/traffic_view.h"
#include "plugin/scenes/object_lanes.h"
#include "plugin/scenes/scene_config.h"

namespace criticality::plugin {

/** Bodies up to this long are one box; a longer one without SUMO's carriage parameters is cut
 *  into equal carriages of at most this length (our choice: a tram's car or a semi-trailer). */
inline constexpr double kMaxBoxLengthM = 20.0;
/** SUMO's default gap between carriages (GUIBaseVehicle: carriageGap 1 m). */
inline constexpr double kDefaultCarriageGapM = 1.0;
/** At most this many carriages behind the first box (the estimator's limit, with a margin): a
 *  body that would need more gets longer ones. */
inline constexpr int kMaxCarriages = 60;

/** How a body is cut: its first box and the carriages behind it, front to back. */
struct BodyPlan {
  double head_length_m{0.0};
  std::vector<double> carriage_lengths_m;
  double gap_m{kDefaultCarriageGapM};
};

/** SUMO's locomotiveLength, carriageLength and carriageGap where the vType gives them (the first
 *  box the locomotive, then carriages, the last one shortened to what is left); otherwise one
 *  box up to kMaxBoxLengthM, and longer bodies in equal carriages of at most that. A body that
 *  would need more than kMaxCarriages carriages gets kMaxCarriages equal ones. */
BodyPlan PlanBody(double length_m, double width_m, const VehicleTypeReport& type);

/** A vehicle is bent where the chord of its way from its front back by its length (the lanes it
 *  came by, way_behind.h LineBehind: SUMO's box of it, but for a lane change since the junction)
 *  is at least this much shorter than its length: about 70 degrees of turn along a 5 m car, 45
 *  along a 12 m bus. */
inline constexpr double kBentBodyToleranceM = 0.3;
/** A bent body is cut into equal boxes of at most this length (our choice: a 12 m bus in a
 *  turn is three boxes that each keep to the lanes they stand on). */
inline constexpr double kBentBoxLengthM = 4.0;

/** Whether the chord of a vehicle's way (`box_length_m`) is shorter than the vehicle by
 *  kBentBodyToleranceM or more. */
bool IsBent(double length_m, double box_length_m);

/** A bent body as a chain: equal boxes of at most kBentBoxLengthM, no gaps, along its way.
 *  A single box would move rigidly along SUMO's angle (back to front), so its back would run
 *  against the way the vehicle's back really goes, e.g. towards its follower in a U-turn. */
BodyPlan PlanBentBody(double length_m);

/** The carriages of `plan` behind the vehicle's first box, placed along the lanes it came by
 *  (its route's previous lanes, internal lanes included; straight on beyond where the network
 *  ends), each with the lane it stands on sampled as its own lane, its yaw rate the lane's at
 *  the vehicle's speed. `v.length_m` is the first box's length. */
std::vector<Carriage> PlaceCarriages(const BodyPlan& plan, const VehicleOnLane& v, double width_m,
                                     const SceneConfig& config, double step_s,
                                     RoadNetwork* network);

}  // namespace criticality::plugin
