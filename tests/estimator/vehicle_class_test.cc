// Vehicle classes (paper Sec. IV-B-1): 6 classes from length and width, 8 with height.
#include "criticality/vehicle_class.h"

#include <gtest/gtest.h>

#include <set>

namespace criticality {
namespace {

TEST(VehicleClass, SixClassesWithoutHeight) {
  EXPECT_EQ(ClassifyVehicle(2.8, 1.5, std::nullopt), VehicleClass::kQuadricycle);
  EXPECT_EQ(ClassifyVehicle(3.9, 1.7, std::nullopt), VehicleClass::kSupermini);
  EXPECT_EQ(ClassifyVehicle(4.3, 1.8, std::nullopt), VehicleClass::kSmallFamily);
  EXPECT_EQ(ClassifyVehicle(4.7, 1.8, std::nullopt), VehicleClass::kLargeFamily);
  EXPECT_EQ(ClassifyVehicle(5.0, 1.85, std::nullopt),
            VehicleClass::kExecutive);  // SUMO's default car
  EXPECT_EQ(ClassifyVehicle(4.8, 1.95, std::nullopt), VehicleClass::kMultiPurpose);
  // Without a height, tall classes are never chosen, whatever the size.
  std::set<VehicleClass> seen;
  for (double l = 2.0; l < 12.0; l += 0.1) {
    for (double w = 1.2; w < 2.6; w += 0.1) seen.insert(ClassifyVehicle(l, w, std::nullopt));
  }
  EXPECT_EQ(seen.size(), 6u);
  EXPECT_EQ(seen.count(VehicleClass::kOffRoader), 0u);
  EXPECT_EQ(seen.count(VehicleClass::kCargo), 0u);
}

TEST(VehicleClass, TwoMoreWithHeight) {
  EXPECT_EQ(ClassifyVehicle(4.7, 1.9, 1.75), VehicleClass::kOffRoader);
  EXPECT_EQ(ClassifyVehicle(6.0, 2.1, 2.6), VehicleClass::kCargo);
  EXPECT_EQ(ClassifyVehicle(4.3, 1.8, 1.45), VehicleClass::kSmallFamily);  // a low car stays put
}

TEST(VehicleClass, MassAndInertiaGrowWithClassAndStayInPublishedRanges) {
  const VehicleClass order[] = {VehicleClass::kQuadricycle, VehicleClass::kSupermini,
                                VehicleClass::kSmallFamily, VehicleClass::kLargeFamily,
                                VehicleClass::kExecutive,   VehicleClass::kCargo};
  double last_mass = 0.0;
  for (VehicleClass c : order) {
    const core::VehicleParams p = VehicleParamsFor(c, 4.5, 1.8);
    EXPECT_GT(p.mass_kg, last_mass) << VehicleClassName(c);
    last_mass = p.mass_kg;
    EXPECT_GE(p.mass_kg, 450.0);
    EXPECT_GE(p.yaw_inertia_kgm2, 300.0);
    EXPECT_LE(p.yaw_inertia_kgm2, 4500.0);
    EXPECT_GT(p.lr_m, p.lf_m) << "CoG ahead of mid-wheelbase";
    // Understeering (stable) with equal axle stiffness and the CoG ahead of mid-wheelbase.
    EXPECT_GT(p.cr_npr * p.lr_m - p.cf_npr * p.lf_m, 0.0);
  }
}

}  // namespace
}  // namespace criticality
