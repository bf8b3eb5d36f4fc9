#pragma once
/** @file Vehicle classes (paper Sec. IV-B-1): a CO's dimensions give its class, the class gives
 *  mass, yaw inertia and tyre/geometry data for the motion models. */
#include <optional>
#include <string>

#include "core/vehicle_params.h"

namespace criticality {

/** 6 classes from length and width (Van Miert 1999, the EU segments); 2 more when the height is
 *  known. */
enum class VehicleClass {
  kQuadricycle,
  kSupermini,
  kSmallFamily,
  kLargeFamily,
  kExecutive,
  kMultiPurpose,
  kOffRoader,  ///< height known only
  kCargo,      ///< height known only
};

std::string VehicleClassName(VehicleClass c);

/** Classifies by dimensions (metres). Thresholds: typical lengths of the segments (A < 3.4 m,
 *  B < 4.1 m, C < 4.5 m, D < 4.8 m, E beyond); multi-purpose when at least 1.9 m wide and 4.4 m
 *  long; with a height, cargo from 2.2 m high or 5.6 m long, off-roader from 1.65 m high. */
VehicleClass ClassifyVehicle(double length_m, double width_m, std::optional<double> height_m);

/** Mass and yaw inertia per class: class averages in the range of Heydinger et al. (NHTSA
 *  inertial data, 1999); axle cornering stiffness and CoG position from Isermann (2006),
 *  scaled with mass (about 55 N/rad per kg per axle); CoG at 45 % of the wheelbase from the
 *  front axle ("a little ahead of mid-wheelbase", DESIGN.md). `length_m` and `width_m` set the
 *  wheelbase (about 60 % of the length) and track (width - 0.25 m).
 *  Driving power at the wheels per unit mass (Params::power_limited_drive), W/kg: rated power
 *  per mass times a drivetrain efficiency of 0.9 (Guzzella & Sciarretta, Vehicle Propulsion
 *  Systems, 2013: about 0.9 for manual and dual-clutch gearboxes). Rated power per mass: our
 *  estimates of the segment averages around the EU new-car average of 95 kW for 1,392 kg, 68
 *  W/kg (ICCT, European Vehicle Market Statistics 2017/18): quadricycle 33 (EU L7e limit 15 kW,
 *  Regulation (EU) 168/2013, at 450 kg), supermini 50, small family 65, large family 73,
 *  executive 86, multi-purpose 58, off-roader 64, cargo van 33; at the wheels 30, 45, 58, 66,
 *  77, 52, 57, 30. A large family car then reaches 3.3 m/s^2 at 20 m/s and 2.2 at 30 m/s. */
core::VehicleParams VehicleParamsFor(VehicleClass c, double length_m, double width_m);

}  // namespace criticality
