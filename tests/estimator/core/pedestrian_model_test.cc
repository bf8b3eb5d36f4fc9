// Pedestrians (paper Sec. IV-B-3): kinematic, never faster than 2.7 m/s.
#include "core/pedestrian_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/trajectory_generation.h"

namespace criticality::core {
namespace {

TEST(Pedestrian, NeverExceedsTheSpeedLimit) {
  std::mt19937_64 rng(1234);
  std::uniform_real_distribution<double> speed(0.0, 4.0), accel(-12.0, 12.0), heading(-kPi, kPi);
  const double kMax = 2.7, kTau = 0.02;
  for (int trial = 0; trial < 2000; ++trial) {
    double x = 0.0, y = 0.0, v = std::fmin(speed(rng), kMax);
    const double h = heading(rng), a = accel(rng);
    for (int n = 0; n < 100; ++n) {
      const double x0 = x, y0 = y;
      PedestrianStep(h, a, kMax, kTau, &x, &y, &v);
      ASSERT_LE(std::hypot(x - x0, y - y0) / kTau, kMax + 1e-9);
      ASSERT_GE(v, 0.0);
      ASSERT_LE(v, kMax);
    }
  }
}

TEST(Pedestrian, HypothesesFromAFastStartRespectTheLimit) {
  HypothesisSet h;
  h.model = MotionModelKind::kPedestrian;
  h.X_WL = Pose2{3.0, -2.0, 0.4};
  h.v0 = 3.5;  // above the limit: clamped
  h.max_speed = 2.7;
  h.n_profiles = 6;
  h.n_paths = 7;
  for (int k = 0; k < 6; ++k) h.profile_target[k] = -12.0 + 24.0 * k / 5.0;
  for (int l = 0; l < 7; ++l) h.heading[l] = 0.4 + 2.0 * kPi * l / 7.0;
  SimulationConfig cfg;
  std::vector<double> x(100), y(100), yaw(100);
  for (int t = 0; t < h.Trajectories(); ++t) {
    SimulateHypothesis(h, cfg, t / 7, t % 7, x.data(), y.data(), yaw.data());
    double px = h.X_WL.x, py = h.X_WL.y;
    for (int n = 0; n < 100; ++n) {
      ASSERT_LE(std::hypot(x[n] - px, y[n] - py) / cfg.tau, 2.7 + 1e-9) << "t=" << t << " n=" << n;
      px = x[n];
      py = y[n];
    }
  }
}

}  // namespace
}  // namespace criticality::core
