// The paper's ablations (Sec. V-A): the lateral controller switched off (open-loop steering,
// whose hypotheses leave the road) and the road model switched off (virtual lanes only).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "bench/paper_scenes.h"
#include "core/lateral_controller.h"
#include "core/trajectory_generation.h"
#include "src/problem.h"

namespace criticality::internal {
namespace {

Scene EgoAloneOnThreeLanes(double speed) {
  Scene scene;
  scene.ego.state.speed_mps = speed;
  scene.ego.lanes = bench::StraightThreeLanes();
  return scene;
}

// The ego at the origin heading +x: the scene frame is its frame. Lateral position and heading
// of every path of the reference profile at the horizon.
struct HorizonPoses {
  std::vector<double> y, yaw;
  double reference_y{0.0};
};

HorizonPoses SimulateEgoPaths(const Problem& pb) {
  HorizonPoses out;
  const int steps = pb.Steps();
  const int profile = pb.ego_reference_trajectory / pb.ego.n_paths;
  std::vector<double> x(steps), y(steps), yaw(steps);
  for (int path = 0; path < pb.ego.n_paths; ++path) {
    core::SimulateHypothesis(pb.ego, pb.sim, profile, path, x.data(), y.data(), yaw.data());
    out.y.push_back(y.back());
    out.yaw.push_back(yaw.back());
    if (profile * pb.ego.n_paths + path == pb.ego_reference_trajectory) out.reference_y = y.back();
  }
  return out;
}

double MaxAbs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::fabs(x));
  return m;
}

TEST(Ablation, OpenLoopSteeringIsThePurePursuitArcThroughTheAimPoint) {
  // A section 3.5 m to the left, parallel to the heading; 20 m/s, 0.7 s ahead: the aim point
  // is (14, 3.5). The circle through the origin, tangent to +x, through (dx, dy) has curvature
  // 2 dy / (dx^2 + dy^2) (elementary geometry, independent of the pure-pursuit formula).
  core::ControllerLimits limits;
  core::MotionState s;
  s.v = 20.0;
  const core::Parabola section{0.0, 0.0, 3.5};
  const double wheelbase = 2.7;
  const double steer = core::OpenLoopSteer(limits, section, s, wheelbase, 0.7);
  EXPECT_NEAR(std::tan(steer) / wheelbase, 2.0 * 3.5 / (14.0 * 14.0 + 3.5 * 3.5), 1e-12);
  // Straight ahead on the section: no steering; the angle limit holds.
  EXPECT_EQ(core::OpenLoopSteer(limits, core::Parabola{}, s, wheelbase, 0.7), 0.0);
  s.v = 1.0;  // 2 m ahead, 3.5 m aside: beyond the limit
  EXPECT_EQ(core::OpenLoopSteer(limits, section, s, wheelbase, 0.7), limits.max_steer_rad);
}

TEST(Ablation, ControllerOffHypothesesLeaveTheRoadWhileTheControlledOnesStayOnIt) {
  const Scene scene = EgoAloneOnThreeLanes(20.0);
  Params on;
  Params off;
  off.lateral_controller = false;
  const HorizonPoses a = SimulateEgoPaths(BuildProblem(scene, on));
  const HorizonPoses b = SimulateEgoPaths(BuildProblem(scene, off));
  ASSERT_EQ(a.y.size(), 343u);
  ASSERT_EQ(b.y.size(), 343u);
  // The road: three 3.5 m lanes, outer edges at +-5.25 m. Every controlled path ends on it.
  // Open loop, the same sections: many paths end beyond an edge, some well beyond.
  const double edge = 1.5 * bench::kLaneWidth;
  auto off_road = [&](const std::vector<double>& y) {
    return std::count_if(y.begin(), y.end(), [&](double v) { return std::fabs(v) > edge; });
  };
  EXPECT_LT(MaxAbs(a.y), edge);
  EXPECT_EQ(off_road(a.y), 0);
  EXPECT_GT(MaxAbs(b.y), edge + 2.0);
  EXPECT_GE(off_road(b.y), 100) << off_road(b.y);
  // Keeping the own lane needs no steering, with or without the controller.
  EXPECT_NEAR(a.reference_y, 0.0, 0.05);
  EXPECT_NEAR(b.reference_y, 0.0, 0.05);
}

TEST(Ablation, RoadModelOffIgnoresTheGivenLanes) {
  // Only an own lane is given, curving left (y = 0.004 x^2: radius about 125 m).
  Scene scene;
  scene.ego.state.speed_mps = 20.0;
  Lane curve;
  for (int i = 0; i < 3; ++i) {
    const double x = 25.0 * i;
    curve.left.points[i] = Point2{x, 0.004 * x * x + 1.75};
    curve.right.points[i] = Point2{x, 0.004 * x * x - 1.75};
  }
  scene.ego.lanes.own = curve;
  Params on;
  Params off;
  off.road_model = false;
  const Problem with_road = BuildProblem(scene, on);
  const Problem without = BuildProblem(scene, off);
  // With the road: the own lane only, 3 samples per instant, 27 paths. Without: a virtual own
  // lane and virtual neighbours, 7 samples, 343 paths.
  EXPECT_EQ(with_road.ego.n_paths, 27);
  EXPECT_EQ(without.ego.n_paths, 343);
  // The reference follows the curve with the road model, and goes straight (no yaw rate)
  // without it: about 0.004 * 40^2 = 6.4 m apart after 2 s at 20 m/s.
  const double y_road = SimulateEgoPaths(with_road).reference_y;
  const double y_virtual = SimulateEgoPaths(without).reference_y;
  EXPECT_GT(y_road, 4.0);
  EXPECT_NEAR(y_virtual, 0.0, 0.05);
}

}  // namespace
}  // namespace criticality::internal
