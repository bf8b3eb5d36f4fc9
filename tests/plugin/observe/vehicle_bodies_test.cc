// SUMO's box of a vehicle's body (plugin/observe/vehicle_bodies.h): from its front to its back
// along the lanes it came by, shorter than the vehicle in a turn; its length where the way
// behind is not known, for a parked vehicle and on a straight lane.
#include "plugin/observe/vehicle_bodies.h"

#include <gtest/gtest.h>

#include <cmath>

#include "../fake_sumo_world.h"

namespace criticality::plugin {
namespace {

using testing::FakeSumoWorld;

// N runs north to (0, 0); a square right turn through the junction's internal lane (0, 0) ->
// (0, 5) -> (5, 5) leads into E, east from (5, 5).
FakeSumoWorld Corner() {
  FakeSumoWorld w;
  testing::AddSquareRightTurn(w);
  return w;
}

SumoObject Truck(FakeSumoWorld& w, const std::string& lane, double pos, double x, double y) {
  SumoObject& t = w.AddVehicle("truck", x, y, 90.0, 5.0, lane, pos, {"N", "E"});
  t.length_m = 7.0;
  t.route_index = lane == "E_0" ? 1 : 0;
  return t;
}

TEST(VehicleBodies, InATurnTheBoxIsTheChordFromFrontToBack) {
  FakeSumoWorld w = Corner();
  // Front 1 m into E at (6, 5): the back is 7 m behind, 1 m before the turn's corner, at (0, 4).
  const SumoObject t = Truck(w, "E_0", 1.0, 6.0, 5.0);
  EXPECT_NEAR(MeasuredBodyLength(w, t), std::hypot(6.0, 1.0), 1e-9);
  // Far into E it is straight: its length.
  EXPECT_NEAR(MeasuredBodyLength(w, Truck(w, "E_0", 20.0, 25.0, 5.0)), 7.0, 1e-9);
  // Inside the junction, its front at (4, 5): back at (0, 2), a 3-4-5 chord.
  EXPECT_NEAR(MeasuredBodyLength(w, Truck(w, ":J_0_0", 9.0, 4.0, 5.0)), 5.0, 1e-9);
  // Its front 6 m into the turn, at (1, 5): the back on N at (0, -1).
  EXPECT_NEAR(MeasuredBodyLength(w, Truck(w, ":J_0_0", 6.0, 1.0, 5.0)), std::hypot(1.0, 6.0), 1e-9);
}

TEST(VehicleBodies, WhereTheWayBehindIsNotKnownOrTheVehicleParksItIsItsLength) {
  FakeSumoWorld w = Corner();
  SumoObject t = Truck(w, "E_0", 1.0, 6.0, 5.0);
  t.route = {"E"};  // its route starts on E: nothing behind
  t.route_index = 0;
  EXPECT_DOUBLE_EQ(MeasuredBodyLength(w, t), 7.0);
  SumoObject parked = Truck(w, "E_0", 1.0, 6.0, 5.0);
  parked.stop_state = 1 | 2;  // stopped, parking: SUMO turns it along its lane
  EXPECT_DOUBLE_EQ(MeasuredBodyLength(w, parked), 7.0);
  SumoObject off = Truck(w, "", 0.0, 6.0, 5.0);
  EXPECT_DOUBLE_EQ(MeasuredBodyLength(w, off), 7.0);
}

TEST(VehicleBodies, EveryVehicleOfAStepIsMeasuredAndPersonsAreNot) {
  FakeSumoWorld w = Corner();
  SumoSurroundings s;
  s.objects.push_back(Truck(w, "E_0", 1.0, 6.0, 5.0));
  SumoObject walker;
  walker.person = true;
  walker.lane = "E_0";
  s.objects.push_back(walker);
  MeasureBodies(w, &s);
  EXPECT_NEAR(s.objects[0].body_length_m, std::hypot(6.0, 1.0), 1e-9);
  EXPECT_DOUBLE_EQ(s.objects[1].body_length_m, 0.0);
}

}  // namespace
}  // namespace criticality::plugin
