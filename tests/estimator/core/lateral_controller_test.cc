// The paper's lateral controller (Sec. IV-B-2b) in closed loop with the one-track model.
#include "core/lateral_controller.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "core/trajectory_generation.h"
#include "criticality/vehicle_class.h"

namespace criticality::core {
namespace {

constexpr double kTau = 0.02;

// A one-track vehicle at the origin heading +x that tracks y = target (one section).
HypothesisSet Tracker(double v, double target) {
  HypothesisSet h;
  h.model = MotionModelKind::kOneTrack;
  h.v0 = v;
  h.vehicle = VehicleParamsFor(VehicleClass::kLargeFamily, 4.6, 1.8);
  h.seam_speed = SeamSpeed(h.vehicle, kTau, 1.5);
  h.n_profiles = 1;
  h.n_instants = 1;
  h.instant_time[0] = 100.0;
  h.n_lateral = 1;
  h.section[0][0] = Parabola{0.0, 0.0, target};
  h.n_paths = 1;
  return h;
}

std::vector<double> LateralPositions(double v, double target, int steps) {
  const HypothesisSet h = Tracker(v, target);
  SimulationConfig cfg;
  cfg.n_steps = steps;
  std::vector<double> x(steps), y(steps), yaw(steps);
  SimulateHypothesis(h, cfg, 0, 0, x.data(), y.data(), yaw.data());
  return y;
}

TEST(LateralController, BringsTheVehicleToItsLaneCentre) {
  // Start 1 m right of the lane centre. The paper's law weights small distance errors weakly
  // (0.5 deg/m), so small offsets close slowly at low speed: we check the approach is
  // monotone and within 10 cm after 16 s at 5 m/s, and faster at higher speeds.
  for (double v : {5.0, 15.0, 30.0}) {
    const std::vector<double> y = LateralPositions(v, 1.0, 800);
    EXPECT_NEAR(y.back(), 1.0, 0.1) << "v=" << v;
    for (size_t n = 1; n < y.size(); ++n) {
      ASSERT_GE(y[n], y[n - 1] - 1e-6) << "not monotone at v=" << v << " step " << n;
      ASSERT_LT(y[n], 1.15) << "overshoot at v=" << v;
    }
    if (v >= 15.0) {
      EXPECT_NEAR(y[399], 1.0, 0.06) << "after 8 s at v=" << v;
    }
  }
}

TEST(LateralController, ReachesTheNeighbouringLanePathQuickly) {
  // A 3.5 m lane change: 90 % within 1.5 s at motorway speeds, at most 10 % overshoot.
  for (double v : {20.0, 30.0, 40.0}) {
    const std::vector<double> y = LateralPositions(v, 3.5, 250);
    int t90 = -1;
    double peak = 0.0;
    for (int n = 0; n < static_cast<int>(y.size()); ++n) {
      if (t90 < 0 && y[n] >= 0.9 * 3.5) t90 = n;
      peak = std::fmax(peak, y[n]);
    }
    ASSERT_GE(t90, 0) << "v=" << v;
    EXPECT_LE((t90 + 1) * kTau, 1.5) << "v=" << v;
    EXPECT_LE(peak, 3.5 * 1.10) << "v=" << v;
    EXPECT_NEAR(y.back(), 3.5, 0.1) << "v=" << v;
  }
}

TEST(LateralController, NeverExceedsSteeringAngleOrRateLimits) {
  ControllerLimits c;
  c.max_steer_rad = 0.5;
  c.max_steer_rate_radps = 0.9;
  const VehicleParams p = VehicleParamsFor(VehicleClass::kLargeFamily, 4.6, 1.8);
  for (double v : {3.0, 10.0, 35.0}) {
    for (double target : {-3.5, 7.0}) {
      MotionState s;
      s.v = v;
      double steer = 0.0;
      const Parabola section{0.001, 0.05, target};
      for (int n = 0; n < 300; ++n) {
        const double next = SteeringCommand(c, section, s, steer, kTau);
        ASSERT_LE(std::fabs(next), c.max_steer_rad + 1e-12);
        ASSERT_LE(std::fabs(next - steer), c.max_steer_rate_radps * kTau + 1e-12);
        steer = next;
        StateDerivative d = s.v < SeamSpeed(p, kTau, 1.5) ? KinematicSingleTrack(p, steer, 0.0, &s)
                                                          : OneTrackDerivative(p, s, steer, 0.0);
        EulerStep(d, kTau, &s);
      }
    }
  }
}

TEST(LateralController, PaperLawSignsAndDegrees) {
  // Path to the left (d > 0) or pointing left (e > 0): steer left. 1 m at 20 m/s: 1.64 deg.
  EXPECT_NEAR(PaperSteeringLawDeg(20.0, 1.0, 0.0), 1.64, 1e-12);
  EXPECT_LT(PaperSteeringLawDeg(20.0, -1.0, 0.0), 0.0);
  EXPECT_NEAR(PaperSteeringLawDeg(20.0, 0.0, 0.1), 9.5 * 3.8197 * 0.1, 1e-12);
}


// A junction's right turn: radius 8 m from the origin (heading +x), in a frame turned by -45
// degrees along its chord (what the estimator fits such a lane in), continuing straight beyond
// its end. Tracked at 6.5 m/s (SUMO's speed for such turns), the paper's law alone builds up an
// error before it steers and leaves the turn wide; with the curvature feed-forward the
// vehicle stays on the arc.
double WorstOffsetFromRightTurn(bool feedforward) {
  const double r = 8.0, rot = -kPi / 4;
  // The arc's three points in the turned frame, fitted there.
  const double xs_local[3] = {0.0, r * std::sin(kPi / 4), r};
  const double ys_local[3] = {0.0, -r * (1.0 - std::cos(kPi / 4)), -r};
  double xr[3], yr[3];
  for (int i = 0; i < 3; ++i) {
    xr[i] = std::cos(rot) * xs_local[i] + std::sin(rot) * ys_local[i];
    yr[i] = -std::sin(rot) * xs_local[i] + std::cos(rot) * ys_local[i];
  }
  Parabola lane;
  EXPECT_TRUE(FitParabola(xr, yr, &lane));
  lane.SetFrame(rot);
  lane.x_end = xr[2];
  HypothesisSet h = Tracker(6.5, 0.0);
  h.section[0][0] = lane;
  h.reference_path = lane;
  h.yaw_rate0 = -6.5 / r;
  h.steer_feedforward = feedforward;
  SimulationConfig cfg;
  cfg.n_steps = 100;  // 2 s: 13 m, the turn (12.6 m of arc) and a little beyond
  std::vector<double> x(cfg.n_steps), y(cfg.n_steps), yaw(cfg.n_steps);
  SimulateHypothesis(h, cfg, 0, 0, x.data(), y.data(), yaw.data());
  double worst = 0.0;
  for (int n = 0; n < cfg.n_steps; ++n) {
    // Distance from the turn: the arc around (0, -r), then the straight exit x = r.
    const double off = y[n] > -r ? std::fabs(std::hypot(x[n], y[n] + r) - r) : std::fabs(x[n] - r);
    worst = std::fmax(worst, off);
  }
  return worst;
}

TEST(LateralController, CurvatureFeedforwardKeepsATurningVehicleInItsTurn) {
  const double with = WorstOffsetFromRightTurn(true);
  const double without = WorstOffsetFromRightTurn(false);
  std::printf("worst offset from the turn: %.2f m with feed-forward, %.2f m without\n", with,
              without);
  // Measured: 1.03 m with, 2.33 m without. Part of the 1 m is the lane model's, not the
  // controller's: the parabola through three points of the arc starts and ends about 5 degrees
  // off the arc's direction.
  EXPECT_LT(with, 1.2);
  EXPECT_GT(without, 2.0);  // the paper's law alone leaves the turn wide, into the next lane
  EXPECT_LT(with, 0.5 * without);
}

}  // namespace
}  // namespace criticality::core
