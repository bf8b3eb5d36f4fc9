// SUMO's vClasses as road users, the estimator's vehicle type from SUMO's vType, and which
// classes are egos with --all-vehicles.
#include "plugin/scenes/road_users.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace criticality::plugin {
namespace {

TEST(RoadUsers, EveryVClassIsTheRoadUserItIs) {
  EXPECT_EQ(RoadUserOf("passenger"), RoadUser::kCar);
  EXPECT_EQ(RoadUserOf("delivery"), RoadUser::kCar);
  EXPECT_EQ(RoadUserOf("truck"), RoadUser::kHeavy);
  EXPECT_EQ(RoadUserOf("trailer"), RoadUser::kHeavy);
  EXPECT_EQ(RoadUserOf("bus"), RoadUser::kHeavy);
  EXPECT_EQ(RoadUserOf("coach"), RoadUser::kHeavy);
  EXPECT_EQ(RoadUserOf("motorcycle"), RoadUser::kMotorcycle);
  EXPECT_EQ(RoadUserOf("moped"), RoadUser::kMotorcycle);
  EXPECT_EQ(RoadUserOf("bicycle"), RoadUser::kBicycle);
  EXPECT_EQ(RoadUserOf("tram"), RoadUser::kRail);
  EXPECT_EQ(RoadUserOf("rail"), RoadUser::kRail);
  EXPECT_EQ(RoadUserOf("rail_urban"), RoadUser::kRail);
  EXPECT_FALSE(RoadUserOf("ship").has_value());  // not on the road: nobody's obstacle
  EXPECT_EQ(RoadUserOf("something_new"), RoadUser::kCar);  // an unknown class is a car
}

TEST(RoadUsers, TheTypeCarriesSumosLimits) {
  VehicleTypeReport truck;
  truck.vehicle_class = "truck";
  truck.accel_mps2 = 1.3;
  truck.decel_mps2 = 4.0;
  truck.emergency_decel_mps2 = 7.0;
  truck.max_speed_mps = 36.1;
  truck.mass_kg = 12000.0;
  const VehicleType t = TypeFrom(truck, RoadUser::kHeavy);
  EXPECT_EQ(t.road_user, RoadUser::kHeavy);
  EXPECT_EQ(t.accel_mps2, 1.3);
  EXPECT_EQ(t.decel_mps2, 4.0);
  EXPECT_EQ(t.emergency_decel_mps2, 7.0);
  EXPECT_EQ(t.max_speed_mps, 36.1);
  EXPECT_EQ(t.mass_kg, 12000.0);
  // A value SUMO gives as 0 (a type that never accelerates) is no limit to pass on.
  truck.accel_mps2 = 0.0;
  EXPECT_FALSE(TypeFrom(truck, RoadUser::kHeavy).accel_mps2.has_value());
}

TEST(RoadUsers, EgoClassesDefaultToEveryRoadUserButRail) {
  const EgoClasses d;
  EXPECT_TRUE(d.Includes("passenger"));
  EXPECT_TRUE(d.Includes("bicycle"));
  EXPECT_TRUE(d.Includes("truck"));
  EXPECT_FALSE(d.Includes("tram"));
  EXPECT_FALSE(d.Includes("ship"));
  const EgoClasses all = ParseEgoClasses("all");
  EXPECT_TRUE(all.Includes("tram"));
  EXPECT_FALSE(all.Includes("ship"));  // no road user is ever an ego
  const EgoClasses some = ParseEgoClasses("bus,tram");
  EXPECT_TRUE(some.Includes("tram"));
  EXPECT_TRUE(some.Includes("bus"));
  EXPECT_FALSE(some.Includes("passenger"));
}

TEST(RoadUsers, AnUnknownEgoClassIsAnErrorNamingIt) {
  try {
    ParseEgoClasses("passenger,lorry");
    FAIL() << "lorry accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'lorry'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("truck"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ParseEgoClasses(","), std::invalid_argument);
  // A vClass SUMO knows that is no road user here (a ship) would select no ego at all.
  try {
    ParseEgoClasses("bus,ship");
    FAIL() << "ship accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'ship' is no road user"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace criticality::plugin
