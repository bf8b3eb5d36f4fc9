// Probabilities the estimator reports lie within [0, 1] also where rounding would put a sum of
// them above 1 (risk_assessment.h, FinishDecisionOutputs).
#include <gtest/gtest.h>

#include <string>

#include "criticality/estimator.h"
#include "criticality/scene_io.h"

namespace criticality {
namespace {

// emer1 (an emergency vehicle, 7.6 m/s) at 72.0 s on a user-style net with trams, trains,
// motorcycles and pedestrians at 0.25 s steps (sumo-criticality --record-scenes), in a jam of 15
// road users: every one of its hypotheses collides, and the weighted sum over them came out
// at 1.0000000000000084 before the rounding to 1.
TEST(ProbabilityRange, AnEgoWhoseEveryHypothesisCollidesGetsAtMostOne) {
  const Scene scene =
      ReadSceneFile(std::string(CRIT_TEST_SCENE_DIR) + "/emergency_vehicle_boxed_in.scene");
  for (Backend backend : {Backend::kReference, Backend::kCpu}) {
    EstimatorOptions options;
    options.backend = backend;
    const Result r = Estimator(Params{}, options).Estimate(scene);
    const std::string name = BackendName(backend);
    EXPECT_GT(r.p_collision, 1.0 - 1e-9) << name;  // the scene still shows the problem
    EXPECT_LE(r.p_collision, 1.0) << name;
    EXPECT_LE(r.p_reference, 1.0) << name;
    EXPECT_LE(r.unavoidability, 1.0) << name;
    ASSERT_FALSE(r.ego_collision_probability.empty()) << name;
    for (double c : r.ego_collision_probability) {
      ASSERT_GE(c, 0.0) << name;
      ASSERT_LE(c, 1.0) << name;
    }
  }
}

}  // namespace
}  // namespace criticality
