// Scenes recorded from SUMO in scenarios/city_free (sumo-criticality --record-scenes), at the
// step where the estimator raised a false alarm before the rule named in each test existed.
// Each test checks that the rule removes the alarm and that without it the alarm is back, so
// it fails if the rule is lost or weakened, or if the scene no longer shows the problem.
#include <gtest/gtest.h>

#include <string>

#include "criticality/estimator.h"
#include "criticality/scene_io.h"

namespace criticality {
namespace {

Scene Recorded(const std::string& name) {
  return ReadSceneFile(std::string(CRIT_TEST_SCENE_DIR) + "/" + name);
}

double P(const Scene& scene, const Params& params) {
  return Estimator(params).Estimate(scene).p_collision;
}

const double kWarn = 0.9;  // sumo-criticality's default --warn-threshold

// car15 at 62.7 s, 8.5 m/s towards junction D3; ped20 walks diagonally over the corner's
// walking area to the sidewalk of car15's own street (SUMO's next edge: that sidewalk), its
// straight line cutting 1.6 m into car15's lane within 2 s. SUMO walks it along the kerb.
TEST(CityScenes, APedestrianRoundingACornerOnTheFootwayIsNoAlarm) {
  const Scene scene = Recorded("city_pedestrian_on_corner.scene");
  ASSERT_EQ(scene.pedestrians.size(), 1u);
  ASSERT_TRUE(scene.pedestrians[0].stays_on_footway);
  EXPECT_LT(P(scene, Params{}), 0.5);
  Params without;
  without.footway_pedestrians = false;
  EXPECT_GE(P(scene, without), kWarn);
  // A pedestrian about to cross (no footway flag) is still a threat.
  Scene crossing = scene;
  crossing.pedestrians[0].stays_on_footway = false;
  EXPECT_GE(P(crossing, Params{}), kWarn);
}

// car47 at 104.5 s turns right at 7.2 m/s through a turn of about 5.6 m (SUMO drives it at
// 9 m/s^2 of lateral acceleration) while accelerating at 2.5 m/s^2; car8 waits at the red light
// on the exit street's other lane, 1.4 m beside the turn's end.
TEST(CityScenes, ACarTooFastForItsTurnIsExpectedToBrakeForIt) {
  const Scene turning = Recorded("city_right_turn_too_fast.scene");
  const Scene waiting = Recorded("city_waiting_at_turn_exit.scene");
  ASSERT_EQ(turning.ego.id, "car47");
  ASSERT_EQ(waiting.ego.id, "car8");
  Params without;
  without.curve_speed_reference = false;
  // Seen from either car: the turning car's reference keeps accelerating, cannot hold the turn
  // and leaves it wide into car8; braking for the turn it stays in it.
  EXPECT_GE(P(turning, without), kWarn);
  EXPECT_GE(P(waiting, without), kWarn);
  EXPECT_LT(P(turning, Params{}), 0.5);
  EXPECT_LT(P(waiting, Params{}), 0.5);
}

}  // namespace
}  // namespace criticality
