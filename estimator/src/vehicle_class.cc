#include "criticality/vehicle_class.h"

#include <algorithm>

namespace criticality {

std::string VehicleClassName(VehicleClass c) {
  switch (c) {
    case VehicleClass::kQuadricycle:
      return "quadricycle";
    case VehicleClass::kSupermini:
      return "supermini";
    case VehicleClass::kSmallFamily:
      return "small family car";
    case VehicleClass::kLargeFamily:
      return "large family car";
    case VehicleClass::kExecutive:
      return "executive";
    case VehicleClass::kMultiPurpose:
      return "multi-purpose vehicle";
    case VehicleClass::kOffRoader:
      return "off-roader";
    case VehicleClass::kCargo:
      return "cargo";
  }
  return "unknown";
}

VehicleClass ClassifyVehicle(double length_m, double width_m, std::optional<double> height_m) {
  if (height_m) {
    if (*height_m >= 2.2 || length_m >= 5.6) return VehicleClass::kCargo;
    if (*height_m >= 1.65) return VehicleClass::kOffRoader;
  }
  if (length_m < 3.4) return VehicleClass::kQuadricycle;
  if (width_m >= 1.9 && length_m >= 4.4) return VehicleClass::kMultiPurpose;
  if (length_m < 4.1) return VehicleClass::kSupermini;
  if (length_m < 4.5) return VehicleClass::kSmallFamily;
  if (length_m < 4.8) return VehicleClass::kLargeFamily;
  return VehicleClass::kExecutive;
}

namespace {
struct ClassData {
  double mass_kg;
  double yaw_inertia_kgm2;
  double power_per_mass_wpkg;  ///< driving power at the wheels per unit mass
};

ClassData DataOf(VehicleClass c) {
  switch (c) {
    case VehicleClass::kQuadricycle:
      return {450.0, 400.0, 30.0};
    case VehicleClass::kSupermini:
      return {1100.0, 1500.0, 45.0};
    case VehicleClass::kSmallFamily:
      return {1300.0, 1900.0, 58.0};
    case VehicleClass::kLargeFamily:
      return {1500.0, 2500.0, 66.0};
    case VehicleClass::kExecutive:
      return {1750.0, 3100.0, 77.0};
    case VehicleClass::kMultiPurpose:
      return {1900.0, 3400.0, 52.0};
    case VehicleClass::kOffRoader:
      return {2200.0, 4000.0, 57.0};
    case VehicleClass::kCargo:
      return {3000.0, 4500.0, 30.0};
  }
  return {1500.0, 2500.0, 60.0};
}
}  // namespace

core::VehicleParams VehicleParamsFor(VehicleClass c, double length_m, double width_m) {
  const ClassData d = DataOf(c);
  core::VehicleParams p;
  p.mass_kg = d.mass_kg;
  p.yaw_inertia_kgm2 = d.yaw_inertia_kgm2;
  p.power_per_mass_wpkg = d.power_per_mass_wpkg;
  const double wheelbase = std::clamp(0.6 * length_m, 1.8, 4.0);
  p.lf_m = 0.45 * wheelbase;
  p.lr_m = 0.55 * wheelbase;
  p.cf_npr = 55.0 * d.mass_kg;
  p.cr_npr = 55.0 * d.mass_kg;
  p.track_m = std::clamp(width_m - 0.25, 0.8, 2.2);
  return p;
}

}  // namespace criticality
