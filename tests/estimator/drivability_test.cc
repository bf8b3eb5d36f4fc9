// Every hypothesis is drivable (DESIGN.md, Params "Drivability"): for every vehicle hypothesis
// of S1, S2, the discrimination scenes and the seeded random family, the acceleration stays in
// the friction circle, positive acceleration within the drive's traction and power, and the
// path of the hypothesis takes over from the reference path only after the steering latency. The
// paper-literal preset, which has none of these limits, must violate the friction circle (so that
// the check can fail).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "bench/discrimination_scenes.h"
#include "bench/paper_scenes.h"
#include "core/trajectory_generation.h"
#include "src/problem.h"
#include "test_scenes.h"

namespace criticality {
namespace {

struct Worst {
  double total_over_mu_g{0.0};  ///< max |a| / (mu g)
  double drive_excess{0.0};     ///< max (dv/dt - drive limit), m/s^2, where dv/dt > 0
  int latency_violations{0};    ///< a path steered differently from the reference path before
                                ///< the latency
  int hypotheses{0};
};

// Simulates every vehicle hypothesis (ego and other vehicles) of the problem with a trace.
Worst Check(const internal::Problem& pb) {
  Worst w;
  const int steps = pb.Steps();
  std::vector<double> x(steps), y(steps), yaw(steps), steer(steps);
  std::vector<core::MotionState> state(steps);
  std::vector<const core::HypothesisSet*> sets{&pb.ego};
  for (const core::HypothesisSet& h : pb.cos) sets.push_back(&h);
  for (const core::HypothesisSet* h : sets) {
    if (h->model == core::MotionModelKind::kPedestrian) continue;
    const double mu_g = h->vehicle.friction * core::kGravity;
    std::vector<double> first_path_steer(steps);
    for (int t = 0; t < h->Trajectories(); ++t) {
      core::StepTrace trace{state.data(), steer.data()};
      core::SimulateHypothesis(*h, pb.sim, t / h->n_paths, t % h->n_paths, x.data(), y.data(),
                               yaw.data(), 1, &trace);
      ++w.hypotheses;
      double v_prev = h->v0;
      for (int n = 0; n < steps; ++n) {
        const core::MotionState& s = state[n];
        w.total_over_mu_g = std::fmax(w.total_over_mu_g, std::hypot(s.ax, s.ay) / mu_g);
        // One-track: dv/dt is the profile's acceleration. (The two-track ego's side forces
        // add to dv/dt along its course when it turns: EgoDriveIsLimited checks it straight.)
        const double v_dot = (s.v - v_prev) / pb.sim.tau;
        if (h->power_limited && h->model == core::MotionModelKind::kOneTrack && v_dot > 0.0) {
          w.drive_excess = std::fmax(w.drive_excess, v_dot - core::DriveAccelLimit(*h, v_prev));
        }
        // Before the latency every path of a profile steers as the first one (all follow
        // the reference path then).
        if (t % h->n_paths == 0) {
          first_path_steer[n] = steer[n];
        } else if (n * pb.sim.tau < h->steer_latency && steer[n] != first_path_steer[n]) {
          ++w.latency_violations;
        }
        v_prev = s.v;
      }
    }
  }
  return w;
}

std::vector<std::pair<std::string, Scene>> Scenes() {
  std::vector<std::pair<std::string, Scene>> out{{"S1", bench::PaperSceneS1()},
                                                 {"S2", bench::PaperSceneS2()}};
  for (unsigned seed = 1; seed <= 12; ++seed) {
    out.push_back(
        {"random " + std::to_string(seed), testing::RandomScene(seed, 5, 2, seed % 2 == 0)});
  }
  for (const bench::DiscriminationScene& d : bench::DiscriminationScenes()) {
    out.push_back({d.name, d.scene});
  }
  return out;
}

TEST(Drivability, EveryHypothesisStaysInTheFrictionCircleWithinItsDriveAndLatency) {
  const Params params;
  int hypotheses = 0;
  for (const auto& [name, scene] : Scenes()) {
    const Worst w = Check(internal::BuildProblem(scene, params));
    hypotheses += w.hypotheses;
    // Exact in exact arithmetic (one-track: per-axle saturation; two-track: per-wheel friction
    // circles; kinematic: steering limit); the tolerance covers rounding.
    EXPECT_LE(w.total_over_mu_g, 1.0 + 1e-9) << name;
    EXPECT_LE(w.drive_excess, 1e-9) << name;
    EXPECT_EQ(w.latency_violations, 0) << name;
  }
  EXPECT_GT(hypotheses, 50000);
}

TEST(Drivability, PaperLiteralHypothesesLeaveTheFrictionCircle) {
  // The linear one-track model and +9.7 m/s^2 at any speed: far beyond 1 g (the issue measured
  // 1.6 g lateral), which is what the default limits remove.
  const Worst w =
      Check(internal::BuildProblem(bench::PaperSceneS1(), ParamsPreset("paper-literal")));
  EXPECT_GT(w.total_over_mu_g, 1.3);
  EXPECT_EQ(w.drive_excess, 0.0);  // not limited, so not checked
}

TEST(Drivability, LimitsActWhereTheyShould) {
  // Lane changes at 30 m/s use the friction limit (some hypothesis reaches 95 % of mu g), the
  // maximum profile at 30 m/s is limited by power (a large family car: 66 W/kg / 30 m/s = 2.2
  // m/s^2), and a standing start by traction (0.55 g).
  Scene scene = bench::PaperSceneS1();
  scene.ego.state.speed_mps = 30.0;
  scene.vehicles.resize(1);
  scene.vehicles[0].state.speed_mps = 30.0;
  scene.vehicles[0].length_m = 4.6;
  internal::Problem pb = internal::BuildProblem(scene, Params{});
  EXPECT_GT(Check(pb).total_over_mu_g, 0.95);
  const core::HypothesisSet& co = pb.cos[0];
  EXPECT_NEAR(core::DriveAccelLimit(co, 30.0), 66.0 / 30.0, 1e-12);
  EXPECT_NEAR(core::DriveAccelLimit(co, 0.0), 0.55 * core::kGravity, 1e-12);
  const int steps = pb.Steps();
  std::vector<double> x(steps), y(steps), yaw(steps);
  core::SimulateHypothesis(co, pb.sim, co.n_profiles - 1, co.n_paths / 2, x.data(), y.data(),
                           yaw.data());
  // Ramp (0.2 s latency, 30 m/s^3) then at most 2.2 m/s^2 falling with speed: about 30*2 + 0.5
  // * 2.1 * 1.7^2 = 63 m, against 60 m + 0.5 * 9.7 * ... = 74 m without the limit.
  const double travelled = x[steps - 1] - scene.vehicles[0].state.x_m;
  EXPECT_GT(travelled, 62.0);
  EXPECT_LT(travelled, 63.6);
}

TEST(Drivability, EgoDriveIsLimited) {
  // The ego's maximum profile on the lane centre (no side forces): dv/dt within the drive
  // limit, and at it once the ramp is done, from a standing start (traction) to 30 m/s (power).
  for (double v0 : {0.0, 5.0, 15.0, 30.0}) {
    Scene scene = bench::PaperSceneS1();
    scene.vehicles.clear();
    scene.ego.state.speed_mps = v0;
    const internal::Problem pb = internal::BuildProblem(scene, Params{});
    const int steps = pb.Steps();
    std::vector<double> x(steps), y(steps), yaw(steps), steer(steps);
    std::vector<core::MotionState> state(steps);
    core::StepTrace trace{state.data(), steer.data()};
    core::SimulateHypothesis(pb.ego, pb.sim, pb.ego.n_profiles - 1, 3 * 49 + 3 * 7 + 3, x.data(),
                             y.data(), yaw.data(), 1, &trace);
    for (int n = 1; n < steps; ++n) {
      const double v_dot = (state[n].v - state[n - 1].v) / pb.sim.tau;
      const double limit = core::DriveAccelLimit(pb.ego, state[n - 1].v);
      EXPECT_LE(v_dot, limit + 1e-9) << "v0 " << v0 << " step " << n;
      if (n * pb.sim.tau > 0.6) {
        EXPECT_GT(v_dot, 0.99 * limit) << "v0 " << v0 << " step " << n;
      }
    }
  }
}

TEST(Drivability, EgoBrakingSpreadsFromGentleToEmergency) {
  const internal::Problem pb = internal::BuildProblem(bench::PaperSceneS1(), Params{});
  const std::vector<double> expected{-9.7, -7.275, -4.85, -2.425, 0.0, 9.7};
  ASSERT_EQ(pb.ego_profile_accel.size(), expected.size());
  for (size_t k = 0; k < expected.size(); ++k) {
    EXPECT_NEAR(pb.ego_profile_accel[k], expected[k], 1e-12) << k;
  }
  // Each braking profile, once ramped, decelerates the two-track ego at its target on the
  // lane centre (the paper's slip spread gave -9.8, -9.6, -8.3 and -5.2 m/s^2).
  const int steps = pb.Steps();
  std::vector<double> x(steps), y(steps), yaw(steps), steer(steps);
  std::vector<core::MotionState> state(steps);
  const int centre = 3 * 49 + 3 * 7 + 3;
  for (int k = 0; k < 4; ++k) {
    core::StepTrace trace{state.data(), steer.data()};
    core::SimulateHypothesis(pb.ego, pb.sim, k, centre, x.data(), y.data(), yaw.data(), 1, &trace);
    const double v_dot = (state[80].v - state[79].v) / pb.sim.tau;
    EXPECT_NEAR(v_dot, expected[k], 0.02) << "profile " << k;
  }
}

}  // namespace
}  // namespace criticality
