// Bodies on their path (Scene::bodies_on_path, HypothesisSet::body_on_path): a vehicle's box in
// a turn is the chord of the path its centre follows, as SUMO draws it (its front and back on
// the path), not the box tangent to the path at its centre, whose ends stand the sagitta
// c^2 / (8 R) outside the turn. The measured pose is such a box, so the prediction starts where
// the vehicle stands; off a turn and at a standstill nothing changes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "core/trajectory_generation.h"
#include "criticality/scene_io.h"
#include "criticality/vehicle_class.h"
#include "src/problem.h"

namespace criticality {
namespace {

constexpr double kRadius = 12.0;  // the turn's radius at its vertex
constexpr double kLength = 8.0;   // the box (a bus's front part, a short truck)

// A one-track vehicle at `v0` tracking the left turn y = x^2 / (2 R) from its vertex, heading
// along x, turning already at yaw_rate0; 3 s.
core::HypothesisSet TurningVehicle(double v0, double yaw_rate0, bool on_path) {
  core::HypothesisSet h;
  h.model = core::MotionModelKind::kOneTrack;
  h.vehicle = VehicleParamsFor(VehicleClass::kLargeFamily, kLength, 2.5);
  h.half_length = 0.5 * kLength;
  h.half_width = 1.25;
  h.v0 = v0;
  h.yaw_rate0 = yaw_rate0;
  h.n_profiles = 1;
  h.profile_target[0] = 0.0;
  h.n_instants = 1;
  h.instant_time[0] = 100.0;
  h.n_lateral = 1;
  h.section[0][0] = core::Parabola{0.5 / kRadius, 0.0, 0.0};
  h.reference_path = h.section[0][0];
  h.n_paths = 1;
  h.steer_feedforward = true;
  h.body_on_path = on_path;
  return h;
}

struct Poses {
  std::vector<double> x, y, yaw;
};

Poses Simulate(const core::HypothesisSet& h, int steps) {
  core::SimulationConfig cfg;
  cfg.tau = 0.02;
  cfg.n_steps = steps;
  Poses p{std::vector<double>(steps), std::vector<double>(steps), std::vector<double>(steps)};
  core::SimulateHypothesis(h, cfg, 0, 0, p.x.data(), p.y.data(), p.yaw.data());
  return p;
}

// The point `ds` along the poses' polyline from pose n (negative: back), interpolated.
void PointAlong(const Poses& p, int n, double ds, double* x, double* y) {
  const int step = ds >= 0.0 ? 1 : -1;
  double left = std::fabs(ds);
  int k = n;
  while (k + step >= 0 && k + step < static_cast<int>(p.x.size())) {
    const double len = std::hypot(p.x[k + step] - p.x[k], p.y[k + step] - p.y[k]);
    if (len >= left) {
      const double u = left / len;
      *x = p.x[k] + u * (p.x[k + step] - p.x[k]);
      *y = p.y[k] + u * (p.y[k + step] - p.y[k]);
      return;
    }
    left -= len;
    k += step;
  }
  ADD_FAILURE() << "the path is too short around pose " << n;
}

TEST(BodiesOnPath, ABoxInATurnStandsAtTheCentreOfItsPathsChord) {
  // Entering the turn with no yaw rate, both start from the same model centre, so the poses
  // without the switch are the path the centre follows (6 s, 30 m through the turn).
  const int steps = 300;
  const Poses centre = Simulate(TurningVehicle(5.0, 0.0, false), steps);
  const Poses chord = Simulate(TurningVehicle(5.0, 0.0, true), steps);
  double worst = 0.0, tangent = 0.0;
  for (int n = 49; n < 260; ++n) {  // front and back within the simulated path
    // The chord between the path's points half a length ahead of and behind the centre.
    double fx = 0.0, fy = 0.0, bx = 0.0, by = 0.0;
    PointAlong(centre, n, 0.5 * kLength, &fx, &fy);
    PointAlong(centre, n, -0.5 * kLength, &bx, &by);
    const double mx = 0.5 * (fx + bx), my = 0.5 * (fy + by);
    worst = std::max(worst, std::hypot(chord.x[n] - mx, chord.y[n] - my));
    tangent = std::max(tangent, std::hypot(centre.x[n] - mx, centre.y[n] - my));
    // It keeps the model's heading (the chord's own heading was measured and not kept).
    EXPECT_EQ(chord.yaw[n], centre.yaw[n]) << n;
  }
  // The model's box, on the path, stands 0.5 m outside the chord's centre at most; the box of a
  // body on its path at it, within the change of the path's curvature along the body.
  EXPECT_GT(tangent, 0.4);
  EXPECT_LT(worst, 0.15);
}

TEST(BodiesOnPath, TheMeasuredBoxIsWhereThePredictionStarts) {
  // Already turning (R = 12 m): the measured box, at the origin along x, is the chord, so the
  // model's centre starts kappa c^2 / 8 = 0.67 m outside it; the first pose after 20 ms is
  // the chord again, 0.1 m on, not 0.67 m off. (Its heading is its course, which the one-track
  // model's sideslip turns by up to 0.08 rad at once: the model starts without sideslip.)
  const double v0 = 5.0, yaw_rate0 = v0 / kRadius;
  const Poses p = Simulate(TurningVehicle(v0, yaw_rate0, true), 10);
  EXPECT_NEAR(std::hypot(p.x[0], p.y[0]), v0 * 0.02, 0.03);
  EXPECT_LT(std::fabs(p.yaw[0]), 0.1);
  // Its model centre: outside (to the right of) the measured one by the sagitta.
  core::HypothesisSet h = TurningVehicle(v0, yaw_rate0, true);
  core::SimulationConfig cfg;
  const core::SimulationState st = core::InitialSimulationState(h, cfg);
  EXPECT_NEAR(st.s.y, -(yaw_rate0 / v0) * kLength * kLength / 8.0, 1e-12);
  EXPECT_NEAR(st.s.x, 0.0, 1e-12);
}

TEST(BodiesOnPath, StraightOrStandingNothingChanges) {
  // Straight: no curvature, no sideslip, the same poses bit for bit.
  core::HypothesisSet straight_on = TurningVehicle(10.0, 0.0, true);
  core::HypothesisSet straight_off = TurningVehicle(10.0, 0.0, false);
  straight_on.section[0][0].a = straight_off.section[0][0].a = 0.0;
  straight_on.reference_path = straight_on.section[0][0];
  straight_off.reference_path = straight_off.section[0][0];
  const Poses a = Simulate(straight_on, 100), b = Simulate(straight_off, 100);
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.y, b.y);
  EXPECT_EQ(a.yaw, b.yaw);
  // Standing in the turn with a measured yaw rate (a car turning on the spot, or the sensor's
  // noise): the model's centre starts off the measured box, and the predicted box must still
  // be where it was measured, not a sagitta away.
  const Poses c = Simulate(TurningVehicle(0.0, 0.05, true), 100);
  for (int n = 0; n < 100; ++n) {
    EXPECT_NEAR(c.x[n], 0.0, 1e-9) << n;
    EXPECT_NEAR(c.y[n], 0.0, 1e-9) << n;
  }
}

TEST(BodiesOnPath, OnlyVehiclesAreBodiesOnTheirPathAndScenesSaySo) {
  Scene scene;
  scene.ego.id = "ego";
  scene.ego.state.speed_mps = 8.0;
  Vehicle v;
  v.id = "car";
  v.state.x_m = 20.0;
  v.state.speed_mps = 5.0;
  scene.vehicles.push_back(v);
  Pedestrian walker;
  walker.id = "walker";
  walker.state.x_m = 10.0;
  walker.state.y_m = 4.0;
  scene.pedestrians.push_back(walker);
  const internal::Problem off = internal::BuildProblem(scene, Params{});
  EXPECT_FALSE(off.ego.body_on_path);
  for (const core::HypothesisSet& h : off.cos) EXPECT_FALSE(h.body_on_path);
  scene.bodies_on_path = true;
  const internal::Problem on = internal::BuildProblem(scene, Params{});
  EXPECT_TRUE(on.ego.body_on_path);
  int vehicles = 0, walkers = 0;
  for (const core::HypothesisSet& h : on.cos) {
    const bool walks = h.model == core::MotionModelKind::kPedestrian;
    EXPECT_EQ(h.body_on_path, !walks);
    (walks ? walkers : vehicles)++;
  }
  EXPECT_EQ(vehicles, 1);
  EXPECT_EQ(walkers, 1);
  // A scene file keeps it; without the line it is off.
  std::stringstream file;
  WriteScene(file, scene);
  EXPECT_NE(file.str().find("bodies-on-path"), std::string::npos);
  EXPECT_TRUE(ReadScene(file).bodies_on_path);
  scene.bodies_on_path = false;
  std::stringstream plain;
  WriteScene(plain, scene);
  EXPECT_EQ(plain.str().find("bodies-on-path"), std::string::npos);
  EXPECT_FALSE(ReadScene(plain).bodies_on_path);
}

}  // namespace
}  // namespace criticality
