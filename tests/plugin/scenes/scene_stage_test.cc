// The scenes stage through a fake SUMO world, no SUMO: lanes from each object's own view
// (neighbours of its edge that its class may use, the opposite direction's lane flagged as
// counter traffic from either side), route ends, stop lines, what each driver is expected to do,
// pedestrians on the footway, yaw rates, invalid objects and the Euler update.
#include "plugin/scenes/scene_stage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "../fake_sumo_world.h"
#include "plugin/network/polyline.h"
#include "plugin/scenes/carriages.h"
#include "plugin/sumo/sumo_conventions.h"

namespace criticality::plugin {
namespace {

using testing::FakeSumoWorld;

Observation Observe(FakeSumoWorld& w, const std::vector<std::string>& egos) {
  return testing::ObserveAll(w, egos);
}

SceneStage Stage(FakeSumoWorld& w, bool euler = true) {
  return SceneStage(SceneConfig{}, w.StepLength(), euler, &w, &w);
}

const Vehicle* VehicleIn(const Scene& s, const std::string& id) {
  for (const Vehicle& v : s.vehicles) {
    if (v.id == id) return &v;
  }
  return nullptr;
}

// An eastbound edge E of `lanes` lanes 3.2 m wide from x = 0 to 200, and its westbound twin W
// placed left of it as netconvert places a two-way street's directions.
void TwoWayStreet(FakeSumoWorld& w, int lanes) {
  w.AddEdge("E", 0, 0, 200, 0, lanes);
  const double w_axis = 0.5 * lanes * 3.2 + 0.5 * lanes * 3.2;  // E's half width + W's
  w.AddEdge("W", 200, w_axis, 0, w_axis, lanes);
}

TEST(SceneStage, AVehicleSeesTheLanesOfItsEdgeItsClassMayUse) {
  FakeSumoWorld w;
  w.AddEdge("E", 0, 0, 300, 0, 3);
  const double lane1_y = 0.0;  // lane 1 is the middle one
  w.AddVehicle("ego", 50, lane1_y, 90, 10, "E_1", 50, {"E"});
  SceneStage stage = Stage(w);
  Scene s = stage.Run(Observe(w, {"ego"})).scenes.at(0);
  ASSERT_TRUE(s.ego.lanes.own && s.ego.lanes.left && s.ego.lanes.right);
  EXPECT_FALSE(s.ego.lanes.left->counter_traffic);
  EXPECT_FALSE(s.ego.lanes.right->counter_traffic);
  // In the ego's frame: its own lane +-1.6 m, the left one 1.6..4.8 m.
  EXPECT_NEAR(s.ego.lanes.own->left.points[0].y, 1.6, 1e-9);
  EXPECT_NEAR(s.ego.lanes.left->left.points[0].y, 4.8, 1e-9);
  EXPECT_NEAR(s.ego.lanes.right->right.points[0].y, -4.8, 1e-9);
  // A bus lane on the left is not the car's neighbour (and it is no counter lane either).
  w.SetAllowed("E_2", {"bus"});
  SceneStage again = Stage(w);
  s = again.Run(Observe(w, {"ego"})).scenes.at(0);
  EXPECT_FALSE(s.ego.lanes.left.has_value());
  EXPECT_TRUE(s.ego.lanes.right.has_value());
}

TEST(SceneStage, TheOppositeDirectionIsCounterTrafficSeenFromEitherSide) {
  FakeSumoWorld w;
  TwoWayStreet(w, 1);
  w.AddVehicle("ego", 60, 0, 90, 10, "E_0", 60, {"E"});         // eastbound
  w.AddVehicle("oncoming", 120, 3.2, 270, 10, "W_0", 80, {"W"});  // westbound, left of the ego
  SceneStage stage = Stage(w);
  const SceneBatch batch = stage.Run(Observe(w, {"ego"}));
  const Scene& s = batch.scenes.at(0);
  ASSERT_TRUE(s.ego.lanes.own && s.ego.lanes.left);
  EXPECT_TRUE(s.ego.lanes.left->counter_traffic);
  EXPECT_FALSE(s.ego.lanes.right.has_value());
  // The oncoming car sees the ego's lane as its own left lane, also flagged.
  const Vehicle* oncoming = VehicleIn(s, "oncoming");
  ASSERT_NE(oncoming, nullptr);
  ASSERT_TRUE(oncoming->lanes && oncoming->lanes->own && oncoming->lanes->left);
  EXPECT_TRUE(oncoming->lanes->left->counter_traffic);
  // Its own lane is straight ahead of it in its own frame (it drives west: x grows westward).
  EXPECT_NEAR(oncoming->lanes->own->left.points[2].y, 1.6, 1e-9);
  EXPECT_GT(oncoming->lanes->own->left.points[2].x, 10.0);
}

TEST(SceneStage, AVehicleWhoseRouteEndsAheadLeavesThere) {
  FakeSumoWorld w;
  w.AddEdge("E", 0, 0, 100, 0, 1);
  w.AddEdge("F", 100, 0, 200, 0, 1);
  w.AddLink("E_0", "F_0");
  w.AddVehicle("ends", 90, 0, 90, 10, "E_0", 90, {"E"});       // its route ends 10 m ahead
  w.AddVehicle("goes_on", 60, 0, 90, 10, "E_0", 60, {"E", "F"});  // continues onto F
  SceneStage stage = Stage(w);
  const SceneBatch b = stage.Run(Observe(w, {"ends", "goes_on"}));
  ASSERT_EQ(b.scenes.size(), 2u);
  ASSERT_TRUE(b.scenes[0].ego.state.route_end_m.has_value());
  EXPECT_NEAR(*b.scenes[0].ego.state.route_end_m, 10.0, 1e-9);
  EXPECT_FALSE(b.scenes[1].ego.state.route_end_m.has_value());
}

TEST(SceneStage, ARedLightOrAYieldToAnApproachingFoeIsAStopLine) {
  FakeSumoWorld w;
  w.AddEdge("E", 0, 0, 100, 0, 1);
  w.AddEdge("F", 100, 0, 200, 0, 1);
  w.AddVehicle("red", 70, 0, 90, 10, "E_0", 70, {"E", "F"});
  w.AddVehicle("green", 40, 0, 90, 10, "E_0", 40, {"E", "F"});
  w.signals["red"] = SignalReport{30.0, 'r'};
  w.signals["green"] = SignalReport{60.0, 'G'};
  SceneStage stage = Stage(w);
  SceneBatch b = stage.Run(Observe(w, {"red", "green"}));
  const ObjectSnapshot& red = b.EgoOf(0);
  ASSERT_TRUE(red.stop_line.has_value());
  EXPECT_EQ(red.stop_line->reason, StopLine::Reason::kRedLight);
  EXPECT_DOUBLE_EQ(red.stop_line->distance_m, 30.0);
  EXPECT_FALSE(b.EgoOf(1).stop_line.has_value());
  // A minor link with a foe approaching, within reach of the lane's end: yield there.
  FakeSumoWorld y;
  y.AddEdge("E", 0, 0, 100, 0, 1);
  y.AddEdge("F", 100, 0, 200, 0, 1);
  y.AddLink("E_0", "F_0", "m", /*has_foe=*/true);
  y.AddVehicle("minor", 85, 0, 90, 10, "E_0", 85, {"E", "F"});
  SceneStage ystage = Stage(y);
  b = ystage.Run(Observe(y, {"minor"}));
  ASSERT_TRUE(b.EgoOf(0).stop_line.has_value());
  EXPECT_EQ(b.EgoOf(0).stop_line->reason, StopLine::Reason::kYield);
  EXPECT_NEAR(b.EgoOf(0).stop_line->distance_m, 15.0, 1e-9);
  // The same link without a foe: nothing to yield to.
  FakeSumoWorld n;
  n.AddEdge("E", 0, 0, 100, 0, 1);
  n.AddEdge("F", 100, 0, 200, 0, 1);
  n.AddLink("E_0", "F_0", "m", /*has_foe=*/false);
  n.AddVehicle("minor", 85, 0, 90, 10, "E_0", 85, {"E", "F"});
  SceneStage nstage = Stage(n);
  EXPECT_FALSE(nstage.Run(Observe(n, {"minor"})).EgoOf(0).stop_line.has_value());
}

// SceneConfig::internal_junction_yield (on by default): a left turn that waits inside the
// junction (its internal lane continues into another one, SUMO's internal junction) yields
// there, at the end of the first internal lane; a turn whose internal lane leads straight out
// keeps its line at the entry.
TEST(SceneStage, ATurnThatWaitsInsideTheJunctionYieldsAtItsInternalJunction) {
  for (const bool inside : {false, true}) {
    SCOPED_TRACE(inside ? "internal junction" : "entry");
    SceneConfig config;
    config.internal_junction_yield = true;
    FakeSumoWorld w;
    w.AddEdge("E", 0, 0, 100, 0, 1);
    w.AddLaneShape(":J_1", {{100, 0}, {108, 0}});   // 8 m to the internal junction
    w.AddLaneShape(":J_2", {{108, 0}, {112, 4}});
    w.AddEdge("F", 112, 4, 112, 100, 1);
    w.AddLinkVia("E_0", "F_0", ":J_1_0", "l", "m", /*has_foe=*/true);
    if (inside)
      w.AddLink(":J_1_0", ":J_2_0", "m");
    else
      w.AddLink(":J_1_0", "F_0", "M");
    w.AddVehicle("left", 95, 0, 90, 8, "E_0", 95, {"E", "F"});
    SceneStage stage(config, w.StepLength(), true, &w, &w);
    const SceneBatch b = stage.Run(Observe(w, {"left"}));
    ASSERT_TRUE(b.EgoOf(0).stop_line.has_value());
    EXPECT_NEAR(b.EgoOf(0).stop_line->distance_m, inside ? 5.0 + 8.0 : 5.0, 1e-9);
    // On by default; switched off, the line stays at the entry.
    SceneStage plain = Stage(w);
    const SceneBatch p = plain.Run(Observe(w, {"left"}));
    ASSERT_TRUE(p.EgoOf(0).stop_line.has_value());
    EXPECT_NEAR(p.EgoOf(0).stop_line->distance_m, inside ? 5.0 + 8.0 : 5.0, 1e-9);
    SceneConfig off;
    off.internal_junction_yield = false;
    SceneStage entry(off, w.StepLength(), true, &w, &w);
    const SceneBatch e = entry.Run(Observe(w, {"left"}));
    ASSERT_TRUE(e.EgoOf(0).stop_line.has_value());
    EXPECT_NEAR(e.EgoOf(0).stop_line->distance_m, 5.0, 1e-9);
  }
}

// --no-yield-stops: the yield line to an approaching foe goes; a red light and a stop sign stay.
TEST(SceneStage, WithoutYieldStopsOnlyLightsAndStopSignsAreStopLines) {
  SceneConfig config;
  config.yield_stops = false;
  FakeSumoWorld y;
  y.AddEdge("E", 0, 0, 100, 0, 1);
  y.AddEdge("F", 100, 0, 200, 0, 1);
  y.AddEdge("G", 0, 10, 100, 10, 1);
  y.AddEdge("H", 100, 10, 200, 10, 1);
  y.AddLink("E_0", "F_0", "m", /*has_foe=*/true);
  y.AddLink("G_0", "H_0", "s", /*has_foe=*/true);
  y.AddVehicle("minor", 85, 0, 90, 10, "E_0", 85, {"E", "F"});
  y.AddVehicle("stop_sign", 85, 10, 90, 10, "G_0", 85, {"G", "H"});
  y.AddVehicle("red", 50, 10, 90, 10, "G_0", 50, {"G", "H"});
  y.signals["red"] = SignalReport{30.0, 'r'};
  SceneStage stage(config, y.StepLength(), true, &y, &y);
  const SceneBatch b = stage.Run(Observe(y, {"minor", "red", "stop_sign"}));
  EXPECT_FALSE(b.EgoOf(0).stop_line.has_value());
  ASSERT_TRUE(b.EgoOf(1).stop_line.has_value());
  EXPECT_EQ(b.EgoOf(1).stop_line->reason, StopLine::Reason::kRedLight);
  ASSERT_TRUE(b.EgoOf(2).stop_line.has_value());
  EXPECT_EQ(b.EgoOf(2).stop_line->reason, StopLine::Reason::kYield);
}

// Params::release_unexplained_braking reads a vehicle's braking as having no cause only where
// the scene holds every cause it could have: not before a link without priority, where SUMO
// slows its vehicles to yield whether or not a foe approaches now.
TEST(SceneStage, BrakingCausesAreKnownExceptBeforeALinkWithoutPriority) {
  FakeSumoWorld w;
  w.AddEdge("E", 0, 0, 100, 0, 1);
  w.AddEdge("F", 100, 0, 200, 0, 1);
  w.AddEdge("G", 0, 10, 100, 10, 1);
  w.AddEdge("H", 100, 10, 200, 10, 1);
  w.AddLink("E_0", "F_0", "m", /*has_foe=*/false);
  w.AddLink("G_0", "H_0", "M", /*has_foe=*/false);
  w.AddVehicle("minor_near", 85, 0, 90, 10, "E_0", 85, {"E", "F"});
  w.AddVehicle("minor_far", 10, 0, 90, 10, "E_0", 10, {"E", "F"});
  w.AddVehicle("major_near", 85, 10, 90, 10, "G_0", 85, {"G", "H"});
  SceneConfig config;
  config.braking_causes = true;  // as --release-braking sets it
  SceneStage stage(config, w.StepLength(), true, &w, &w);
  const SceneBatch b = stage.Run(Observe(w, {"minor_near", "minor_far", "major_near"}));
  EXPECT_FALSE(b.EgoOf(0).state.braking_causes_known);  // 15 m from a minor link
  EXPECT_TRUE(b.EgoOf(1).state.braking_causes_known);   // the link is beyond its reach
  EXPECT_TRUE(b.EgoOf(2).state.braking_causes_known);   // a major link: nothing to yield to
  // Without the experiment nothing is read or said: the estimator's reference is unchanged.
  SceneStage plain = Stage(w);
  const SceneBatch q = plain.Run(Observe(w, {"minor_near", "minor_far", "major_near"}));
  for (size_t k = 0; k < 3; ++k) EXPECT_FALSE(q.EgoOf(k).state.braking_causes_known);
}

TEST(SceneStage, AFollowerExpectsToStopBehindALeaderThatMustStop) {
  FakeSumoWorld w;
  w.AddEdge("E", 0, 0, 200, 0, 1);
  // The leader at 8 m/s must stop at a red light 10 m ahead of its front; the follower at
  // 8 m/s, 4 m behind it (gap from SUMO), is expected to stop within 14 m: 64 / 28.
  w.AddVehicle("leader", 100, 0, 90, 8, "E_0", 100, {"E"});
  w.AddVehicle("follower", 91, 0, 90, 8, "E_0", 91, {"E"});
  w.signals["leader"] = SignalReport{10.0, 'r'};
  w.leaders["follower"] = LeaderReport{"leader", 4.0, 8.0, 0.0};
  SceneStage stage = Stage(w);
  const SceneBatch b = stage.Run(Observe(w, {"follower"}));
  const std::optional<double> a = b.scenes.at(0).ego.state.expected_accel_mps2;
  ASSERT_TRUE(a.has_value());
  EXPECT_NEAR(*a, -64.0 / 28.0, 1e-9);
  // Without the leader's obligation the follower at equal speed has nothing to react to.
  w.signals.clear();
  SceneStage plain = Stage(w);
  EXPECT_FALSE(plain.Run(Observe(w, {"follower"})).scenes.at(0).ego.state.expected_accel_mps2);
}

TEST(SceneStage, AWalkerKeepsToTheFootwayUnlessItsNextEdgeIsACrossing) {
  FakeSumoWorld w;
  w.AddEdge("E", 0, 0, 200, 0, 2);
  w.SetAllowed("E_0", {"pedestrian"});  // a sidewalk
  w.AddEdge(":J_c0", 200, -3, 200, 10, 1, 3.0, {"pedestrian"});  // a crossing
  w.AddEdge("S", 200, -2, 300, -2, 1, 2.0, {"pedestrian"});     // a sidewalk further on
  w.AddVehicle("ego", 100, 1.6, 90, 10, "E_1", 100, {"E"});
  w.AddPerson("strolls", 110, -1.6, 90, 1.2, "E_0", "S");
  w.AddPerson("crosses", 120, -1.6, 90, 1.2, "E_0", ":J_c0");
  w.AddPerson("ends_here", 130, -1.6, 90, 1.2, "E_0", "");
  SceneStage stage = Stage(w);
  const Scene s = stage.Run(Observe(w, {"ego"})).scenes.at(0);
  ASSERT_EQ(s.pedestrians.size(), 3u);  // ID order: crosses, ends_here, strolls
  EXPECT_FALSE(s.pedestrians[0].stays_on_footway);
  EXPECT_TRUE(s.pedestrians[1].stays_on_footway);
  EXPECT_TRUE(s.pedestrians[2].stays_on_footway);
  EXPECT_DOUBLE_EQ(s.pedestrians[0].length_m, Pedestrian{}.length_m);
}

TEST(SceneStage, AWalkerWaitingAtACrossingItMayNotEnterKeepsToTheFootway) {
  FakeSumoWorld w;
  w.AddEdge("E", 0, 0, 200, 0, 1);
  w.AddEdge(":J_w0", 195, -3, 198, -3, 1, 3.0, {"pedestrian"});  // a corner's walking area
  w.AddEdge(":J_c0", 200, -3, 200, 10, 1, 3.0, {"pedestrian"});  // its crossing
  w.AddEdge(":K_w0", 185, -3, 188, -3, 1, 3.0, {"pedestrian"});
  w.AddEdge(":K_c0", 190, -3, 190, 10, 1, 3.0, {"pedestrian"});
  w.AddEdge(":J_w1", 198, 12, 202, 12, 1, 3.0, {"pedestrian"});  // the crossing's other end
  w.AddLink(":J_w0_0", ":J_c0_0", "s", true);   // no priority, a vehicle approaches: waits
  w.AddLink(":J_c0_0", ":J_w1_0", "M", false);  // netconvert's link out of the crossing
  w.AddLink(":K_w0_0", ":K_c0_0", "M", true);   // a zebra: it may cross
  w.AddVehicle("ego", 150, 0, 90, 10, "E_0", 150, {"E"});
  w.AddPerson("waits", 196, -3, 0, 1.0, ":J_w0_0", ":J_c0");
  w.AddPerson("goes", 186, -3, 0, 1.0, ":K_w0_0", ":K_c0");
  // Walking the crossing against its links' direction it obeys the same link, as SUMO's do.
  w.AddPerson("waits_too", 200, 12, 180, 1.0, ":J_w1_0", ":J_c0");
  auto read = [&](SceneConfig config) {
    SceneStage stage(config, w.StepLength(), true, &w, &w);
    return stage.Run(Observe(w, {"ego"})).scenes.at(0);
  };
  const Scene s = read(SceneConfig{});
  ASSERT_EQ(s.pedestrians.size(), 3u);  // ID order: goes, waits, waits_too
  EXPECT_FALSE(s.pedestrians[0].stays_on_footway);
  EXPECT_TRUE(s.pedestrians[1].stays_on_footway);
  EXPECT_TRUE(s.pedestrians[2].stays_on_footway);
  // The waiting walker is expected to stop where its crossing begins, (200, -3), 4 m ahead:
  // 1 m/s within 4 m is 1 / 8 m/s^2. The one that may cross is not.
  ASSERT_TRUE(s.pedestrians[1].state.expected_accel_mps2.has_value());
  EXPECT_NEAR(*s.pedestrians[1].state.expected_accel_mps2, -1.0 / 8.0, 1e-9);
  EXPECT_FALSE(s.pedestrians[0].state.expected_accel_mps2.has_value());
  SceneConfig no_stops;
  no_stops.crossing_stops = false;  // --no-crossing-stops: waits, but no stop expected
  const Scene n = read(no_stops);
  EXPECT_TRUE(n.pedestrians[1].stays_on_footway);
  EXPECT_FALSE(n.pedestrians[1].state.expected_accel_mps2.has_value());
  SceneConfig off;
  off.crossing_obligations = false;  // --no-crossing-obligations: neither
  EXPECT_FALSE(read(off).pedestrians[1].stays_on_footway);
  EXPECT_FALSE(read(off).pedestrians[2].stays_on_footway);
  EXPECT_FALSE(read(off).pedestrians[1].state.expected_accel_mps2.has_value());
}

// A square right turn: N north to (0, 0), the internal lane (0, 0) -> (0, 5) -> (5, 5), E east
// from (5, 5). A 12 m bus 1 m into E stands along 1 m of E, the whole turn and 1 m of N: its
// back at (0, -1), so SUMO's angle (back to front) is 45 degrees across both lanes. An ego
// comes up N 20 m behind the junction.
void AddBusAcrossASquareTurn(FakeSumoWorld& w) {
  testing::AddSquareRightTurn(w);
  SumoObject& bus = w.AddVehicle("bus", 6, 5, 45, 4.0, "E_0", 1.0, {"N", "E"});
  bus.length_m = 12.0;
  bus.width_m = 2.5;
  bus.route_index = 1;
  bus.body_length_m = std::hypot(6.0, 6.0);  // SUMO's box, as the observe stage measures it
  w.AddVehicle("ego", 0, -20, 0, 5.0, "N_0", 80.0, {"N", "E"});
}

TEST(SceneStage, ABodyBentByATurnIsAChainOfBoxesAlongItsWay) {
  FakeSumoWorld w;
  AddBusAcrossASquareTurn(w);
  auto read = [&](SceneConfig config, const std::string& ego) {
    SceneStage stage(config, w.StepLength(), true, &w, &w);
    return stage.Run(Observe(w, {ego})).scenes.at(0);
  };
  SceneConfig chains;
  chains.bent_bodies = true;  // --bent-bodies
  const Scene s = read(chains, "ego");
  const Vehicle* b = VehicleIn(s, "bus");
  ASSERT_NE(b, nullptr);
  // Three 4 m boxes. The first points along its own part of the way, east along E and the turn's
  // last leg, not along SUMO's angle; the last stands on the turn's first leg, pointing north.
  EXPECT_DOUBLE_EQ(b->length_m, 4.0);
  EXPECT_NEAR(b->state.yaw_rad, 0.0, 1e-9);
  EXPECT_NEAR(b->state.x_m, 4.0, 1e-9);
  EXPECT_NEAR(b->state.y_m, 5.0, 1e-9);
  ASSERT_EQ(b->carriages.size(), 2u);
  EXPECT_DOUBLE_EQ(b->carriages[1].length_m, 4.0);
  EXPECT_NEAR(b->carriages[1].x_m, 0.0, 1e-9);  // its centre 10 m behind the front
  EXPECT_NEAR(b->carriages[1].y_m, 1.0, 1e-9);
  EXPECT_NEAR(b->carriages[1].yaw_rad, kPi / 2, 1e-9);
  // As an ego it is its first box (an ego's carriages are not modelled, as a train's).
  const Scene as_ego = read(chains, "bus");
  EXPECT_DOUBLE_EQ(as_ego.ego.length_m, 4.0);
  EXPECT_NEAR(as_ego.ego.state.yaw_rad, 0.0, 1e-9);
  EXPECT_TRUE(as_ego.ego.lanes.own.has_value());
  // By default: SUMO's box, front to back, centred between them, predicted as every box is.
  const Scene q = read(SceneConfig{}, "ego");
  EXPECT_FALSE(q.bodies_on_path);
  const Vehicle* qb = VehicleIn(q, "bus");
  ASSERT_NE(qb, nullptr);
  EXPECT_NEAR(qb->length_m, std::hypot(6.0, 6.0), 1e-9);
  EXPECT_NEAR(qb->state.x_m, 3.0, 1e-9);  // between the front (6, 5) and the back (0, -1)
  EXPECT_NEAR(qb->state.y_m, 2.0, 1e-9);
  EXPECT_NEAR(qb->state.yaw_rad, kPi / 4, 1e-9);
  EXPECT_TRUE(qb->carriages.empty());
  // With --no-sumo-box: one 12 m box along SUMO's angle, reaching back across both lanes.
  SceneConfig long_box;
  long_box.sumo_box = false;
  const Scene o = read(long_box, "ego");
  const Vehicle* ob = VehicleIn(o, "bus");
  ASSERT_NE(ob, nullptr);
  EXPECT_DOUBLE_EQ(ob->length_m, 12.0);
  EXPECT_NEAR(ob->state.yaw_rad, kPi / 4, 1e-9);
  EXPECT_NEAR(ob->state.x_m, 6.0 - 6.0 * std::sqrt(0.5), 1e-9);  // 6 m back from the front
  EXPECT_TRUE(ob->carriages.empty());
  EXPECT_FALSE(o.bodies_on_path);
  // With --bodies-on-path (even with --no-sumo-box): SUMO's box, and the scene says so (the
  // estimator predicts it as the chord of its path).
  SceneConfig on_path = long_box;
  on_path.bodies_on_path = true;
  const Scene p = read(on_path, "ego");
  EXPECT_TRUE(p.bodies_on_path);
  const Vehicle* pb = VehicleIn(p, "bus");
  ASSERT_NE(pb, nullptr);
  EXPECT_NEAR(pb->length_m, std::hypot(6.0, 6.0), 1e-9);
  EXPECT_NEAR(pb->state.x_m, 3.0, 1e-9);
  EXPECT_NEAR(pb->state.y_m, 2.0, 1e-9);
  EXPECT_NEAR(pb->state.yaw_rad, kPi / 4, 1e-9);
  EXPECT_TRUE(pb->carriages.empty());
  // Far into E the bus is straight: one 12 m box, whatever the switch.
  w.Find("bus")->x_m = 40.0;
  w.Find("bus")->angle_deg = 90.0;
  w.Find("bus")->lane_position_m = 35.0;
  w.Find("bus")->body_length_m = 12.0;
  const Vehicle* straight = VehicleIn(read(chains, "ego"), "bus");
  ASSERT_NE(straight, nullptr);
  EXPECT_DOUBLE_EQ(straight->length_m, 12.0);
  EXPECT_TRUE(straight->carriages.empty());
}

TEST(SceneStage, AVehicleWhoseBodyIsInAJunctionBringsItsWayThroughIt) {
  // The bus across the whole turn, its back on N at (0, -1). Its way (SceneConfig::
  // junction_ways) puts its front and back where SUMO has them, in its frame: its box (SUMO's,
  // front to back) from -c/2 to c/2.
  FakeSumoWorld w;
  AddBusAcrossASquareTurn(w);
  auto read = [&](SceneConfig config) {
    SceneStage stage(config, w.StepLength(), true, &w, &w);
    return stage.Run(Observe(w, {"ego"})).scenes.at(0);
  };
  const Scene s = read(SceneConfig{});
  const Vehicle* b = VehicleIn(s, "bus");
  ASSERT_NE(b, nullptr);
  ASSERT_TRUE(b->way.has_value());
  const Way& way = *b->way;
  EXPECT_NEAR(way.front_m - way.back_m, 12.0, 1e-9);  // SUMO's length along its lanes
  double heading = 0.0;
  const Point2 front = PointAlong(way.points, way.front_m, &heading);
  const Point2 back = PointAlong(way.points, way.back_m, &heading);
  const double half = 0.5 * std::hypot(6.0, 6.0);
  EXPECT_NEAR(front.x, half, 1e-9);
  EXPECT_NEAR(front.y, 0.0, 1e-9);
  EXPECT_NEAR(back.x, -half, 1e-9);
  EXPECT_NEAR(back.y, 0.0, 1e-9);
  // --no-junction-ways: none; far into E (out of the junction): none.
  SceneConfig off;
  off.junction_ways = false;
  EXPECT_FALSE(VehicleIn(read(off), "bus")->way.has_value());
  w.Find("bus")->x_m = 40.0;
  w.Find("bus")->angle_deg = 90.0;
  w.Find("bus")->lane_position_m = 35.0;
  w.Find("bus")->body_length_m = 12.0;
  EXPECT_FALSE(VehicleIn(read(SceneConfig{}), "bus")->way.has_value());
}

TEST(SceneStage, YawRateIsTheHeadingChangeOrWithLongStepsTheLanes) {
  FakeSumoWorld w(0.1);
  w.AddEdge("E", 0, 0, 300, 0, 1);
  w.AddVehicle("ego", 50, 0, 90, 10, "E_0", 50, {"E"});
  SceneStage stage = Stage(w);
  stage.Run(Observe(w, {"ego"}));
  w.Step();
  w.Find("ego")->angle_deg = 88.0;  // turned 2 degrees left within 0.1 s
  const Scene s = stage.Run(Observe(w, {"ego"})).scenes.at(0);
  EXPECT_NEAR(s.ego.state.yaw_rate_radps, (2.0 * kPi / 180.0) / 0.1, 1e-9);
  // With 1 s steps the stale heading change is replaced by the lane's: a straight lane, 0.
  FakeSumoWorld slow(1.0);
  slow.AddEdge("E", 0, 0, 300, 0, 1);
  slow.AddVehicle("ego", 50, 0, 90, 10, "E_0", 50, {"E"});
  SceneStage long_steps = Stage(slow);
  long_steps.Run(Observe(slow, {"ego"}));
  slow.Step();
  slow.Find("ego")->angle_deg = 70.0;
  EXPECT_NEAR(long_steps.Run(Observe(slow, {"ego"})).scenes.at(0).ego.state.yaw_rate_radps, 0.0,
              1e-12);
}

TEST(SceneStage, InvalidObjectsAreLeftOutCountedOncePerStepAndRangeIsExact) {
  FakeSumoWorld w;
  w.AddEdge("E", 0, 0, 300, 0, 1);
  w.AddVehicle("ego", 50, 0, 90, 10, "E_0", 50, {"E"});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  w.AddPerson("lost", nan, nan, nan, 1.0);
  // The ego's centre is at x = 47.5; 80 m on is 127.5: a front bumper at 130 puts the
  // centre at 127.5 (in range), 131 at 128.5 (out).
  w.AddVehicle("in", 130, 0, 90, 0, "E_0", 130, {"E"});
  w.AddVehicle("out", 131, 0.5, 90, 0, "", 0, {});
  SceneStage stage = Stage(w);
  const SceneBatch b = stage.Run(Observe(w, {"ego"}));
  ASSERT_EQ(b.scenes.size(), 1u);
  ASSERT_EQ(b.scenes[0].vehicles.size(), 1u);
  EXPECT_EQ(b.scenes[0].vehicles[0].id, "in");
  EXPECT_TRUE(b.scenes[0].pedestrians.empty());
  EXPECT_EQ(stage.invalid_objects(), 1);
  stage.Run(Observe(w, {"ego"}));
  EXPECT_EQ(stage.invalid_objects(), 2);
}

TEST(SceneStage, ScenesSayWhetherSumoMovesObjectsByItsEulerUpdate) {
  FakeSumoWorld w(0.5);
  w.AddEdge("E", 0, 0, 300, 0, 1);
  w.AddVehicle("ego", 50, 0, 90, 10, "E_0", 50, {"E"});
  SceneStage euler = Stage(w, true);
  SceneStage ballistic = Stage(w, false);
  EXPECT_DOUBLE_EQ(euler.Run(Observe(w, {"ego"})).scenes.at(0).euler_update_step_s, 0.5);
  EXPECT_DOUBLE_EQ(ballistic.Run(Observe(w, {"ego"})).scenes.at(0).euler_update_step_s, 0.0);
  // SUMO switched mid-run (a vehicle type with its own action step length was loaded).
  euler.SwitchToBallistic();
  EXPECT_DOUBLE_EQ(euler.Run(Observe(w, {"ego"})).scenes.at(0).euler_update_step_s, 0.0);
}

TEST(SceneStage, EgoCentreAndMathYawComeFromSumosFrontBumperAndNavigationAngle) {
  FakeSumoWorld w;
  w.AddEdge("N", 10, 0, 10, 300, 1);  // northbound
  w.AddVehicle("ego", 10, 100, 0, 10, "N_0", 100, {"N"});
  SceneStage stage = Stage(w);
  const Scene s = stage.Run(Observe(w, {"ego"})).scenes.at(0);
  EXPECT_NEAR(s.ego.state.x_m, 10.0, 1e-9);
  EXPECT_NEAR(s.ego.state.y_m, 97.5, 1e-9);  // half of 5 m behind the front
  EXPECT_NEAR(s.ego.state.yaw_rad, kPi / 2, 1e-12);
  // Its lane runs straight ahead in its own frame, though it is vertical in the world.
  ASSERT_TRUE(s.ego.lanes.own);
  EXPECT_NEAR(s.ego.lanes.own->left.points[2].y, 1.6, 1e-9);
}

TEST(SceneStage, AParkedVehicleIsNoEgoAndBesideTheRoadNoObject) {
  FakeSumoWorld w;
  w.AddEdge("E", 0, 0, 300, 0, 1);
  w.AddVehicle("ego", 50, 0, 90, 10, "E_0", 50, {"E"});
  // Parked in a parking area beside the lane (SUMO's stop state 2 + 128): 4 m off its centre.
  w.AddVehicle("beside", 70, -4.0, 90, 0, "E_0", 70, {"E"}).stop_state = 2 | 128;
  // Parked on the lane itself (a parking stop without a parking area): an obstacle.
  w.AddVehicle("on_lane", 90, 0.0, 90, 0, "E_0", 90, {"E"}).stop_state = 2;
  // Stopped at a bus stop: a standing object, and still an ego (it will pull out).
  w.AddVehicle("bus", 110, 0.0, 90, 0, "E_0", 110, {"E"}).stop_state = 1 | 16;
  w.AddVehicle("ship", 60, 30.0, 90, 3).vehicle_class = "ship";  // on a waterway nearby
  // Parked with parking="true": SUMO reports it on no lane (libsumo 1.15), beside the road.
  w.AddVehicle("taken_off", 80, -4.0, 90, 0).stop_state = 2;
  SceneStage stage = Stage(w);
  const SceneBatch b =
      stage.Run(Observe(w, {"ego", "beside", "on_lane", "bus", "ship", "taken_off"}));
  std::vector<std::string> egos;
  for (size_t k = 0; k < b.scenes.size(); ++k) egos.push_back(b.EgoOf(k).id);
  EXPECT_EQ(egos, (std::vector<std::string>{"ego", "bus"}));
  std::vector<std::string> objects;
  for (const Vehicle& v : b.scenes[0].vehicles) objects.push_back(v.id);
  EXPECT_EQ(objects, (std::vector<std::string>{"bus", "on_lane"}));
  EXPECT_EQ(stage.parked_objects(), 2);
  EXPECT_EQ(stage.other_class_objects(), 1);
  EXPECT_EQ(stage.parked_egos(), 3);
}

// "Off its lane" measures the parked vehicle from its lane position scaled onto the lane's shape
// (OnShape), as SUMO places it: on a lane whose shape is twice SUMO's length, a car parked on the
// lane at lane position 100 stands 200 m along the shape, on the lane, an obstacle.
TEST(SceneStage, AVehicleParkedOnALaneWhoseShapeIsLongerThanItsLengthIsOnIt) {
  FakeSumoWorld w;
  w.AddEdge("E", 0, 0, 300, 0, 1);
  w.SetLaneLength("E_0", 150.0);
  w.AddVehicle("ego", 150, 0, 90, 10, "E_0", 75, {"E"});
  w.AddVehicle("parked", 200, 0, 90, 0, "E_0", 100, {"E"}).stop_state = 2;
  SceneStage stage = Stage(w);
  const SceneBatch b = stage.Run(Observe(w, {"ego"}));
  std::vector<std::string> objects;
  for (const Vehicle& v : b.scenes.at(0).vehicles) objects.push_back(v.id);
  EXPECT_EQ(objects, (std::vector<std::string>{"parked"}));
  EXPECT_EQ(stage.parked_objects(), 0);
}

TEST(SceneStage, AHeadingJumpSumoCouldNotDriveIsReplacedByTheLanesYawRate) {
  FakeSumoWorld w(0.1);
  w.AddEdge("E", 0, 0, 300, 0, 1);
  w.AddVehicle("ego", 50, 0, 90, 5.8, "E_0", 50, {"E"});
  w.AddVehicle("other", 80, 0, 90, 5.8, "E_0", 80, {"E"});
  SceneStage stage = Stage(w);
  stage.Run(Observe(w, {"ego"}));
  w.Step();
  w.Find("other")->angle_deg = 90.0 - 27.0;  // 27 degrees in 0.1 s at 5.8 m/s: 4.7 rad/s
  w.Find("ego")->angle_deg = 90.0 - 1.0;    // 1 degree: 0.17 rad/s, a car can
  const Scene s = stage.Run(Observe(w, {"ego"})).scenes.at(0);
  ASSERT_EQ(s.vehicles.size(), 1u);
  EXPECT_NEAR(s.vehicles[0].state.yaw_rate_radps, 0.0, 1e-12);  // its straight lane's
  EXPECT_NEAR(s.ego.state.yaw_rate_radps, (kPi / 180.0) / 0.1, 1e-9);  // kept
  EXPECT_EQ(stage.conditioned_states(), 1);
}

// The heading "other" is read with after its SUMO angle (navigation degrees) was set to
// `angles` one 0.1 s step after another (12 m/s: grip allows 0.82 rad/s, 4.7 degrees a step);
// at read `teleported_at` SUMO reports that it was teleported.
std::vector<double> HeadingsRead(const SceneConfig& config, const std::vector<double>& angles,
                                 int teleported_at = -1) {
  FakeSumoWorld w(0.1);
  w.AddEdge("E", 0, 0, 300, 0, 2);
  w.AddVehicle("ego", 50, 0, 90, 12, "E_0", 50, {"E"});
  w.AddVehicle("other", 80, 0, 90, 12, "E_0", 80, {"E"});
  SceneStage stage(config, w.StepLength(), true, &w, &w);
  stage.Run(Observe(w, {"ego"}));
  std::vector<double> yaw;
  for (size_t k = 0; k < angles.size(); ++k) {
    w.Step();
    w.Find("other")->angle_deg = angles[k];
    Observation obs = Observe(w, {"ego"});
    if (static_cast<int>(k) == teleported_at) obs.teleported = {"other"};
    const Scene s = stage.Run(obs).scenes.at(0);
    const Vehicle* other = VehicleIn(s, "other");
    yaw.push_back(other ? other->state.yaw_rad * 180.0 / kPi : NAN);
  }
  return yaw;
}

TEST(SceneStage, AHeadingSumoTurnsFasterThanGripIsHeldForAtMostHalfASecond) {
  // After a lane change within one step SUMO's angle points from the back, still in the old
  // lane, to the front in the new one: 32 degrees for two steps, then back along the lane.
  const std::vector<double> glitch = {58, 58, 90, 90};
  SceneConfig config;  // SUMO's defaults: lanechange.duration 0
  std::vector<double> yaw = HeadingsRead(config, glitch);
  for (size_t k = 0; k < yaw.size(); ++k) EXPECT_NEAR(yaw[k], 0.0, 1e-9) << "step " << k;
  // A heading that stays is taken after 0.5 s (five steps held, the sixth SUMO's).
  yaw = HeadingsRead(config, {58, 58, 58, 58, 58, 58, 58});
  for (size_t k = 0; k < 5; ++k) EXPECT_NEAR(yaw[k], 0.0, 1e-9) << "step " << k;
  EXPECT_NEAR(yaw[5], 32.0, 1e-9);
  EXPECT_NEAR(yaw[6], 32.0, 1e-9);
  // A turn within grip is SUMO's at once.
  yaw = HeadingsRead(config, {87, 84});
  EXPECT_NEAR(yaw[0], 3.0, 1e-9);
  EXPECT_NEAR(yaw[1], 6.0, 1e-9);
  // Where SUMO moves lane-changing vehicles over time, a sudden heading on a normal lane is a
  // lane change starting: taken as it is. And --no-heading-hold takes every heading.
  config.instant_lane_changes = false;
  EXPECT_NEAR(HeadingsRead(config, glitch)[0], 32.0, 1e-9);
  config.instant_lane_changes = true;
  config.heading_hold = false;
  EXPECT_NEAR(HeadingsRead(config, glitch)[0], 32.0, 1e-9);
}

// A right turn into a two-lane road: N runs north to (0, 0), the turn's internal lane goes
// (0, 0) -> (0, 3.4) -> (5, 3.4) into E's lane 0 (y = 3.4; lane 1 at y = 6.6), E runs east from
// x = 5.
void AddRightTurnIntoTwoLanes(FakeSumoWorld& w) {
  w.AddEdge("N", 0, -100, 0, 0, 1);
  w.AddLaneShape(":J_0", {Point2{0, 0}, Point2{0, 3.4}, Point2{5, 3.4}});
  w.AddEdge("E", 5, 5, 105, 5, 2);
  w.AddLinkVia("N_0", "E_0", ":J_0_0", "r");
  w.AddLink(":J_0_0", "E_0");
}

// A 5 m car in that turn whose front is `position_m` into E on `lane`, with SUMO's angle
// `angle_deg`: the heading it is read with, in degrees.
double HeadingPastTheTurn(const SceneConfig& config, const std::string& lane, double position_m,
                          double angle_deg, double* centre_y = nullptr) {
  FakeSumoWorld w;
  AddRightTurnIntoTwoLanes(w);
  const double y = lane == "E_1" ? 6.6 : 3.4;
  SumoObject& car =
      w.AddVehicle("car", 5 + position_m, y, angle_deg, 8.0, lane, position_m, {"N", "E"});
  car.route_index = 1;
  SceneStage stage(config, w.StepLength(), true, &w, &w);
  const Scene s = stage.Run(Observe(w, {"car"})).scenes.at(0);
  if (centre_y) *centre_y = s.ego.state.y_m;
  return s.ego.state.yaw_rad * 180.0 / kPi;
}

// SceneConfig::junction_chord_heading (the default): a 5 m car in the right turn above, its
// front 5 m along
// the internal lane at (1.6, 3.4), its back 5 m behind along its lanes at (0, 0); SUMO's angle
// is its front piece's (east). By default it is read along the chord from its back to
// its front (64.8 degrees), its centre half its length behind the front along that; turned off,
// SUMO's angle. Catches a chord taken from the wrong length or lanes, a centre not moved with
// it, or the rule acting outside a junction.
TEST(SceneStage, InAJunctionTheChordOfItsLanesIsTheHeadingWithTheExperiment) {
  auto read = [](const SceneConfig& config, const std::string& lane, double position_m,
                 double x, double y, double angle_deg) {
    FakeSumoWorld w;
    AddRightTurnIntoTwoLanes(w);
    SumoObject& car = w.AddVehicle("car", x, y, angle_deg, 8.0, lane, position_m, {"N", "E"});
    car.route_index = lane[0] == ':' ? 0 : 1;
    SceneStage stage(config, w.StepLength(), true, &w, &w);
    return stage.Run(Observe(w, {"car"})).scenes.at(0).ego.state;
  };
  SceneConfig chord;
  EXPECT_TRUE(chord.junction_chord_heading);  // the default
  SceneConfig held;
  held.junction_chord_heading = false;
  const double expected = std::atan2(3.4, 1.6);
  const ObjectState on = read(chord, ":J_0_0", 5.0, 1.6, 3.4, 90.0);
  EXPECT_NEAR(on.yaw_rad, expected, 1e-9);
  EXPECT_NEAR(on.x_m, 1.6 - 2.5 * std::cos(expected), 1e-9);
  EXPECT_NEAR(on.y_m, 3.4 - 2.5 * std::sin(expected), 1e-9);
  const ObjectState off = read(held, ":J_0_0", 5.0, 1.6, 3.4, 90.0);
  EXPECT_NEAR(off.yaw_rad, 0.0, 1e-9);  // SUMO's angle: east
  // Out of the junction (front 20 m into E, back on it too): SUMO's angle either way.
  EXPECT_NEAR(read(chord, "E_0", 20.0, 25.0, 3.4, 80.0).yaw_rad, 10.0 * kPi / 180.0, 1e-9);
}

TEST(SceneStage, AfterALaneChangeJustPastAJunctionTheHeadingIsTheWayOfItsNewLane) {
  // The car came through the turn into E_0 and changed into E_1 within one step, 1 m into E:
  // SUMO's back stays on the turn 4 m before its end, at (1, 3.4), so SUMO's angle points from
  // there to the front at (6, 6.6): 32.6 degrees left of the road, 57.4 in navigation degrees.
  const double sumo = std::atan2(3.2, 5.0) * 180.0 / kPi;
  SceneConfig config;  // SUMO's defaults: lanechange.duration 0
  // SUMO's angle while the back is in the junction (the rule before junction_chord_heading,
  // which replaces it by default and is tested above).
  config.junction_chord_heading = false;
  double centre_y = 0.0;
  // Read along the turn moved onto E_1: its back at (1, 6.6), heading east, centred on E_1.
  EXPECT_NEAR(HeadingPastTheTurn(config, "E_1", 1.0, 90.0 - sumo, &centre_y), 0.0, 1e-9);
  EXPECT_NEAR(centre_y, 6.6, 1e-9);
  // Without a lane change SUMO's angle is taken, whatever it is (here 5 degrees left).
  EXPECT_NEAR(HeadingPastTheTurn(config, "E_0", 1.0, 85.0), 5.0, 1e-9);
  // Once the whole body is on E_1 its back has followed: SUMO's angle again.
  EXPECT_NEAR(HeadingPastTheTurn(config, "E_1", 6.0, 85.0), 5.0, 1e-9);
  // --no-way-heading takes SUMO's angle; so does a run where SUMO moves lane changes over time.
  SceneConfig off = config;
  off.way_heading = false;
  EXPECT_NEAR(HeadingPastTheTurn(off, "E_1", 1.0, 90.0 - sumo), sumo, 1e-9);
  SceneConfig gradual = config;
  gradual.instant_lane_changes = false;
  EXPECT_NEAR(HeadingPastTheTurn(gradual, "E_1", 1.0, 90.0 - sumo), sumo, 1e-9);
}

// A right turn whose internal lane is two straight pieces: north from (0, 0) to (0, 10), then
// east to (10, 10). A 5 m car at 6 m/s, its front 9.0 m and then, 0.1 s later, 9.6 m into the
// turn: both ends on the first piece, so SUMO's angle (back to front) is north at both reads.
// The yaw rate it is read with at the second read.
double YawRateEnteringACorner(const SceneConfig& config, double angle_deg) {
  FakeSumoWorld w(0.1);
  w.AddEdge("N", 0, -100, 0, 0, 1);
  w.AddLaneShape(":J_0", {Point2{0, 0}, Point2{0, 10}, Point2{10, 10}});
  w.AddEdge("E", 10, 10, 110, 10, 1);
  w.AddLinkVia("N_0", "E_0", ":J_0_0", "r");
  w.AddLink(":J_0_0", "E_0");
  w.AddVehicle("car", 0, 9.0, angle_deg, 6.0, ":J_0_0", 9.0, {"N", "E"});
  SceneStage stage(config, w.StepLength(), true, &w, &w);
  stage.Run(Observe(w, {"car"}));
  w.Step();
  SumoObject& car = *w.Find("car");
  car.x_m = 0.0;
  car.y_m = 9.6;
  car.lane_position_m = 9.6;
  car.angle_deg = angle_deg;
  return stage.Run(Observe(w, {"car"})).scenes.at(0).ego.state.yaw_rate_radps;
}

TEST(SceneStage, AtShortStepsAVehicleFollowingItsLanesTurnsAsItsHeadingAlongThemTurns) {
  // Its heading did not change since the last step, but 1.5 m on (a quarter second at 6 m/s)
  // its front has rounded the corner: from (0, 6.1) to (1.1, 10) the chord points right of
  // north, while 1.5 m back it pointed north. (SUMO's angle in the junction: without
  // junction_chord_heading, whose chord turns with the lanes itself.)
  SceneConfig config;
  config.junction_chord_heading = false;
  const double r = YawRateEnteringACorner(config, 0.0);
  const double turned = std::atan2(1.1, 3.9);  // radians, clockwise, over 3 m
  EXPECT_NEAR(r, -6.0 * turned / 3.0, 1e-9);
  EXPECT_LT(r, -0.5);
  // --no-lane-heading-yaw-rate takes the last step's change: none.
  config.lane_heading_yaw_rate = false;
  EXPECT_NEAR(YawRateEnteringACorner(config, 0.0), 0.0, 1e-12);
  // A heading off its lanes' (5 degrees: a sublane change) keeps the last step's change.
  config.lane_heading_yaw_rate = true;
  EXPECT_NEAR(YawRateEnteringACorner(config, 5.0), 0.0, 1e-12);
}

// A 5 m car at 8 m/s on lane 0 of a straight two-lane road E running east from x = 0, come
// straight on through a junction from W (a 10 m internal lane), read twice 0.1 s apart with
// its front `front_m` and then `front_m` + 0.8 m into E, SUMO's angle `first_deg` and then
// `second_deg` (navigation degrees; east is 90): the yaw rate it is read with at the second.
double YawRateAfterAHeadingStep(const SceneConfig& config, double first_deg, double second_deg,
                                double front_m = 1.0) {
  FakeSumoWorld w(0.1);
  w.AddEdge("W", -110, 0, -10, 0, 2);
  w.AddLaneShape(":J_0", {Point2{-10, -1.6}, Point2{0, -1.6}});
  w.AddEdge("E", 0, 0, 300, 0, 2);
  w.AddLinkVia("W_0", "E_0", ":J_0_0", "s");
  w.AddLink(":J_0_0", "E_0");
  SumoObject& car = w.AddVehicle("car", front_m, -1.6, first_deg, 8.0, "E_0", front_m, {"W", "E"});
  car.route_index = 1;
  SceneStage stage(config, w.StepLength(), true, &w, &w);
  stage.Run(Observe(w, {"car"}));
  w.Step();
  SumoObject& moved = *w.Find("car");
  moved.x_m = front_m + 0.8;
  moved.lane_position_m = front_m + 0.8;
  moved.angle_deg = second_deg;
  return stage.Run(Observe(w, {"car"})).scenes.at(0).ego.state.yaw_rate_radps;
}

// SceneConfig::lane_change_yaw_rate. Where SUMO moves vehicles sideways over time, its heading
// of a car whose back is still behind its lane's start jumps when such a move begins (the
// traced sublane-grid case: 9 degrees in one step, read as a turn into the counter lane); the
// car then turns as its lane does (here not at all), not at the jump's rate. Catches a rule
// that is ignored, one applied with SUMO's instant lane changes (where a heading change on a
// lane is the car's), one applied to headings beyond kSidewaysMaxAngleRad of the lane, one
// applied once the back is on the lane (SUMO's heading change is then the sideways motion's),
// and an option that does not turn it off.
TEST(SceneStage, ACarMovedSidewaysAlongItsLaneTurnsAsItsLaneNotAsItsHeadingJumped) {
  const double jump = (5.0 * kPi / 180.0) / 0.1;  // 5 degrees left in 0.1 s: within grip
  SceneConfig gradual;
  gradual.instant_lane_changes = false;
  gradual.junction_chord_heading = false;  // SUMO's angle while the back is in the junction
  EXPECT_NEAR(YawRateAfterAHeadingStep(gradual, 90.0, 85.0), 0.0, 1e-12);
  // Turned 25 degrees from its lane: not a sideways move along it; its heading's change.
  EXPECT_NEAR(YawRateAfterAHeadingStep(gradual, 70.0, 65.0), jump, 1e-9);
  // Its back on E (front 6 m into it): its heading's change.
  EXPECT_NEAR(YawRateAfterAHeadingStep(gradual, 90.0, 85.0, 6.0), jump, 1e-9);
  SceneConfig instant;  // SUMO's defaults: lanechange.duration 0
  instant.junction_chord_heading = false;
  EXPECT_NEAR(YawRateAfterAHeadingStep(instant, 90.0, 85.0), jump, 1e-9);
  gradual.lane_change_yaw_rate = false;
  EXPECT_NEAR(YawRateAfterAHeadingStep(gradual, 90.0, 85.0), jump, 1e-9);
}

TEST(SceneStage, ATeleportForgetsTheHeadingThatWouldBeHeld) {
  // 32 degrees in 0.1 s: held without the teleport (the test above), taken after it.
  EXPECT_NEAR(HeadingsRead(SceneConfig{}, {58}, /*teleported_at=*/0)[0], 32.0, 1e-9);
}

TEST(SceneStage, AnAccelerationBeyondTheTypesLimitsIsBoundedByThem) {
  FakeSumoWorld w;
  w.AddEdge("E", 0, 0, 300, 0, 1);
  SumoObject& ego = w.AddVehicle("ego", 50, 0, 90, 4, "E_0", 50, {"E"});
  ego.vehicle_type = "slow";
  ego.accel_mps2 = -60.0;  // a scripted speed drop within one step
  VehicleTypeReport slow;
  slow.emergency_decel_mps2 = 7.0;
  slow.accel_mps2 = 1.3;
  w.types["slow"] = slow;
  SceneStage stage = Stage(w);
  const Scene s = stage.Run(Observe(w, {"ego"})).scenes.at(0);
  EXPECT_DOUBLE_EQ(s.ego.state.accel_mps2, -7.0);
  EXPECT_EQ(stage.conditioned_states(), 1);
  EXPECT_EQ(s.ego.type.emergency_decel_mps2, 7.0);  // and the estimator gets the type
}

// SceneConfig::accel_window_s: SUMO's per-step accelerations, as its driver imperfection makes
// them at 0.1 s steps, read at each step with `window_s`; the ego's, then the car ahead's.
std::vector<double> AccelsRead(double step_s, double window_s, const std::vector<double>& sumo) {
  FakeSumoWorld w(step_s);
  w.AddEdge("E", 0, 0, 300, 0, 1);
  w.AddVehicle("ego", 50, 0, 90, 10, "E_0", 50, {"E"});
  SceneConfig config;
  config.accel_window_s = window_s;
  SceneStage stage(config, w.StepLength(), true, &w, &w);
  std::vector<double> read;
  for (std::size_t i = 0; i < sumo.size(); ++i) {
    if (i > 0) w.Step();
    w.Find("ego")->accel_mps2 = sumo[i];
    read.push_back(stage.Run(Observe(w, {"ego"})).scenes.at(0).ego.state.accel_mps2);
  }
  return read;
}

TEST(SceneStage, AnAccelerationWindowReadsTheSpeedChangeOverItsTime) {
  const std::vector<double> sumo{2.5, -4.5, 2.5, -4.5, 2.5, 2.5};
  // 0.4 s at 0.1 s steps: the mean of the reads of now and the 3 steps before.
  const std::vector<double> windowed = AccelsRead(0.1, 0.4, sumo);
  ASSERT_EQ(windowed.size(), sumo.size());
  EXPECT_NEAR(windowed[0], 2.5, 1e-12);  // one read so far
  EXPECT_NEAR(windowed[1], -1.0, 1e-12);
  EXPECT_NEAR(windowed[2], 0.5 / 3.0, 1e-12);
  EXPECT_NEAR(windowed[3], -1.0, 1e-12);
  EXPECT_NEAR(windowed[4], -1.0, 1e-12);  // the first read has left the window
  EXPECT_NEAR(windowed[5], 0.75, 1e-12);
  // Without a window, and at steps as long as the window, SUMO's of the last step.
  EXPECT_EQ(AccelsRead(0.1, 0.0, sumo), sumo);
  EXPECT_EQ(AccelsRead(0.5, 0.4, sumo), sumo);
}

TEST(SceneStage, AFollowerReadsItsLeadersAccelerationOverTheWindow) {
  // The leader 4 m ahead at the follower's speed, SUMO's acceleration +2.5 for three 0.1 s
  // steps and -4.5 in the last: over 0.4 s it speeds up (+0.75 m/s^2), so the follower has
  // nothing to react to; from the last step alone it brakes to a stop, and so must the follower.
  const auto expected = [](double window_s) {
    FakeSumoWorld w(0.1);
    w.AddEdge("E", 0, 0, 300, 0, 1);
    w.AddVehicle("lead", 100, 0, 90, 8, "E_0", 100, {"E"});
    w.AddVehicle("ego", 91, 0, 90, 8, "E_0", 91, {"E"});
    SceneConfig config;
    config.accel_window_s = window_s;
    SceneStage stage(config, w.StepLength(), true, &w, &w);
    std::optional<double> a;
    bool first = true;
    for (double sumo : {2.5, 2.5, 2.5, -4.5}) {
      if (!first) w.Step();
      first = false;
      w.Find("lead")->accel_mps2 = sumo;
      w.leaders["ego"] = LeaderReport{"lead", 4.0, 8.0, sumo};
      a = stage.Run(Observe(w, {"ego"})).scenes.at(0).ego.state.expected_accel_mps2;
    }
    return a;
  };
  EXPECT_FALSE(expected(0.4).has_value());
  ASSERT_TRUE(expected(0.0).has_value());
  EXPECT_LT(*expected(0.0), -1.0);
}

TEST(SceneStage, WithAllVehiclesOnlyTheEgoClassesAreEstimated) {
  FakeSumoWorld w;
  w.AddEdge("E", 0, 0, 300, 0, 1);
  w.AddVehicle("car", 50, 0, 90, 10, "E_0", 50, {"E"});
  w.AddVehicle("tram", 100, 0, 90, 10, "E_0", 100, {"E"}).vehicle_class = "tram";
  SceneConfig all;
  all.all_vehicles = true;
  SceneStage stage(all, w.StepLength(), true, &w, &w);
  SceneBatch b = stage.Run(Observe(w, {"car", "tram"}));
  ASSERT_EQ(b.scenes.size(), 1u);  // by default a tram is no ego
  EXPECT_EQ(b.EgoOf(0).id, "car");
  EXPECT_EQ(b.scenes[0].vehicles.at(0).type.road_user, RoadUser::kRail);  // but an object
  all.ego_classes = ParseEgoClasses("tram");
  SceneStage trams(all, w.StepLength(), true, &w, &w);
  b = trams.Run(Observe(w, {"car", "tram"}));
  ASSERT_EQ(b.scenes.size(), 1u);
  EXPECT_EQ(b.EgoOf(0).id, "tram");
}

TEST(SceneStage, ALongVehicleIsInTheSceneWhenACarriageIsInRange) {
  FakeSumoWorld w;
  w.AddEdge("D", -500, 0, 0, 0, 1);
  w.AddEdge("E", 0, 0, 500, 0, 1);
  w.AddLink("D_0", "E_0");
  // A 200 m train whose front is 150 m ahead of the ego's centre: its rear half is in range.
  SumoObject& train = w.AddVehicle("train", 150, 0, 90, 0, "E_0", 150, {"D", "E"});
  train.vehicle_class = "rail";
  train.length_m = 200.0;
  train.route_index = 1;
  w.AddVehicle("ego", 2.5, 20.0, 90, 0);  // off any lane, beside the track
  SceneStage stage = Stage(w);
  const Scene s = stage.Run(Observe(w, {"ego"})).scenes.at(0);
  ASSERT_EQ(s.vehicles.size(), 1u);
  const Vehicle& v = s.vehicles[0];
  EXPECT_LE(v.length_m, kMaxBoxLengthM);
  ASSERT_GE(v.carriages.size(), 9u);
  double body = v.length_m;
  for (const Carriage& c : v.carriages) body += 1.0 + c.length_m;
  EXPECT_NEAR(body, 200.0, 1e-6);
  EXPECT_NEAR(v.carriages.back().x_m, 150.0 - 200.0 + 0.5 * v.carriages.back().length_m, 1e-6);
}

}  // namespace
}  // namespace criticality::plugin
