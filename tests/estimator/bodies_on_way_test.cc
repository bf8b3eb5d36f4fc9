// Bodies on their way (Vehicle::way, Params::bodies_on_way, HypothesisSet::on_way): a vehicle
// whose body is in a junction moves as SUMO moves it, the middle of its front and of its back
// on its way, its box pointing from back to front, whatever the way's radius; a turn tighter
// than a car's steering (SUMO's 1.6-3 m junction corners) is followed, which the steered model
// cannot do.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "core/trajectory_generation.h"
#include "criticality/errors.h"
#include "criticality/estimator.h"
#include "criticality/scene_io.h"
#include "src/problem.h"
#include "test_scenes.h"

namespace criticality {
namespace {

using internal::BuildProblem;
using internal::Problem;

constexpr double kPi = 3.14159265358979323846;
constexpr double kLength = 4.5;
constexpr double kRadius = 3.0;  // tighter than 0.5 rad of steering on a 2.7 m wheelbase

// In the vehicle's frame: straight along +x to its front (2.25, 0), a right turn of `radius`
// about (2.25, -radius) in 16 pieces, then straight on (-y) for 20 m; `shift` moves it all
// sideways (+y), so that the vehicle stands off it.
Way RightTurnWay(double radius, double shift = 0.0) {
  Way w;
  w.points.push_back({-6.0, shift});
  w.points.push_back({2.25, shift});
  for (int k = 1; k <= 16; ++k) {
    const double a = 0.5 * kPi * k / 16.0;
    w.points.push_back({2.25 + radius * std::sin(a), shift - radius + radius * std::cos(a)});
  }
  w.points.push_back({2.25 + radius, shift - radius - 20.0});
  w.front_m = 8.25;
  w.back_m = 8.25 - kLength;
  return w;
}

// A vehicle at (100, 50) heading +x at `speed` with that way; the ego far away.
Scene TurningVehicle(double speed, const Way& way) {
  Scene s;
  s.ego.state.speed_mps = 10.0;
  Vehicle v;
  v.id = "turner";
  v.state.x_m = 100.0;
  v.state.y_m = 50.0;
  v.state.speed_mps = speed;
  v.length_m = kLength;
  v.way = way;
  s.vehicles.push_back(v);
  return s;
}

// The distance from (x, y) to the polyline.
double DistanceTo(const std::vector<Point2>& line, double x, double y) {
  double best = std::numeric_limits<double>::infinity();
  for (size_t k = 1; k < line.size(); ++k) {
    const double ax = line[k - 1].x, ay = line[k - 1].y;
    const double dx = line[k].x - ax, dy = line[k].y - ay;
    const double u =
        std::fmax(0.0, std::fmin(1.0, ((x - ax) * dx + (y - ay) * dy) / (dx * dx + dy * dy)));
    best = std::fmin(best, std::hypot(x - ax - u * dx, y - ay - u * dy));
  }
  return best;
}

struct Offsets {
  double front{0.0};  ///< the largest distance of the front's middle from the way
  double back{0.0};   ///< ... of the nearest point 3-4.5 m behind it along the heading
  double travelled{0.0};
};

// Simulates every hypothesis of the set (the vehicle's, set 0, by default; those of path `only`
// where given) standing at (x0, y0) heading +x, and measures, in its frame, how far its front
// and back stray from the way.
Offsets Stray(const Problem& pb, const std::vector<Point2>& way, int only = -1,
              const core::HypothesisSet* set = nullptr, double x0 = 100.0, double y0 = 50.0) {
  const core::HypothesisSet& h = set ? *set : pb.cos[0];
  Offsets o;
  std::vector<double> x(pb.sim.n_steps), y(pb.sim.n_steps), yaw(pb.sim.n_steps);
  for (int t = 0; t < h.Trajectories(); ++t) {
    if (only >= 0 && t % h.n_paths != only) continue;
    core::SimulateHypothesis(h, pb.sim, t / h.n_paths, t % h.n_paths, x.data(), y.data(),
                             yaw.data());
    for (int n = 0; n < pb.sim.n_steps; ++n) {
      const double ux = std::cos(yaw[n]), uy = std::sin(yaw[n]);
      const double fx = x[n] - x0 + h.half_length * ux, fy = y[n] - y0 + h.half_length * uy;
      o.front = std::fmax(o.front, DistanceTo(way, fx, fy));
      double back = std::numeric_limits<double>::infinity();
      for (double d = 3.0; d <= 4.5; d += 0.001)
        back = std::fmin(back, DistanceTo(way, fx - d * ux, fy - d * uy));
      o.back = std::fmax(o.back, back);
      o.travelled = std::fmax(o.travelled, std::hypot(x[n] - x0, y[n] - y0));
    }
  }
  return o;
}

// Params with the experiment of lateral paths beside the way (Params::way_lateral_paths).
Params LateralPathsOnWay() {
  Params p;
  p.way_lateral_paths = true;
  return p;
}

// The path of a vehicle on its way that asks no sideways offset at any instant (its lane's
// centre, where it stands on it); -1 if none.
int PathAlongTheWay(const core::HypothesisSet& h) {
  for (int path = 0; path < h.n_paths; ++path) {
    bool zero = true;
    for (int k = 0; k < h.n_instants; ++k)
      zero = zero && h.way_lateral[k][core::SectionOfPath(h, path, k)] == 0.0;
    if (zero) return path;
  }
  return -1;
}

TEST(BodiesOnWay, AVehicleInATightTurnKeepsItsFrontAndBackOnItsWay) {
  const Way way = RightTurnWay(kRadius);
  const Problem pb = BuildProblem(TurningVehicle(6.0, way), Params{});
  ASSERT_TRUE(pb.cos[0].on_way);
  EXPECT_EQ(pb.cos[0].n_paths, 1);  // its hypotheses are its profiles
  const Offsets o = Stray(pb, way.points);
  EXPECT_LT(o.front, 0.01);
  EXPECT_LT(o.back, 0.01);
  EXPECT_GT(o.travelled, 5.0);  // it went round the turn, not stood still
  // With lateral paths beside it (the experiment), the one along the way stays on it as well.
  const Problem lateral = BuildProblem(TurningVehicle(6.0, way), LateralPathsOnWay());
  ASSERT_TRUE(lateral.cos[0].on_way);
  ASSERT_GT(lateral.cos[0].n_paths, 1);
  const int along = PathAlongTheWay(lateral.cos[0]);
  ASSERT_GE(along, 0);
  const Offsets on = Stray(lateral, way.points, along);
  EXPECT_LT(on.front, 0.01);
  EXPECT_LT(on.back, 0.01);
}

// A vehicle at (100, 50) heading +x on a straight way along its heading, 0.3 m to its right
// when `beside` (its frame: x along it, y across).
Way StraightWay(double beside) {
  Way w;
  w.points.push_back({-6.0, -beside});
  w.points.push_back({2.25, -beside});
  w.points.push_back({60.0, -beside});
  w.front_m = 8.25;
  w.back_m = 8.25 - kLength;
  return w;
}

TEST(BodiesOnWay, AVehicleOnItsWayKeepsItsLanesLateralPathsBesideIt) {
  // Its lanes' lateral samples are its paths (as without a way), each moving it sideways from
  // where it started, after the lateral latency, at most kWayCrabSlope per metre driven,
  // turned by the angle of that move, to the sample's offset.
  for (double beside : {0.0, 0.3}) {
    Params off;
    off.bodies_on_way = false;
    const Scene scene = TurningVehicle(8.0, StraightWay(beside));
    const Problem pb = BuildProblem(scene, LateralPathsOnWay());
    const core::HypothesisSet& h = pb.cos[0];
    ASSERT_TRUE(h.on_way);
    EXPECT_EQ(h.n_paths, BuildProblem(scene, off).cos[0].n_paths);
    ASSERT_GT(h.n_paths, 2);
    const int n_steps = pb.sim.n_steps;
    std::vector<double> x(n_steps), y(n_steps), yaw(n_steps);
    double leftmost = 0.0, rightmost = 0.0;
    // How often each conditional check below ran (so that none of them can pass unrun).
    int latent_checked = 0, heading_checked = 0, paths_reaching_their_offset = 0;
    for (int path = 0; path < h.n_paths; ++path) {
      bool reached = false;
      for (int profile = 0; profile < h.n_profiles; ++profile) {
        core::SimulateHypothesis(h, pb.sim, profile, path, x.data(), y.data(), yaw.data());
        double px = 100.0, py = 50.0;
        for (int n = 0; n < n_steps; ++n) {
          const double t = (n + 1) * pb.sim.tau, dx = x[n] - px, dy = y[n] - py;
          if (t <= h.steer_latency + 1e-9) {
            EXPECT_NEAR(y[n], 50.0, 1e-9) << "path " << path << " step " << n;
            ++latent_checked;
          }
          EXPECT_LE(std::fabs(dy), core::kWayCrabSlope * std::fmax(dx, 0.0) + 1e-9)
              << "path " << path;
          if (dx > 1e-6) {
            EXPECT_NEAR(yaw[n], std::atan2(dy, dx), 1e-9) << "path " << path;
            ++heading_checked;
          }
          px = x[n];
          py = y[n];
        }
        // Where it ends: the last instant's offset, reached (8 m/s leaves it room enough) on
        // the profiles that keep it moving.
        const double last = h.way_lateral[h.n_instants - 1][path];
        if (x[n_steps - 1] - 100.0 > 10.0) {
          EXPECT_NEAR(y[n_steps - 1] - 50.0, last, 1e-6) << "path " << path;
          reached = true;
        }
        leftmost = std::fmax(leftmost, y[n_steps - 1] - 50.0);
        rightmost = std::fmin(rightmost, y[n_steps - 1] - 50.0);
      }
      paths_reaching_their_offset += reached;
    }
    const int latent_steps = static_cast<int>(h.steer_latency / pb.sim.tau + 1e-9);
    EXPECT_GE(latent_checked, h.n_paths * h.n_profiles * latent_steps);
    EXPECT_GE(heading_checked, h.n_paths * h.n_profiles);
    EXPECT_EQ(paths_reaching_their_offset, h.n_paths);  // each path on some moving profile
    EXPECT_GT(leftmost, 0.2);  // paths on both sides of its way
    EXPECT_LT(rightmost, -0.2);
    // Scored as without the way: the path along it the likeliest.
    const int along = PathAlongTheWay(h);
    ASSERT_GE(along, 0);
    for (int path = 0; path < h.n_paths; ++path)
      EXPECT_LE(pb.co_probability[path], pb.co_probability[along] + 1e-12);
  }
}

TEST(BodiesOnWay, AStandingVehicleOnItsWayDoesNotCrabSideways) {
  Scene scene = TurningVehicle(0.0, StraightWay(0.0));
  const Problem pb = BuildProblem(scene, LateralPathsOnWay());
  const core::HypothesisSet& h = pb.cos[0];
  ASSERT_TRUE(h.on_way);
  std::vector<double> x(pb.sim.n_steps), y(pb.sim.n_steps), yaw(pb.sim.n_steps);
  // The profile that brakes (it stays where it stands) on every path: never sideways.
  for (int path = 0; path < h.n_paths; ++path) {
    core::SimulateHypothesis(h, pb.sim, 0, path, x.data(), y.data(), yaw.data());
    for (int n = 0; n < pb.sim.n_steps; ++n) {
      ASSERT_NEAR(x[n], 100.0, 1e-9);
      ASSERT_NEAR(y[n], 50.0, 1e-9);
    }
  }
}

TEST(BodiesOnWay, WithoutItTheSteeredModelCannotFollowTheTurn) {
  // The check above is not met by the vehicle steering after its lanes: the same scene with
  // the mechanism off puts its front more than a metre off the 3 m turn.
  Params p;
  p.bodies_on_way = false;
  const Way way = RightTurnWay(kRadius);
  const Problem pb = BuildProblem(TurningVehicle(6.0, way), p);
  ASSERT_FALSE(pb.cos[0].on_way);
  EXPECT_GT(Stray(pb, way.points).front, 1.0);
  // Paper-literal ignores the way as well.
  EXPECT_FALSE(BuildProblem(TurningVehicle(6.0, way), ParamsPreset("paper-literal")).cos[0].on_way);
}

TEST(BodiesOnWay, AVehicleBesideItsWayKeepsItsOffsetAndStartsWhereItStands) {
  // The way 0.4 m to its right (SUMO's sublane model lets a vehicle ride off its lane's centre).
  const Way way = RightTurnWay(kRadius, -0.4);
  const Problem pb = BuildProblem(TurningVehicle(6.0, way), Params{});
  ASSERT_TRUE(pb.cos[0].on_way);
  const core::HypothesisSet& h = pb.cos[0];
  std::vector<double> x(pb.sim.n_steps), y(pb.sim.n_steps), yaw(pb.sim.n_steps);
  core::SimulateHypothesis(h, pb.sim, 0, 0, x.data(), y.data(), yaw.data());
  // The first step moves it at most its speed's distance from where it stands, not onto the way.
  EXPECT_LT(std::hypot(x[0] - 100.0, y[0] - 50.0), 6.0 * pb.sim.tau + 1e-3);
  EXPECT_NEAR(yaw[0], 0.0, 0.01);
  for (int n = 0; n < pb.sim.n_steps; ++n) {
    const double fx = x[n] - 100.0 + h.half_length * std::cos(yaw[n]);
    const double fy = y[n] - 50.0 + h.half_length * std::sin(yaw[n]);
    EXPECT_NEAR(DistanceTo(way.points, fx, fy), 0.4, 0.1) << "step " << n;
  }
}

TEST(BodiesOnWay, AWayThatDoesNotPassTheVehicleIsNotItsWay) {
  // 2 m beside it (more than kWayMaxShiftM): predicted as without a way, with its paths.
  const Problem pb = BuildProblem(TurningVehicle(6.0, RightTurnWay(kRadius, 2.0)), Params{});
  EXPECT_FALSE(pb.cos[0].on_way);
  EXPECT_GT(pb.cos[0].n_paths, 1);
}

TEST(BodiesOnWay, ATrailerOfAVehicleOnItsWayIsSteeredAlongItsOwnLane) {
  // The tractor is bound to its way; its trailer (a carriage: its own box and lanes) is not,
  // and keeps a vehicle's steering latency rather than the bound tractor's none.
  Scene scene = TurningVehicle(6.0, RightTurnWay(kRadius));
  Carriage trailer;
  trailer.x_m = 100.0 - 0.5 * kLength - 0.5 - 5.0;
  trailer.y_m = 50.0;
  trailer.length_m = 10.0;
  scene.vehicles[0].carriages.push_back(trailer);
  const Params p;
  const Problem pb = BuildProblem(scene, p);
  ASSERT_EQ(pb.cos.size(), 2u);
  EXPECT_TRUE(pb.cos[0].on_way);
  EXPECT_FALSE(pb.cos[1].on_way);
  EXPECT_EQ(pb.cos[1].n_way, 0);
  EXPECT_EQ(pb.cos[1].n_paths, 1);  // the vehicle's one path: its lane's centre
  EXPECT_EQ(pb.cos[1].steer_latency, p.steer_latency_s);
  EXPECT_EQ(pb.cos[0].steer_latency, 0.0);
  // With the tractor's lateral paths beside its way (the experiment) the trailer keeps its
  // one path on its own lane, and none of the tractor's way data.
  const Problem lateral = BuildProblem(scene, LateralPathsOnWay());
  EXPECT_GT(lateral.cos[0].n_paths, 1);
  EXPECT_EQ(lateral.cos[0].steer_latency, p.steer_latency_s);
  EXPECT_EQ(lateral.cos[1].n_paths, 1);
  EXPECT_EQ(lateral.cos[1].steer_latency, p.steer_latency_s);
  bool any = false;
  for (int k = 0; k < lateral.cos[0].n_instants; ++k) {
    for (int l = 0; l < lateral.cos[0].n_lateral; ++l) {
      any = any || lateral.cos[0].way_lateral[k][l] != 0.0;
      EXPECT_EQ(lateral.cos[1].way_lateral[k][l], 0.0);
    }
  }
  EXPECT_TRUE(any);  // (so that the check above could fail)
}

// The ego alone at the origin, heading +x at 6 m/s, on `way`.
Scene EgoInATightTurn(const Way& way) {
  Scene scene;
  scene.ego.state.speed_mps = 6.0;
  scene.ego.length_m = kLength;
  scene.ego.way = way;
  return scene;
}

TEST(BodiesOnWay, AnEgoOnItsWayFollowsATightTurnOnOnePathAsOtherVehiclesDo) {
  // The experiment Params::ego_on_way alone: the ego (at the origin, heading +x, 6 m/s) in a
  // 3 m turn gets one path, along its way, without lateral latency, as any vehicle on its way.
  const Way way = RightTurnWay(kRadius);
  const Scene scene = EgoInATightTurn(way);
  Params on;
  on.ego_on_way = true;
  const Problem pb = BuildProblem(scene, on);
  const Problem off = BuildProblem(scene, Params{});
  ASSERT_TRUE(pb.ego.on_way);
  EXPECT_EQ(pb.ego.n_paths, 1);
  EXPECT_GT(off.ego.n_paths, 1);  // steered after its lanes: the whole tree
  EXPECT_EQ(pb.ego.steer_latency, 0.0);
  EXPECT_EQ(pb.ego_probability.size(), static_cast<size_t>(pb.ego.n_profiles));
  // Every hypothesis (one per profile) keeps front and back on the way (within 1 cm) and goes
  // round the turn.
  const Offsets o = Stray(pb, way.points, -1, &pb.ego, 0.0, 0.0);
  EXPECT_LT(o.front, 0.01);
  EXPECT_LT(o.back, 0.01);
  EXPECT_GT(o.travelled, 5.0);
  // With the lateral paths along the way the tree comes back (the next test); the steered
  // ego's path with every section at its reference misses the way by more than a metre.
  Params lateral = on;
  lateral.way_lateral_paths = true;
  const Problem tree = BuildProblem(scene, lateral);
  EXPECT_EQ(tree.ego.n_paths, off.ego.n_paths);
  const int along = PathAlongTheWay(tree.ego);
  ASSERT_GE(along, 0);
  EXPECT_GT(Stray(off, way.points, along, &off.ego, 0.0, 0.0).front, 1.0);
}

TEST(BodiesOnWay, AnEgoOnItsWayWithLateralPathsFollowsATightTurnWithItsPathTreeBesideIt) {
  // Params::ego_on_way with way_lateral_paths: the ego (at the origin, heading +x, 6 m/s) in a
  // 3 m turn keeps its path tree, each path's sections as offsets beside the way.
  const Way way = RightTurnWay(kRadius);
  const Scene scene = EgoInATightTurn(way);
  Params on;
  on.ego_on_way = true;
  on.way_lateral_paths = true;
  const Problem pb = BuildProblem(scene, on);
  const Problem off = BuildProblem(scene, Params{});
  ASSERT_TRUE(pb.ego.on_way);
  EXPECT_FALSE(off.ego.on_way);  // off by default: the way is ignored
  EXPECT_EQ(pb.ego.n_paths, off.ego.n_paths);  // the same path tree
  ASSERT_GT(pb.ego.n_paths, 1);
  // The path whose every section is at its reference keeps front and back on the way, which
  // the steered ego misses by more than a metre.
  const int along = PathAlongTheWay(pb.ego);
  ASSERT_GE(along, 0);
  const Offsets o = Stray(pb, way.points, along, &pb.ego, 0.0, 0.0);
  EXPECT_LT(o.front, 0.01);
  EXPECT_LT(o.back, 0.01);
  EXPECT_GT(o.travelled, 5.0);
  EXPECT_GT(Stray(off, way.points, along, &off.ego, 0.0, 0.0).front, 1.0);
  // Its other paths move beside the way: some end more than 0.5 m from it.
  double widest = 0.0;
  std::vector<double> x(pb.sim.n_steps), y(pb.sim.n_steps), yaw(pb.sim.n_steps);
  for (int path = 0; path < pb.ego.n_paths; ++path) {
    core::SimulateHypothesis(pb.ego, pb.sim, 0, path, x.data(), y.data(), yaw.data());
    const int n = pb.sim.n_steps - 1;
    widest = std::fmax(widest, DistanceTo(way.points, x[n] + pb.ego.half_length * std::cos(yaw[n]),
                                          y[n] + pb.ego.half_length * std::sin(yaw[n])));
  }
  EXPECT_GT(widest, 0.5);
  // A scene file carries the ego's way.
  std::stringstream file;
  WriteScene(file, scene);
  const Scene back = ReadScene(file, "test");
  ASSERT_TRUE(back.ego.way.has_value());
  EXPECT_EQ(back.ego.way->points.size(), way.points.size());
  EXPECT_EQ(back.ego.way->front_m, way.front_m);
  EXPECT_EQ(testing::PCollision(scene, on), testing::PCollision(back, on));
}

TEST(BodiesOnWay, BadWaysAreOneLineErrorsNamingTheVehicle) {
  auto error_of = [](const Way& way) {
    try {
      BuildProblem(TurningVehicle(6.0, way), Params{});
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  Way one = RightTurnWay(kRadius);
  one.points.resize(1);
  EXPECT_NE(error_of(one).find("scene.vehicles[0] ('turner').way.points (count) = 1"),
            std::string::npos)
      << error_of(one);
  Way beyond = RightTurnWay(kRadius);
  beyond.front_m = 1000.0;
  EXPECT_NE(error_of(beyond).find(".way.front_m = 1000: must lie on the way"), std::string::npos)
      << error_of(beyond);
  Way nan = RightTurnWay(kRadius);
  nan.points[3].x = std::nan("");
  EXPECT_NE(error_of(nan).find(".way.points[3].x"), std::string::npos) << error_of(nan);
  Way repeated = RightTurnWay(kRadius);
  repeated.points[2] = repeated.points[1];
  EXPECT_NE(error_of(repeated).find("at least 1 cm"), std::string::npos) << error_of(repeated);
}

TEST(BodiesOnWay, AScenesWayIsWrittenAndReadBackExactly) {
  const Scene scene = TurningVehicle(6.0, RightTurnWay(kRadius, 0.1));
  std::stringstream file;
  WriteScene(file, scene);
  const Scene back = ReadScene(file, "test");
  ASSERT_TRUE(back.vehicles[0].way.has_value());
  const Way& a = *scene.vehicles[0].way;
  const Way& b = *back.vehicles[0].way;
  EXPECT_EQ(a.front_m, b.front_m);
  EXPECT_EQ(a.back_m, b.back_m);
  ASSERT_EQ(a.points.size(), b.points.size());
  for (size_t k = 0; k < a.points.size(); ++k) {
    EXPECT_EQ(a.points[k].x, b.points[k].x);
    EXPECT_EQ(a.points[k].y, b.points[k].y);
  }
  EXPECT_EQ(testing::PCollision(scene), testing::PCollision(back));
}

}  // namespace
}  // namespace criticality
