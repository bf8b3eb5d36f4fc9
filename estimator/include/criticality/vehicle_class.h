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
 *  wheelbase (about 60 % of the length) and track (width - 0.25 m). */
core::VehicleParams VehicleParamsFor(VehicleClass c, double length_m, double width_m);

}  // namespace criticality
