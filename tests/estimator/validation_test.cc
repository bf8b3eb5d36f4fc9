// Bad input: every invalid scene or parameter gives an exception naming the field and value.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "bench/paper_scenes.h"
#include "criticality/errors.h"
#include "criticality/estimator.h"

namespace criticality {
namespace {

// Runs an estimate that must throw E; returns its message.
template <typename E>
std::string EstimateError(const Scene& scene, const Params& params = {}) {
  try {
    Estimator estimator(params);
    estimator.Estimate(scene);
  } catch (const E& e) {
    return e.what();
  }
  ADD_FAILURE() << "no exception";
  return "";
}

// The message names the field and its value as "FIELD = VALUE" (a value found anywhere else,
// such as the "0" of "must be > 0", does not count).
void ExpectMentions(const std::string& msg, const std::string& field, const std::string& value) {
  EXPECT_NE(msg.find(field + " = " + value), std::string::npos) << msg;
}

// The message names the field and, after it, what is wrong with it.
void ExpectNamesProblem(const std::string& msg, const std::string& field,
                        const std::string& problem) {
  const size_t at = msg.find(field);
  ASSERT_NE(at, std::string::npos) << msg;
  EXPECT_NE(msg.find(problem, at + field.size()), std::string::npos) << msg;
}

TEST(Validation, NanAndInfiniteStates) {
  Scene s = bench::PaperSceneS1();
  s.vehicles[1].state.speed_mps = std::nan("");
  ExpectMentions(EstimateError<InputError>(s), "scene.vehicles[1] ('left').state.speed_mps", "nan");
  s = bench::PaperSceneS1();
  s.ego.state.x_m = std::numeric_limits<double>::infinity();
  ExpectMentions(EstimateError<InputError>(s), "scene.ego.state.x_m", "inf");
}

TEST(Validation, EulerUpdateStepMustBeInRange) {
  Scene scene = bench::PaperSceneS1();
  const std::vector<std::pair<double, std::string>> bad{
      {-0.1, "-0.1"}, {11.0, "11"}, {std::numeric_limits<double>::quiet_NaN(), "nan"}};
  for (const auto& [value, text] : bad) {
    scene.euler_update_step_s = value;
    ExpectMentions(EstimateError<InputError>(scene), "scene.euler_update_step_s", text);
  }
  scene.euler_update_step_s = 1.0;  // SUMO's default step
  EXPECT_NO_THROW(Estimator(Params{}).Estimate(scene));
}

TEST(Validation, NegativeSizesAndSpeeds) {
  Scene s = bench::PaperSceneS1();
  s.vehicles[0].length_m = -4.0;
  ExpectMentions(EstimateError<InputError>(s), "scene.vehicles[0] ('lead').length_m", "-4");
  s = bench::PaperSceneS1();
  s.ego.width_m = 0.0;
  ExpectMentions(EstimateError<InputError>(s), "scene.ego.width_m", "0");
  s = bench::PaperSceneS1();
  Pedestrian p;
  p.state.speed_mps = -1.0;
  s.pedestrians.push_back(p);
  ExpectMentions(EstimateError<InputError>(s), "scene.pedestrians[0].state.speed_mps", "-1");
}

TEST(Validation, ALongVehicleOfOneBoxIsAcceptedUpTo400Metres) {
  Scene s = bench::PaperSceneS1();
  s.vehicles[1].length_m = 135.0;  // a city train as one box (the first failure)
  s.vehicles[1].width_m = 2.65;
  EXPECT_NO_THROW(Estimator(Params{}).Estimate(s));
  s.ego.length_m = 135.0;  // and as the ego
  EXPECT_NO_THROW(Estimator(Params{}).Estimate(s));
  s = bench::PaperSceneS1();
  s.vehicles[2].id = "train7";
  s.vehicles[2].length_m = 401.0;
  const std::string msg = EstimateError<InputError>(s);
  EXPECT_NE(msg.find("scene.vehicles[2] ('train7').length_m = 401: must be <= 400 m"),
            std::string::npos)
      << msg;
}

TEST(Validation, ErrorsNameTheObjectByIndexAndId) {
  Scene s = bench::PaperSceneS1();
  s.vehicles[0].width_m = 5.5;
  ExpectMentions(EstimateError<InputError>(s), "scene.vehicles[0] ('lead').width_m", "5.5");
  s = bench::PaperSceneS1();
  s.vehicles[0].id.clear();  // no id: the index alone
  s.vehicles[0].width_m = 5.5;
  ExpectMentions(EstimateError<InputError>(s), "scene.vehicles[0].width_m", "5.5");
  s = bench::PaperSceneS1();
  Pedestrian p;
  p.id = "walker";
  p.state.speed_mps = std::nan("");
  s.pedestrians.push_back(p);
  ExpectMentions(EstimateError<InputError>(s), "scene.pedestrians[0] ('walker').state.speed_mps",
                 "nan");
}

TEST(Validation, CarriagesAreCheckedBoxByBox) {
  auto with_carriages = [](int n) {
    Scene s = bench::PaperSceneS1();
    s.vehicles[0].id = "tram3";
    for (int k = 0; k < n; ++k) {
      Carriage c;
      c.x_m = s.vehicles[0].state.x_m - 10.0 * (k + 1);
      s.vehicles[0].carriages.push_back(c);
    }
    return s;
  };
  EXPECT_NO_THROW(Estimator(Params{}).Estimate(with_carriages(kMaxCarriages)));
  ExpectMentions(EstimateError<InputError>(with_carriages(kMaxCarriages + 1)),
                 "scene.vehicles[0] ('tram3').carriages (count)", "65");
  Scene s = with_carriages(3);
  s.vehicles[0].carriages[1].length_m = 401.0;
  ExpectMentions(EstimateError<InputError>(s), "scene.vehicles[0] ('tram3').carriages[1].length_m",
                 "401");
  s = with_carriages(3);
  s.vehicles[0].carriages[2].yaw_rad = std::numeric_limits<double>::infinity();
  ExpectMentions(EstimateError<InputError>(s), "scene.vehicles[0] ('tram3').carriages[2].yaw_rad",
                 "inf");
  s = with_carriages(3);
  s.vehicles[0].carriages[0].y_m = std::nan("");
  ExpectMentions(EstimateError<InputError>(s), "scene.vehicles[0] ('tram3').carriages[0].y_m",
                 "nan");
  s = with_carriages(1);
  s.vehicles[0].carriages[0].lanes = bench::StraightThreeLanes();
  s.vehicles[0].carriages[0].lanes->own->left.points[1].x = 0.0;  // repeated x
  ExpectNamesProblem(EstimateError<InputError>(s),
                     "scene.vehicles[0] ('tram3').carriages[0].lanes.own.left", "distinct x");
}

TEST(Validation, VehicleTypeValuesMustBePositive) {
  Scene s = bench::PaperSceneS1();
  s.vehicles[1].type.emergency_decel_mps2 = -3.0;
  ExpectMentions(EstimateError<InputError>(s),
                 "scene.vehicles[1] ('left').type.emergency_decel_mps2", "-3");
  s = bench::PaperSceneS1();
  s.ego.type.max_speed_mps = 0.0;
  ExpectMentions(EstimateError<InputError>(s), "scene.ego.type.max_speed_mps", "0");
  s = bench::PaperSceneS1();
  s.vehicles[2].type.road_user = static_cast<RoadUser>(9);
  ExpectMentions(EstimateError<InputError>(s), "scene.vehicles[2] ('right-behind').type.road_user",
                 "9");
  Params p;
  p.heavy.emergency_decel_mps2 = 0.0;
  EXPECT_THROW(ValidateParams(p), InputError);
}

TEST(Validation, DegenerateLanePoints) {
  Scene s = bench::PaperSceneS1();
  s.ego.lanes.right->right.points[2] = s.ego.lanes.right->right.points[1];
  ExpectNamesProblem(EstimateError<InputError>(s), "scene.ego.lanes.right.right", "distinct x");
  s = bench::PaperSceneS1();
  s.vehicles[2].lanes->own->left.points[0].y = std::nan("");
  ExpectMentions(EstimateError<InputError>(s),
                 "scene.vehicles[2] ('right-behind').lanes.own.left.points[0]", "(0, nan)");
}

TEST(Validation, HorizonAndStepMustBePositive) {
  Params p;
  p.horizon_s = 0.0;
  try {
    Estimator e(p);
    FAIL();
  } catch (const InputError& e) {
    ExpectMentions(e.what(), "params.horizon_s", "0");
  }
  p = Params{};
  p.step_s = -0.02;
  EXPECT_THROW(Estimator{p}, InputError);
  p = Params{};
  p.step_s = 0.03;  // 2 s is not a whole number of 30 ms steps
  EXPECT_THROW(Estimator{p}, InputError);
}

TEST(Validation, ImpossibleCounts) {
  Params p;
  p.profiles = 2;  // max, min and zero need 3
  try {
    Estimator e(p);
    FAIL();
  } catch (const InputError& e) {
    ExpectMentions(e.what(), "params.profiles", "2");
  }
  p = Params{};
  p.path_sample_times_s = {};
  EXPECT_THROW(Estimator{p}, InputError);
  p = Params{};
  p.path_sample_times_s = {1.0, 0.5};
  EXPECT_THROW(Estimator{p}, InputError);
  p = Params{};
  p.own_lane_samples = 0;
  EXPECT_THROW(Estimator{p}, InputError);
  EstimatorOptions opt;
  opt.threads = -2;
  EXPECT_THROW(Estimator(Params{}, opt), InputError);
  EXPECT_THROW(ParseBackend("gpu"), InputError);
}

TEST(Validation, DrivabilityAndScoringParams) {
  // Each invalid value is named with its field.
  struct Case {
    const char* field;
    std::function<void(Params*)> set;
  };
  const std::vector<Case> cases{
      {"params.steer_latency_s", [](Params* p) { p->steer_latency_s = -0.1; }},
      {"params.drive_traction_share", [](Params* p) { p->drive_traction_share = 1.5; }},
      {"params.drive_traction_share", [](Params* p) { p->drive_traction_share = 0.0; }},
      {"params.accel_score_sigma_mps2", [](Params* p) { p->accel_score_sigma_mps2 = 0.0; }},
      {"params.lateral_offset_sigma_m", [](Params* p) { p->lateral_offset_sigma_m = -1.0; }},
      {"params.heading_score_sigma_rad", [](Params* p) { p->heading_score_sigma_rad = 0.0; }},
      {"params.pedestrian_speed_sigma_mps",
       [](Params* p) { p->pedestrian_speed_sigma_mps = std::nan(""); }},
      {"params.lane_crossing_penalty", [](Params* p) { p->lane_crossing_penalty = 0.5; }},
      {"params.counter_traffic_penalty", [](Params* p) { p->counter_traffic_penalty = 0.9; }},
      {"params.scoring", [](Params* p) { p->scoring = static_cast<Params::Scoring>(7); }},
  };
  for (const Case& c : cases) {
    Params p;
    c.set(&p);
    try {
      ValidateParams(p);
      ADD_FAILURE() << c.field << ": no exception";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(c.field), std::string::npos) << e.what();
    }
  }
  EXPECT_NO_THROW(ValidateParams(ParamsPreset("paper-literal")));
  EXPECT_THROW(ParamsPreset("Paper-Literal"), InputError);
}

TEST(Validation, WorkloadTooLargeForMemory) {
  Params p;
  p.max_memory_bytes = 1 << 20;  // 1 MiB
  const std::string msg = EstimateError<WorkloadError>(bench::PaperSceneS2(), p);
  EXPECT_NE(msg.find("workload too large"), std::string::npos) << msg;
  EXPECT_NE(msg.find("max_memory_bytes"), std::string::npos) << msg;
}

}  // namespace
}  // namespace criticality
