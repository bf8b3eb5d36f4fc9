#pragma once
// What kind of road user a SUMO vehicle is and what its vehicle type says, for the estimator
// (criticality::VehicleType: its class and the limits of its hypotheses), and which vClasses
// are egos with --all-vehicles. SUMO-independent (SUMO's vClass names as text).
#include <optional>
#include <set>
#include <string>

#include "criticality/scene.h"
#include "plugin/network/traffic_view.h"

namespace criticality::plugin {

/** The road user class of a SUMO vClass: cars (passenger, taxi, delivery, emergency, ...),
 *  heavy vehicles (truck, trailer, bus, coach), motorcycles (motorcycle, moped), bicycles
 *  (bicycle, scooter, and vehicles of vClass pedestrian: wheelchairs and the like), rail (tram,
 *  rail_urban, rail, rail_electric, rail_fast, subway, cable_car). nullopt: no road user (ship,
 *  aircraft, drone, container): it is left out of every scene. An unknown vClass is a car. */
std::optional<RoadUser> RoadUserOf(const std::string& vehicle_class);

/** The estimator's vehicle type from SUMO's: its class and SUMO's accel, decel,
 *  emergencyDecel, maxSpeed and (where given) mass. */
VehicleType TypeFrom(const VehicleTypeReport& sumo, RoadUser road_user);

/** Which vClasses are egos with --all-vehicles (--ego-classes). */
struct EgoClasses {
  /** The vClasses named; empty: the default, every road user but rail (a tram's or train's
   *  carriages are not modelled for an ego, only its first box). */
  std::set<std::string> classes;
  bool all{false};  ///< "all": every road user, rail included
  bool Includes(const std::string& vehicle_class) const;
};

/** Parses "all" or a comma-separated list of SUMO vClasses; throws std::invalid_argument naming
 *  an unknown class (and the known ones). */
EgoClasses ParseEgoClasses(const std::string& text);

}  // namespace criticality::plugin
