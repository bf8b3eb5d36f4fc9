// Scene files: what --record-scenes writes, criticality-bench --scene-file reads back exactly.
#include "criticality/scene_io.h"

#include <gtest/gtest.h>

#include <sstream>

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
  EXPECT_NE(error("criticality-scene 1\npedestrian p 0 0 0 1 0 0 0 .5 .5\nexpected-accel -1\n")
                .find("f.scene:3: 'expected-accel' must follow"),
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
