// The observe stage through a fake SUMO world, no SUMO: the egos' life cycle (depart,
// teleport, arrive, vanish) as events, estimation paused while teleported, collisions once per
// contact and placed where SUMO removed the collider, neighbours when the whole network is read.
#include "plugin/observe/observe_stage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "../fake_sumo_world.h"

namespace criticality::plugin {
namespace {

using testing::FakeSumoWorld;

std::string Events(const Observation& obs) {
  std::string out;
  for (const EgoEvent& e : obs.ego_events) {
    out += (out.empty() ? "" : "; ") + e.ego + " " + EgoEventName(e.kind);
    if (!e.detail.empty()) out += " (" + e.detail + ")";
  }
  return out;
}

std::vector<std::string> Egos(const Observation& obs) {
  std::vector<std::string> ids;
  for (const SumoSurroundings::Ego& e : obs.surroundings.egos)
    ids.push_back(obs.surroundings.objects[e.self].id);
  return ids;
}

ObserveConfig Named(std::vector<std::string> egos) {
  ObserveConfig c;
  c.egos = std::move(egos);
  return c;
}

TEST(ObserveStage, ANamedEgosLifeCycleIsEventsAndTeleportsPauseIt) {
  FakeSumoWorld w;
  ObserveStage stage(Named({"ego"}), &w);
  w.AddVehicle("ego", 0, 0, 90, 10);
  w.next_report.departed = {"ego"};
  w.Step();
  Observation obs = stage.Run();
  EXPECT_EQ(Events(obs), "ego depart");
  EXPECT_EQ(Egos(obs), std::vector<std::string>{"ego"});
  EXPECT_EQ(stage.EgosSeen(), 1);
  // A teleport that starts and one that ends; while teleported it is not read.
  w.next_report.teleport_start = {"ego"};
  w.Step();
  obs = stage.Run();
  EXPECT_EQ(Events(obs), "ego teleport-start (jammed or stuck (time-to-teleport))");
  EXPECT_TRUE(Egos(obs).empty());
  w.next_report.teleport_end = {"ego"};
  w.Step();
  obs = stage.Run();
  EXPECT_EQ(Events(obs), "ego teleport-end");
  EXPECT_EQ(Egos(obs), std::vector<std::string>{"ego"});
  // It arrives: its memory in the world is dropped and the named egos are all done.
  EXPECT_FALSE(stage.AllNamedEgosDone());
  w.Remove("ego");
  w.next_report.arrived = {"ego"};
  w.Step();
  obs = stage.Run();
  EXPECT_EQ(Events(obs), "ego arrive");
  EXPECT_EQ(obs.left, std::vector<std::string>{"ego"});
  EXPECT_EQ(w.forgotten, std::vector<std::string>{"ego"});
  EXPECT_TRUE(stage.AllNamedEgosDone());
  EXPECT_EQ(stage.NeverDeparted(obs.time_s), "");
}

TEST(ObserveStage, ANamedEgoGoneWithoutArrivingVanishedAndOneNeverSeenIsReported) {
  FakeSumoWorld w;
  ObserveStage stage(Named({"ego", "late"}), &w);
  w.AddVehicle("ego", 0, 0, 90, 10);
  w.next_report.departed = {"ego"};
  w.Step();
  stage.Run();
  w.Remove("ego");  // removed by SUMO (e.g. collision.action remove) without arriving
  w.Step();
  const Observation obs = stage.Run();
  EXPECT_EQ(Events(obs), "ego vanish (left the network without arriving)");
  EXPECT_EQ(obs.left, std::vector<std::string>{"ego"});
  EXPECT_NE(stage.NeverDeparted(obs.time_s).find("--ego 'late' never departed"),
            std::string::npos);
  EXPECT_NE(stage.NeverDeparted(0.5).find("by t = 0.5 s:"), std::string::npos)
      << stage.NeverDeparted(0.5);  // no trailing zeros
}

TEST(ObserveStage, ACollisionIsRecordedOncePerContact) {
  FakeSumoWorld w;
  ObserveStage stage(Named({"ego"}), &w);
  w.AddVehicle("ego", 0, 0, 90, 10);
  w.next_report.departed = {"ego"};
  w.Step();
  stage.Run();
  SumoCollision c;
  c.collider = "ego";
  c.victim = "other";
  c.x_m = 1.0;
  c.y_m = 2.0;
  for (int k = 0; k < 3; ++k) {  // SUMO reports the pair again while they overlap
    w.next_report.collisions = {c};
    w.Step();
    const Observation obs = stage.Run();
    ASSERT_EQ(obs.collisions.size(), k == 0 ? 1u : 0u) << "step " << k;
    if (k == 0) {
      EXPECT_TRUE(obs.collisions[0].involves_ego);
      EXPECT_DOUBLE_EQ(obs.collisions[0].sumo.x_m, 1.0);  // read from the collider: kept
    }
  }
  w.Step();  // they separate
  stage.Run();
  w.next_report.collisions = {c};  // and touch again: a new contact
  w.Step();
  EXPECT_EQ(stage.Run().collisions.size(), 1u);
}

TEST(ObserveStage, ACollisionWhoseColliderSumoRemovedIsPlacedFromItsLane) {
  FakeSumoWorld w;
  w.AddEdge("E", 0, 10, 100, 10, 1);
  ObserveStage stage(Named({"ego"}), &w);
  w.AddVehicle("ego", 0, 0, 90, 10);
  w.next_report.departed = {"ego"};
  w.Step();
  stage.Run();
  SumoCollision gone;  // collision.action remove: SUMO's lane and position of the collider
  gone.collider = "a";
  gone.victim = "b";
  gone.lane = "E_0";
  gone.pos_m = 40.0;
  gone.collider_present = false;
  gone.x_m = gone.y_m = std::nan("");
  SumoCollision person = gone;  // with a person SUMO reports the person's lane: unknown place
  person.collider = "c";
  person.type = "crossing";
  w.next_report.collisions = {gone, person};
  w.Step();
  const Observation obs = stage.Run();
  ASSERT_EQ(obs.collisions.size(), 2u);
  EXPECT_DOUBLE_EQ(obs.collisions[0].sumo.x_m, 40.0);
  EXPECT_DOUBLE_EQ(obs.collisions[0].sumo.y_m, 10.0);
  EXPECT_FALSE(obs.collisions[0].involves_ego);
  EXPECT_TRUE(std::isnan(obs.collisions[1].sumo.x_m));
}

TEST(ObserveStage, EveryVehicleIsAnEgoWithItsNeighboursWhenTheWholeNetworkIsRead) {
  FakeSumoWorld w;
  ObserveConfig all;
  all.all_vehicles = true;
  all.range_m = 80.0;
  ObserveStage stage(all, &w);
  w.AddVehicle("a", 0, 0, 90, 10);
  w.AddVehicle("b", 30, 0, 90, 10);
  w.AddVehicle("far", 1000, 0, 90, 10);
  w.AddPerson("p", 10, 5, 0, 1);
  w.next_report.departed = {"a", "b", "far"};
  w.Step();
  Observation obs = stage.Run();
  EXPECT_EQ(Egos(obs), (std::vector<std::string>{"a", "b", "far"}));
  const SumoSurroundings& s = obs.surroundings;
  auto names = [&](int ego) {
    std::vector<std::string> ids;
    for (int k : s.egos[ego].nearby) ids.push_back(s.objects[k].id);
    return ids;
  };
  EXPECT_EQ(names(0), (std::vector<std::string>{"b", "p"}));
  EXPECT_EQ(names(1), (std::vector<std::string>{"a", "p"}));
  EXPECT_TRUE(names(2).empty());
  // A vehicle that leaves the network without arriving vanished; the others go on.
  w.Remove("far");
  w.Step();
  obs = stage.Run();
  EXPECT_EQ(Events(obs), "far vanish (left the network without arriving)");
  EXPECT_EQ(Egos(obs), (std::vector<std::string>{"a", "b"}));
}

// Under --all-vehicles, vehicles of a class --ego-classes leaves out (a tram by default) are
// read as objects but get no ego events: no depart, no arrive.
TEST(ObserveStage, VehiclesOfNoEgoClassGetNoEgoEvents) {
  FakeSumoWorld w;
  ObserveConfig all;
  all.all_vehicles = true;
  all.ego_class = [](const std::string& vehicle_class) { return vehicle_class != "tram"; };
  ObserveStage stage(all, &w);
  w.AddVehicle("car", 0, 0, 90, 10);
  w.AddVehicle("tram", 30, 0, 90, 10).vehicle_class = "tram";
  w.next_report.departed = {"car", "tram"};
  w.Step();
  Observation obs = stage.Run();
  EXPECT_EQ(Events(obs), "car depart");
  ASSERT_EQ(obs.surroundings.objects.size(), 2u);  // the tram is still an object
  w.Remove("car");
  w.Remove("tram");
  w.next_report.arrived = {"car", "tram"};
  w.Step();
  obs = stage.Run();
  EXPECT_EQ(Events(obs), "car arrive");
}

TEST(ObserveStage, APersonNamedAsEgoIsAnError) {
  FakeSumoWorld w;
  w.AddPerson("walker", 0, 0, 0, 1);
  ObserveStage stage(Named({"walker"}), &w);
  EXPECT_THROW(stage.CheckNamedEgos(), EgoError);
}

// A flow's own ID names none of its vehicles (SUMO calls them FLOW.0, FLOW.1, ...): the error
// says so instead of "no file defines it"; a typo gets the plain error.
TEST(ObserveStage, AFlowsIdNamedAsEgoIsAnErrorNamingItsVehicles) {
  const std::string routes = ::testing::TempDir() + "observe_flow_ego.rou.xml";
  std::ofstream(routes) << "<routes><flow id=\"bikes\" begin=\"0\" end=\"9\" number=\"2\" "
                           "from=\"a\" to=\"b\"/></routes>\n";
  for (const std::string& ego : {std::string("bikes"), std::string("bikez")}) {
    FakeSumoWorld w;
    w.options["route-files"] = routes;
    ObserveStage stage(Named({ego}), &w);
    try {
      stage.CheckNamedEgos();
      ADD_FAILURE() << ego << " accepted";
    } catch (const EgoError& e) {
      const bool flow_hint = std::string(e.what()).find("'bikes.0'") != std::string::npos;
      EXPECT_EQ(flow_hint, ego == "bikes") << e.what();
    }
  }
  // A vehicle of the flow is an ego SUMO will load.
  FakeSumoWorld w;
  w.options["route-files"] = routes;
  ObserveStage stage(Named({"bikes.1"}), &w);
  EXPECT_NO_THROW(stage.CheckNamedEgos());
  std::remove(routes.c_str());
}

TEST(ObserveStage, CriticalEventsComeFromTheEgosBodies) {
  FakeSumoWorld w;
  ObserveStage stage(Named({"ego"}), &w);
  w.AddVehicle("ego", 10, 0, 90, 10);     // body from x = 5 to 10
  w.AddVehicle("touching", 14, 0, 90, 0);  // body from x = 9 to 14: overlaps
  w.next_report.departed = {"ego"};
  w.Step();  // both move on at their speeds: ego to 11, touching stays
  const Observation obs = stage.Run();
  ASSERT_EQ(obs.critical_events.size(), 1u);
  EXPECT_EQ(obs.critical_events[0].other, "touching");
  EXPECT_EQ(obs.critical_events[0].kind, CriticalEvent::Kind::kOverlap);
}

TEST(ObserveStage, ALongTrainIsNearAnEgoItsRearPasses) {
  FakeSumoWorld w;
  ObserveConfig all;
  all.all_vehicles = true;
  all.range_m = 80.0;
  ObserveStage stage(all, &w);
  w.AddVehicle("car", 0, 0, 0, 10);                            // northbound at the origin
  // A 720 m freight train, its front 700 m east: its centre (340 m) is 3 cells away, its rear
  // (-20 m) beside the car.
  w.AddVehicle("train", 700, 5, 90, 20).length_m = 720.0;
  w.next_report.departed = {"car", "train"};
  w.Step();
  const Observation obs = stage.Run();
  ASSERT_EQ(obs.surroundings.egos.size(), 2u);
  const SumoSurroundings::Ego& car = obs.surroundings.egos[0];
  ASSERT_EQ(car.nearby.size(), 1u);
  EXPECT_EQ(obs.surroundings.objects[car.nearby[0]].id, "train");
}

}  // namespace
}  // namespace criticality::plugin
