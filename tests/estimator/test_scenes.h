#pragma once
// Scenes shared by the estimator tests.
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "bench/paper_scenes.h"
#include "criticality/estimator.h"
#include "criticality/scene.h"

namespace criticality::testing {

/** p_collision of one estimate of `scene` with `params` on backend `b`. */
inline double PCollision(const Scene& scene, const Params& params = {},
                         Backend b = Backend::kCpu) {
  EstimatorOptions opt;
  opt.backend = b;
  return Estimator(params, opt).Estimate(scene).p_collision;
}

/** A seeded random scene around an ego on a straight 3-lane road: 0..max_vehicles vehicles
 *  (some with lanes of their own, some associated, some crossing), 0..max_pedestrians
 *  pedestrians. Dense when `dense`. Every third seed has an Euler position update
 *  (Scene::euler_update_step_s). */
inline Scene RandomScene(unsigned seed, int max_vehicles, int max_pedestrians, bool dense) {
  std::mt19937_64 rng(seed);
  auto uni = [&](double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
  };
  Scene s;
  s.ego.state.speed_mps = uni(0.0, 30.0);
  s.ego.state.accel_mps2 = uni(-3.0, 2.0);
  s.ego.state.yaw_rate_radps = uni(-0.05, 0.05);
  s.ego.lanes = bench::StraightThreeLanes();
  if (rng() % 4 == 0) s.ego.lanes.left.reset();
  if (rng() % 4 == 0) s.ego.lanes.right.reset();
  if (rng() % 5 == 0) s.ego.lanes.right.reset(), s.ego.lanes.own.reset();  // virtual lane
  const double reach = dense ? 25.0 : 60.0;
  const int n_veh = static_cast<int>(rng() % (max_vehicles + 1));
  for (int i = 0; i < n_veh; ++i) {
    Vehicle v;
    v.id = "v" + std::to_string(i);
    v.state.x_m = uni(-reach, reach);
    v.state.y_m = 3.5 * static_cast<int>(rng() % 3 - 1) + uni(-0.5, 0.5);
    v.state.speed_mps = uni(0.0, 35.0);
    v.state.accel_mps2 = uni(-2.0, 2.0);
    v.length_m = uni(3.0, 6.0);
    v.width_m = uni(1.5, 2.1);
    const unsigned kind = rng() % 4;
    if (kind == 0) {
      v.lanes = bench::StraightThreeLanes();
    } else if (kind == 1) {
      v.state.yaw_rad = 3.14159265358979;  // oncoming, associated with the ego's lanes
    } else if (kind == 2) {
      v.state.yaw_rad = uni(1.2, 1.9);  // crossing: virtual lane
    }
    // Every other vehicle must stop at a line ahead (red light, yield), drawn without the
    // random stream so that the rest of the scene stays as it was.
    if (i % 2 == 1) v.stop_line = StopLine{StopLine::Reason::kRedLight, 2.0 + 4.0 * i};
    s.vehicles.push_back(v);
  }
  const int n_ped = static_cast<int>(rng() % (max_pedestrians + 1));
  for (int i = 0; i < n_ped; ++i) {
    Pedestrian p;
    p.id = "p" + std::to_string(i);
    p.state.x_m = uni(0.0, reach);
    p.state.y_m = uni(-8.0, 8.0);
    p.state.yaw_rad = uni(-3.14, 3.14);
    p.state.speed_mps = uni(0.0, 2.5);
    s.pedestrians.push_back(p);
  }
  // Every third seed as a simulator with an Euler position update sees it (drawn without the
  // random stream, as the stop lines).
  if (seed % 3 == 2) s.euler_update_step_s = 0.1 * static_cast<double>(1 + seed % 10);
  return s;
}

/** A small fleet as a simulator step gives it (issue 23): seven vehicles on a straight 3-lane
 *  road (two in a queue, one cutting across, one oncoming from beyond most egos' reach), and
 *  one scene per vehicle with it as the ego and the other six as objects, each vehicle's data
 *  the same in every scene it is in. So every vehicle is an object in six scenes, and some of
 *  its hypotheses collide. */
inline std::vector<Scene> FleetScenes() {
  struct Member {
    const char* id;
    double x, y, yaw, v;
  };
  const Member members[] = {{"a", 0.0, 0.0, 0.0, 12.0},     {"b", 14.0, 0.0, 0.0, 6.0},
                            {"c", 6.0, 3.5, 0.0, 14.0},     {"d", 22.0, -3.5, 0.3, 9.0},
                            {"e", -15.0, 0.0, 0.0, 15.0},   {"f", 30.0, 3.5, -0.4, 8.0},
                            {"g", 75.0, 3.5, 3.14159, 15.0}};
  std::vector<Scene> scenes;
  for (const Member& ego : members) {
    Scene s;
    s.ego.id = ego.id;
    s.ego.state.x_m = ego.x;
    s.ego.state.y_m = ego.y;
    s.ego.state.yaw_rad = ego.yaw;
    s.ego.state.speed_mps = ego.v;
    s.ego.lanes = bench::StraightThreeLanes();
    for (const Member& m : members) {
      if (&m == &ego) continue;
      Vehicle v;
      v.id = m.id;
      v.state.x_m = m.x;
      v.state.y_m = m.y;
      v.state.yaw_rad = m.yaw;
      v.state.speed_mps = m.v;
      v.lanes = bench::StraightThreeLanes();
      s.vehicles.push_back(v);
    }
    scenes.push_back(s);
  }
  return scenes;
}

/** The scene with every vehicle made a `user` (a truck, a train) pulling two 10 m carriages
 *  behind it along its heading, 1 m apart: long bodies for the backends' tests. */
inline Scene WithTrailers(Scene s, RoadUser user) {
  for (Vehicle& v : s.vehicles) {
    v.type.road_user = user;
    for (int k = 0; k < 2; ++k) {
      Carriage c;
      c.x_m = v.state.x_m - 0.5 * v.length_m - 0.5 - 5.0 - 10.5 * k;
      c.y_m = v.state.y_m;
      c.length_m = 10.0;
      c.width_m = v.width_m;
      c.lanes = v.lanes;
      v.carriages.push_back(c);
    }
  }
  return s;
}

/** A way (Vehicle::way, Ego::way) that turns right ahead of a body `length_m` long at
 *  `radius` (tighter than a car steers below about 5 m): from 1 m behind its back straight to
 *  its front, a quarter circle in 12 pieces, then 30 m straight on. */
inline Way TurningWay(double length_m, double radius) {
  Way w;
  const double half = 0.5 * length_m;
  w.points.push_back({-half - 1.0, 0.0});
  for (int k = 0; k <= 12; ++k) {
    const double a = 1.5707963267948966 * k / 12.0;
    w.points.push_back({half + radius * std::sin(a), -radius + radius * std::cos(a)});
  }
  w.points.push_back({half + radius, -radius - 30.0});
  w.front_m = 2.0 * half + 1.0;
  w.back_m = 1.0;
  return w;
}

/** The scene with every vehicle given a TurningWay. */
inline Scene WithTurningWays(Scene s, double radius) {
  for (Vehicle& v : s.vehicles) v.way = TurningWay(v.length_m, radius);
  return s;
}

}  // namespace criticality::testing
