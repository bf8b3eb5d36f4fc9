// The paper's lateral controller (Sec. IV-B-2b) in closed loop with the one-track model.
#include "core/lateral_controller.h"

#include <gtest/gtest.h>

#include <cmath>
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

}  // namespace
}  // namespace criticality::core
