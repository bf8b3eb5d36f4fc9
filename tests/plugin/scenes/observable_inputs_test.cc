// --observable-only (SceneConfig::observable_only) through a fake SUMO world: scenes hold only
// what the vehicles' sensors could know. Each vehicle's way on is its blinker's or straight on,
// never its route; no route ends; the signal of the link it is seen to take, not getNextTLS
// along its route; a class's limits instead of its vType's; a leader only in its own lane; a
// walker keeps to a sidewalk it walks on, whatever its next edge.
#include <gtest/gtest.h>

#include "../fake_sumo_world.h"
#include "plugin/scenes/scene_stage.h"

namespace criticality::plugin {
namespace {

using testing::FakeSumoWorld;

Observation Observe(FakeSumoWorld& w, const std::vector<std::string>& egos) {
  return testing::ObserveAll(w, egos);
}

SceneBatch Scenes(FakeSumoWorld& w, const std::vector<std::string>& egos, bool observable) {
  SceneConfig config;
  config.observable_only = observable;
  SceneStage stage(config, w.StepLength(), true, &w, &w);
  return stage.Run(Observe(w, egos));
}

// An eastbound edge E (x 0..100) that goes on straight (F, east) or bears left (N, north-east:
// a turn the lane samples follow).
void Junction(FakeSumoWorld& w) {
  w.AddEdge("E", 0, 0, 100, 0, 1);
  w.AddEdge("F", 100, 0, 300, 0, 1);
  w.AddEdge("N", 100, 0, 240, 140, 1);
  w.AddLink("E_0", "F_0", "M", false, "s");
  w.AddLink("E_0", "N_0", "m", false, "l");
}

// The farthest sample of the ego's own lane, in its frame: y ~ 0 straight on, y > 0 turned left.
double FarLeft(const Scene& s) { return s.ego.lanes.own->left.points[2].y; }

TEST(ObservableInputs, TheWayOnIsTheBlinkersOrStraightNotTheRoute) {
  FakeSumoWorld w;
  Junction(w);
  w.AddVehicle("ego", 95, 0, 90, 12, "E_0", 95, {"E", "N"});  // its route turns left
  ASSERT_TRUE(Scenes(w, {"ego"}, false).scenes.at(0).ego.lanes.own);
  const double route = FarLeft(Scenes(w, {"ego"}, false).scenes.at(0));
  const double seen = FarLeft(Scenes(w, {"ego"}, true).scenes.at(0));
  EXPECT_GT(route, 5.0);            // along its route: into the left turn
  EXPECT_NEAR(seen, 0.9, 1.0);      // no blinker: straight on
  w.Find("ego")->signals = 2;       // the left blinker
  EXPECT_GT(FarLeft(Scenes(w, {"ego"}, true).scenes.at(0)), 5.0);
  w.Find("ego")->signals = 1 | 2;   // hazard lights are no turn signal
  EXPECT_NEAR(FarLeft(Scenes(w, {"ego"}, true).scenes.at(0)), 0.9, 1.0);
}

TEST(ObservableInputs, WhereARouteEndsIsNotKnown) {
  FakeSumoWorld w;
  w.AddEdge("E", 0, 0, 100, 0, 1);
  w.AddVehicle("ends", 90, 0, 90, 10, "E_0", 90, {"E"});
  EXPECT_TRUE(Scenes(w, {"ends"}, false).scenes.at(0).ego.state.route_end_m.has_value());
  EXPECT_FALSE(Scenes(w, {"ends"}, true).scenes.at(0).ego.state.route_end_m.has_value());
}

TEST(ObservableInputs, TheSignalIsTheSeenLinksAtTheLanesEnd) {
  FakeSumoWorld w;
  w.AddEdge("E", 0, 0, 100, 0, 1);
  w.AddEdge("F", 100, 0, 300, 0, 1);
  w.AddLink("E_0", "F_0", "r", false, "s");
  w.AddVehicle("v", 80, 0, 90, 10, "E_0", 80, {"E", "F"});
  w.signals["v"] = SignalReport{45.0, 'G'};  // getNextTLS along its route: green further on
  const SceneBatch route = Scenes(w, {"v"}, false);
  EXPECT_FALSE(route.EgoOf(0).stop_line.has_value());
  const SceneBatch seen = Scenes(w, {"v"}, true);
  ASSERT_TRUE(seen.EgoOf(0).stop_line.has_value());
  EXPECT_EQ(seen.EgoOf(0).stop_line->reason, StopLine::Reason::kRedLight);
  EXPECT_NEAR(seen.EgoOf(0).stop_line->distance_m, 20.0, 1e-9);
  // A red signal on its route that the link it is seen to take does not show is not seen.
  FakeSumoWorld g;
  g.AddEdge("E", 0, 0, 100, 0, 1);
  g.AddEdge("F", 100, 0, 300, 0, 1);
  g.AddLink("E_0", "F_0", "G", false, "s");
  g.AddVehicle("v", 80, 0, 90, 10, "E_0", 80, {"E", "F"});
  g.signals["v"] = SignalReport{20.0, 'r'};
  EXPECT_TRUE(Scenes(g, {"v"}, false).EgoOf(0).stop_line.has_value());
  EXPECT_FALSE(Scenes(g, {"v"}, true).EgoOf(0).stop_line.has_value());
}

TEST(ObservableInputs, AClassIsSeenItsTypesLimitsAreNot) {
  FakeSumoWorld w;
  w.AddEdge("E", 0, 0, 300, 0, 1);
  SumoObject& truck = w.AddVehicle("truck", 50, 0, 90, 10, "E_0", 50, {"E"});
  truck.vehicle_class = "truck";
  truck.vehicle_type = "t";
  VehicleTypeReport t;
  t.vehicle_class = "truck";
  t.emergency_decel_mps2 = 6.0;
  t.max_speed_mps = 25.0;
  t.mass_kg = 18000.0;
  w.types["t"] = t;
  const VehicleType route = Scenes(w, {"truck"}, false).scenes.at(0).ego.type;
  EXPECT_EQ(route.emergency_decel_mps2, 6.0);
  EXPECT_EQ(route.mass_kg, 18000.0);
  const VehicleType seen = Scenes(w, {"truck"}, true).scenes.at(0).ego.type;
  EXPECT_EQ(seen.road_user, RoadUser::kHeavy);
  EXPECT_FALSE(seen.emergency_decel_mps2 || seen.max_speed_mps || seen.mass_kg ||
               seen.accel_mps2 || seen.decel_mps2);
}

TEST(ObservableInputs, ALeaderCountsOnlyInTheVehiclesOwnLane) {
  FakeSumoWorld w;
  w.AddEdge("E", 0, 0, 100, 0, 1);
  w.AddEdge("F", 100, 0, 300, 0, 1);
  w.AddLink("E_0", "F_0");
  w.AddVehicle("near", 50, 0, 90, 10, "E_0", 50, {"E", "F"});
  w.AddVehicle("far", 60, 0, 90, 10, "E_0", 60, {"E", "F"});
  w.leaders["near"] = LeaderReport{"x", 20.0, 0.0, 0.0};  // 20 m ahead: in E, 50 m left of it
  w.leaders["far"] = LeaderReport{"y", 60.0, 0.0, 0.0};   // 60 m ahead: beyond E's end (40 m)
  const SceneBatch seen = Scenes(w, {"near", "far"}, true);
  EXPECT_TRUE(seen.EgoOf(0).leader.has_value());
  EXPECT_FALSE(seen.EgoOf(1).leader.has_value());
  EXPECT_TRUE(Scenes(w, {"near", "far"}, false).EgoOf(1).leader.has_value());
}

TEST(ObservableInputs, AWalkerOnASidewalkKeepsToItWhateverItsNextEdge) {
  FakeSumoWorld w;
  w.AddEdge("E", 0, 0, 200, 0, 2);
  w.SetAllowed("E_0", {"pedestrian"});  // a sidewalk
  w.AddEdge(":J_c0", 200, -3, 200, 10, 1, 3.0, {"pedestrian"});  // a crossing
  w.AddEdge(":K_w0", 130, -3, 133, -3, 1, 3.0, {"pedestrian"});  // a corner's walking area
  w.AddVehicle("ego", 100, 1.6, 90, 10, "E_1", 100, {"E"});
  w.AddPerson("crosses", 120, -1.6, 90, 1.2, "E_0", ":J_c0");
  w.AddPerson("corner", 131, -3, 90, 1.2, ":K_w0_0", "E");
  const Scene route = Scenes(w, {"ego"}, false).scenes.at(0);
  const Scene seen = Scenes(w, {"ego"}, true).scenes.at(0);
  ASSERT_EQ(route.pedestrians.size(), 2u);  // ID order: corner, crosses
  ASSERT_EQ(seen.pedestrians.size(), 2u);
  EXPECT_FALSE(route.pedestrians[1].stays_on_footway);  // its next edge is a crossing
  EXPECT_TRUE(seen.pedestrians[1].stays_on_footway);    // seen: on the sidewalk
  EXPECT_FALSE(seen.pedestrians[0].stays_on_footway);   // at a corner it may cross
}

}  // namespace
}  // namespace criticality::plugin
