// Scene files: what --record-scenes writes, criticality-bench --scene-file reads back exactly.
#include "criticality/scene_io.h"

#include <gtest/gtest.h>

#include <sstream>

#include "bench/paper_scenes.h"
#include "criticality/errors.h"
#include "criticality/estimator.h"
#include "test_scenes.h"

namespace criticality {
namespace {

TEST(SceneIo, RoundTripGivesTheSameEstimate) {
  for (unsigned seed : {3u, 4u, 21u}) {
    const Scene scene = testing::RandomScene(seed, 4, 2, true);
    std::stringstream file;
    WriteScene(file, scene);
    const Scene back = ReadScene(file);
    ASSERT_EQ(back.vehicles.size(), scene.vehicles.size());
    ASSERT_EQ(back.pedestrians.size(), scene.pedestrians.size());
    Estimator a(Params{}), b(Params{});
    EXPECT_EQ(a.Estimate(scene).p_collision, b.Estimate(back).p_collision) << seed;
    std::stringstream again;
    WriteScene(again, back);
    EXPECT_EQ(again.str(), file.str()) << seed;
  }
}

TEST(SceneIo, ExpectedAccelerationsRoundTrip) {
  Scene scene = testing::RandomScene(5, 3, 1, true);
  scene.ego.state.expected_accel_mps2 = -2.25;
  scene.vehicles[1].state.expected_accel_mps2 = -4.5;
  std::stringstream file;
  WriteScene(file, scene);
  const Scene back = ReadScene(file);
  ASSERT_EQ(back.vehicles.size(), 3u);
  EXPECT_EQ(back.ego.state.expected_accel_mps2, std::optional<double>(-2.25));
  EXPECT_FALSE(back.vehicles[0].state.expected_accel_mps2.has_value());
  EXPECT_EQ(back.vehicles[1].state.expected_accel_mps2, std::optional<double>(-4.5));
  EXPECT_FALSE(back.vehicles[2].state.expected_accel_mps2.has_value());
  EXPECT_EQ(back.vehicles[1].lanes.has_value(), scene.vehicles[1].lanes.has_value());
  // A pedestrian's (a person stopping where it must wait), after its footway flag's peer.
  Pedestrian walker;
  walker.id = "w";
  walker.state.speed_mps = 1.2;
  walker.state.expected_accel_mps2 = -2.4;
  walker.stays_on_footway = true;
  Pedestrian standing;
  standing.id = "s";
  scene.pedestrians = {walker, standing};
  std::stringstream again;
  WriteScene(again, scene);
  const Scene peds = ReadScene(again);
  ASSERT_EQ(peds.pedestrians.size(), 2u);
  EXPECT_EQ(peds.pedestrians[0].state.expected_accel_mps2, std::optional<double>(-2.4));
  EXPECT_TRUE(peds.pedestrians[0].stays_on_footway);
  EXPECT_FALSE(peds.pedestrians[1].state.expected_accel_mps2.has_value());
}

TEST(SceneIo, FootwayFlagsRoundTrip) {
  Scene scene = testing::RandomScene(6, 1, 0, true);
  for (int i = 0; i < 3; ++i) {
    Pedestrian p;
    p.id = "p" + std::to_string(i);
    p.state.x_m = 5.0 + i;
    p.stays_on_footway = i == 1;
    scene.pedestrians.push_back(p);
  }
  std::stringstream file;
  WriteScene(file, scene);
  const Scene back = ReadScene(file);
  ASSERT_EQ(back.pedestrians.size(), 3u);
  EXPECT_FALSE(back.pedestrians[0].stays_on_footway);
  EXPECT_TRUE(back.pedestrians[1].stays_on_footway);
  EXPECT_FALSE(back.pedestrians[2].stays_on_footway);
}

TEST(SceneIo, RouteEndsRoundTrip) {
  Scene scene = testing::RandomScene(6, 0, 0, true);
  scene.vehicles.resize(2);
  scene.vehicles[0].id = "a";
  scene.vehicles[1].id = "b";
  scene.vehicles[1].state.x_m = 10.0;
  scene.ego.state.route_end_m = 12.5;
  scene.vehicles[1].state.route_end_m = 0.0;
  std::stringstream file;
  WriteScene(file, scene);
  const Scene back = ReadScene(file);
  EXPECT_EQ(back.ego.state.route_end_m, std::optional<double>(12.5));
  EXPECT_FALSE(back.vehicles[0].state.route_end_m.has_value());
  EXPECT_EQ(back.vehicles[1].state.route_end_m, std::optional<double>(0.0));
  std::istringstream bad("criticality-scene 1\npedestrian p 0 0 0 1 0 0 0 .5 .5\nroute-end 3\n");
  EXPECT_THROW(ReadScene(bad), InputError);
}

TEST(SceneIo, BrakingCausesKnownRoundTrips) {
  Scene scene = testing::RandomScene(6, 0, 0, true);
  scene.vehicles.resize(2);
  scene.vehicles[0].id = "a";
  scene.vehicles[1].id = "b";
  scene.vehicles[1].state.x_m = 10.0;
  scene.ego.state.braking_causes_known = true;
  scene.vehicles[1].state.braking_causes_known = true;
  std::stringstream file;
  WriteScene(file, scene);
  const Scene back = ReadScene(file);
  EXPECT_TRUE(back.ego.state.braking_causes_known);
  EXPECT_FALSE(back.vehicles[0].state.braking_causes_known);
  EXPECT_TRUE(back.vehicles[1].state.braking_causes_known);
  std::istringstream bad(
      "criticality-scene 1\npedestrian p 0 0 0 1 0 0 0 .5 .5\nbraking-causes-known\n");
  EXPECT_THROW(ReadScene(bad), InputError);
}

TEST(SceneIo, TheEgosStopLineRoundTrips) {
  Scene scene = testing::RandomScene(6, 1, 0, true);
  scene.ego.stop_line = StopLine{StopLine::Reason::kYield, 8.5};
  for (Vehicle& v : scene.vehicles) v.stop_line.reset();
  std::stringstream file;
  WriteScene(file, scene);
  const Scene back = ReadScene(file);
  ASSERT_TRUE(back.ego.stop_line.has_value());
  EXPECT_EQ(back.ego.stop_line->reason, StopLine::Reason::kYield);
  EXPECT_EQ(back.ego.stop_line->distance_m, 8.5);
  for (const Vehicle& v : back.vehicles) EXPECT_FALSE(v.stop_line.has_value());
  std::istringstream bad("criticality-scene 1\nego e 0 0 0 1 0 0 0 4 2 -\n"
                         "pedestrian p 0 0 0 1 0 0 0 .5 .5\nstop yield 3\n");
  EXPECT_THROW(ReadScene(bad), InputError);
}

TEST(SceneIo, EulerUpdateStepRoundTrips) {
  Scene scene = testing::RandomScene(6, 1, 0, true);
  scene.euler_update_step_s = 0.25;
  std::stringstream file;
  WriteScene(file, scene);
  EXPECT_EQ(ReadScene(file).euler_update_step_s, 0.25);
  scene.euler_update_step_s = 0.0;  // continuous: no line, read back as 0
  std::stringstream plain;
  WriteScene(plain, scene);
  EXPECT_EQ(plain.str().find("euler-update-step"), std::string::npos);
  EXPECT_EQ(ReadScene(plain).euler_update_step_s, 0.0);
}

TEST(SceneIo, StraightToMiddleRoundTrips) {
  Scene scene = testing::RandomScene(6, 1, 0, true);
  scene.ego.lanes = bench::StraightThreeLanes();
  scene.ego.lanes.own->straight_to_middle = true;
  std::stringstream file;
  WriteScene(file, scene);
  const Scene back = ReadScene(file);
  ASSERT_TRUE(back.ego.lanes.own && back.ego.lanes.left);
  EXPECT_TRUE(back.ego.lanes.own->straight_to_middle);
  EXPECT_FALSE(back.ego.lanes.left->straight_to_middle);
  std::istringstream bad(
      "criticality-scene 1\nego e 0 0 0 1 0 0 0 4.5 1.8 -\n"
      "lane own 0 0 1 10 1 20 1 0 -1 10 -1 20 -1 curvy\n");
  try {
    ReadScene(bad, "f.scene");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("f.scene:3: lane shape 'curvy'"), std::string::npos)
        << e.what();
  }
}

// Catches a corner that is not written, not read back (or read as another number), a reader
// that accepts a corner of no length, and one that stops after the first shape word.
TEST(SceneIo, CornerRoundTrips) {
  Scene scene = testing::RandomScene(6, 1, 0, true);
  scene.ego.lanes = bench::StraightThreeLanes();
  scene.ego.lanes.own->corner_tangent_m = 6.25;
  scene.ego.lanes.own->straight_to_middle = true;
  std::stringstream file;
  WriteScene(file, scene);
  const Scene back = ReadScene(file);
  ASSERT_TRUE(back.ego.lanes.own && back.ego.lanes.left);
  EXPECT_EQ(back.ego.lanes.own->corner_tangent_m, 6.25);
  EXPECT_TRUE(back.ego.lanes.own->straight_to_middle);
  EXPECT_EQ(back.ego.lanes.left->corner_tangent_m, 0.0);
  std::istringstream bad(
      "criticality-scene 1\nego e 0 0 0 1 0 0 0 4.5 1.8 -\n"
      "lane own 0 0 1 10 1 20 1 0 -1 10 -1 20 -1 corner 0\n");
  try {
    ReadScene(bad, "f.scene");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("f.scene:3: corner tangent length"), std::string::npos)
        << e.what();
  }
}

TEST(SceneIo, TypesAndCarriagesRoundTrip) {
  Scene scene = testing::RandomScene(5, 3, 1, true);
  ASSERT_EQ(scene.vehicles.size(), 3u);
  scene.ego.type.road_user = RoadUser::kHeavy;
  scene.ego.type.mass_kg = 18000.0;
  scene.ego.type.emergency_decel_mps2 = 5.5;
  Vehicle& tram = scene.vehicles[0];
  tram.type.road_user = RoadUser::kRail;
  tram.type.accel_mps2 = 1.1;
  tram.type.decel_mps2 = 1.3;
  tram.type.max_speed_mps = 70.0 / 3.6;
  for (int k = 0; k < 3; ++k) {
    Carriage c;
    c.x_m = tram.state.x_m - 20.0 * (k + 1);
    c.y_m = tram.state.y_m + 0.1 * k;
    c.yaw_rad = 0.01 * k;
    c.yaw_rate_radps = -0.02 * k;
    c.length_m = 19.0 + k;
    c.width_m = 2.65;
    if (k == 1) c.lanes = bench::StraightThreeLanes();
    tram.carriages.push_back(c);
  }
  scene.vehicles[2].type.road_user = RoadUser::kBicycle;  // a class without values
  std::stringstream file;
  WriteScene(file, scene);
  const Scene back = ReadScene(file);
  ASSERT_EQ(back.vehicles.size(), 3u);
  EXPECT_EQ(back.ego.type.road_user, RoadUser::kHeavy);
  EXPECT_EQ(back.ego.type.mass_kg, std::optional<double>(18000.0));
  EXPECT_EQ(back.ego.type.emergency_decel_mps2, std::optional<double>(5.5));
  EXPECT_FALSE(back.ego.type.accel_mps2.has_value());
  const Vehicle& t = back.vehicles[0];
  EXPECT_EQ(t.type.road_user, RoadUser::kRail);
  EXPECT_EQ(t.type.accel_mps2, std::optional<double>(1.1));
  EXPECT_EQ(t.type.decel_mps2, std::optional<double>(1.3));
  EXPECT_EQ(t.type.max_speed_mps, tram.type.max_speed_mps);  // 17 digits: exactly
  EXPECT_FALSE(t.type.mass_kg.has_value());
  ASSERT_EQ(t.carriages.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(t.carriages[k].x_m, tram.carriages[k].x_m) << k;
    EXPECT_EQ(t.carriages[k].y_m, tram.carriages[k].y_m) << k;
    EXPECT_EQ(t.carriages[k].yaw_rad, tram.carriages[k].yaw_rad) << k;
    EXPECT_EQ(t.carriages[k].yaw_rate_radps, tram.carriages[k].yaw_rate_radps) << k;
    EXPECT_EQ(t.carriages[k].length_m, tram.carriages[k].length_m) << k;
    EXPECT_EQ(t.carriages[k].width_m, tram.carriages[k].width_m) << k;
    EXPECT_EQ(t.carriages[k].lanes.has_value(), k == 1) << k;
  }
  ASSERT_TRUE(t.carriages[1].lanes && t.carriages[1].lanes->left);
  EXPECT_EQ(t.carriages[1].lanes->left->left.points[2].y,
            tram.carriages[1].lanes->left->left.points[2].y);
  // The vehicle's own lanes stayed its own (the carriage's lane lines did not go to it).
  EXPECT_EQ(t.lanes.has_value(), tram.lanes.has_value());
  EXPECT_EQ(back.vehicles[1].type.road_user, RoadUser::kCar);
  EXPECT_TRUE(back.vehicles[1].carriages.empty());
  EXPECT_EQ(back.vehicles[2].type.road_user, RoadUser::kBicycle);
  // The same estimate, and the same text once more.
  EXPECT_EQ(Estimator(Params{}).Estimate(scene).p_collision,
            Estimator(Params{}).Estimate(back).p_collision);
  std::stringstream again;
  WriteScene(again, back);
  EXPECT_EQ(again.str(), file.str());
}

TEST(SceneIo, FilesWithoutTypesReadAsCarsAndUntypedScenesWriteNoTypeLines) {
  // A file from before types and carriages: every vehicle a car with no values.
  std::istringstream old(
      "criticality-scene 1\nego e 0 0 0 10 0 0 0 4.5 1.8 -\n"
      "vehicle v 20 0 0 8 0 0 0 4.5 1.8 - 0\n");
  const Scene scene = ReadScene(old);
  ASSERT_EQ(scene.vehicles.size(), 1u);
  EXPECT_EQ(scene.vehicles[0].type.road_user, RoadUser::kCar);
  EXPECT_FALSE(scene.vehicles[0].type.accel_mps2.has_value());
  EXPECT_TRUE(scene.vehicles[0].carriages.empty());
  std::stringstream file;
  WriteScene(file, testing::RandomScene(7, 4, 2, false));
  EXPECT_EQ(file.str().find("\ntype "), std::string::npos);
  EXPECT_EQ(file.str().find("\ncarriage "), std::string::npos);
}

TEST(SceneIo, BadTypeAndCarriageLinesNameTheLine) {
  auto error = [](const std::string& text) {
    std::istringstream in(text);
    try {
      ReadScene(in, "f.scene");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string head = "criticality-scene 1\nego e 0 0 0 1 0 0 0 4.5 1.8 -\n";
  EXPECT_NE(error(head + "type tractor\n").find("f.scene:3: road user 'tractor'"),
            std::string::npos);
  EXPECT_NE(error(head + "type heavy weight 3\n").find("f.scene:3: type value 'weight'"),
            std::string::npos);
  EXPECT_NE(error(head + "carriage 0 0 0 0 10 2.5 0\n").find("f.scene:3: 'carriage' must follow"),
            std::string::npos);
  EXPECT_NE(error(head + "pedestrian p 0 0 0 1 0 0 0 .5 .5\ntype car\n")
                .find("f.scene:4: 'type' must follow"),
            std::string::npos);
  EXPECT_NE(error(head + "vehicle v 9 0 0 1 0 0 0 4.5 1.8 - 0\ncarriage 0 0 0 0 10 2.5 0\n"
                         "lane own 0 0 1 10 1 20 1 0 -1 10 -1 20 -1\n")
                .find("f.scene:5: 'lane' must follow"),
            std::string::npos);
}

TEST(SceneIo, BadFilesNameTheLine) {
  auto error = [](const std::string& text) {
    std::istringstream in(text);
    try {
      ReadScene(in, "f.scene");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error("hello\n").find("f.scene:1"), std::string::npos);
  EXPECT_NE(error("criticality-scene 1\n").find("no 'ego'"), std::string::npos);
  EXPECT_NE(error("criticality-scene 1\nego e 0 0 0 x 0 0 0 4 2 -\n").find("f.scene:2: 'x'"),
            std::string::npos);
  EXPECT_NE(error("criticality-scene 1\npedestrian p 0 0 0 1 0 0 0 .5 .5\nlane own 0 0 0 1 0 2 0 0 "
                  "1 1 1 2 1\n")
                .find("f.scene:3"),
            std::string::npos);
  // A pedestrian may have an expected acceleration (a person stopping where it must wait),
  // not a route end; before any object neither has anything to follow.
  EXPECT_NE(error("criticality-scene 1\nexpected-accel -1\n")
                .find("f.scene:2: 'expected-accel' must follow"),
            std::string::npos);
  EXPECT_NE(error("criticality-scene 1\npedestrian p 0 0 0 1 0 0 0 .5 .5\nroute-end 3\n")
                .find("f.scene:3: 'route-end' must follow"),
            std::string::npos);
  EXPECT_NE(error("criticality-scene 1\nego e 0 0 0 1 0 0 0 4.5 1.8 -\nfootway\n")
                .find("f.scene:3: 'footway' must follow a pedestrian"),
            std::string::npos);
  EXPECT_NE(error("criticality-scene 1\npedestrian p 0 0 0 1 0 0 0 .5 .5\n"
                  "vehicle v 9 0 0 1 0 0 0 4.5 1.8 - 0\nfootway\n")
                .find("f.scene:4: 'footway' must follow a pedestrian"),
            std::string::npos);
  EXPECT_THROW(ReadSceneFile("/nonexistent.scene"), InputError);
}

}  // namespace
}  // namespace criticality
