// Hypothesis set-up and scoring (paper Sec. IV-B-2, IV-D-1): probabilities per object sum to 1,
// the reference hypothesis is the most probable, penalties act as documented.
#include "src/problem.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <optional>

#include "bench/paper_scenes.h"
#include "core/hypothesis_set.h"
#include "criticality/errors.h"
#include "test_scenes.h"

namespace criticality::internal {
namespace {

TEST(Problem, ProbabilitiesOfEachObjectSumToOne) {
  for (unsigned seed = 11; seed < 19; ++seed) {
    const Scene scene = testing::RandomScene(seed, 5, 3, false);
    const Problem pb = BuildProblem(scene, Params{});
    EXPECT_NEAR(std::accumulate(pb.ego_probability.begin(), pb.ego_probability.end(), 0.0), 1.0,
                1e-12);
    for (size_t o = 0; o < pb.cos.size(); ++o) {
      double sum = 0.0;
      for (int j = pb.co_offset[o]; j < pb.co_offset[o + 1]; ++j) {
        EXPECT_GT(pb.co_probability[j], 0.0);
        sum += pb.co_probability[j];
      }
      EXPECT_NEAR(sum, 1.0, 1e-12) << "seed " << seed << " object " << o;
    }
  }
}

TEST(Problem, ReferenceHypothesisIsTheMostProbable) {
  // Cruising (zero slip) along the own lane's centre at every sample instant.
  const Problem pb = BuildProblem(bench::PaperSceneS1(), Params{});
  const auto best = std::max_element(pb.ego_probability.begin(), pb.ego_probability.end());
  const int i = static_cast<int>(best - pb.ego_probability.begin());
  EXPECT_EQ(pb.ego.profile_target[i / pb.ego.n_paths], 0.0);
  for (int k = 0; k < pb.ego.n_instants; ++k)
    EXPECT_EQ(core::SectionOfPath(pb.ego, i % pb.ego.n_paths, k), 3);
}

TEST(Problem, PaperLiteralPenalisesSectionChanges) {
  Params p = ParamsPreset("paper-literal");
  const Problem pb = BuildProblem(bench::PaperSceneS1(), p);
  const int cruise = p.profiles - 2;  // the zero profile
  auto prob = [&](int s0, int s1, int s2) {
    return pb.ego_probability[cruise * pb.ego.n_paths + s0 * 49 + s1 * 7 + s2];
  };
  // Straight into the left lane beats left-then-back (same mean offset at the samples after).
  EXPECT_GT(prob(5, 5, 5), prob(5, 3, 5));
  p.complexity_penalty = 0.0;
  const Problem flat = BuildProblem(bench::PaperSceneS1(), p);
  const double ratio_flat = flat.ego_probability[cruise * 343 + 5 * 49 + 3 * 7 + 5] /
                            flat.ego_probability[cruise * 343 + 5 * 49 + 5 * 7 + 5];
  const double ratio = prob(5, 3, 5) / prob(5, 5, 5);
  EXPECT_LT(ratio, ratio_flat);
}

TEST(Problem, PaperLiteralProfilesForEgoAreSlipsAndForOthersAccelerations) {
  const Problem pb = BuildProblem(bench::PaperSceneS1(), ParamsPreset("paper-literal"));
  EXPECT_EQ(pb.ego.model, core::MotionModelKind::kTwoTrack);
  EXPECT_FALSE(pb.ego.force_profiles);
  EXPECT_EQ(pb.ego.profile_target[0], -0.1);
  EXPECT_EQ(pb.ego.profile_target[5], 0.1);
  EXPECT_EQ(pb.cos[0].model, core::MotionModelKind::kOneTrack);
  EXPECT_EQ(pb.cos[0].profile_target[0], -9.7);
  EXPECT_EQ(pb.cos[0].profile_target[5], 9.7);
}

// Probability mass of object o's hypotheses whose path index satisfies `pick`.
template <typename Pick>
double PathMass(const Problem& pb, size_t o, Pick pick) {
  const core::HypothesisSet& h = pb.cos[o];
  double m = 0.0;
  for (int t = 0; t < h.Trajectories(); ++t) {
    if (pick(t % h.n_paths)) m += pb.co_probability[pb.co_offset[o] + t];
  }
  return m;
}

TEST(Problem, EveryObjectsLaneChangesArePenalisedPerCrossing) {
  // S1's lead car has three lanes (7 paths: 0-1 right lane, 2-4 its own, 5-6 left lane): with
  // lane_crossing_penalty 100 its four neighbour-lane paths get about 1 % (highD: about 0.75 %
  // of vehicles start a lane change within 2 s), without it a large share.
  Params p;
  const Problem pb = BuildProblem(bench::PaperSceneS1(), p);
  auto neighbour = [](int path) { return path < 2 || path > 4; };
  const double lane_change = PathMass(pb, 0, neighbour);
  EXPECT_GT(lane_change, 0.003);
  EXPECT_LT(lane_change, 0.02);
  p.lane_crossing_penalty = 1.0;
  EXPECT_GT(PathMass(BuildProblem(bench::PaperSceneS1(), p), 0, neighbour), 10 * lane_change);
  // The ego: a path that leaves its lane and comes back crosses twice (100^2), one that stays
  // in the new lane once.
  const Problem ego = BuildProblem(bench::PaperSceneS1(), Params{});
  const int ref = ego.ego_reference_trajectory / ego.ego.n_paths * ego.ego.n_paths;
  const double once = ego.ego_probability[ref + 5 * 49 + 5 * 7 + 5];
  const double twice = ego.ego_probability[ref + 5 * 49 + 3 * 7 + 3];
  EXPECT_GT(once / twice, 50.0);
}

TEST(Problem, CounterTrafficPenaltyAppliesToOtherVehiclesAsTheySeeTheirLanes) {
  // An oncoming car in the ego's left lane (counter traffic for the ego) without lanes of its
  // own: the ego's lane is ITS left lane, with traffic against it, so its paths there (the two
  // samples left of its own three) carry c_cou.
  Scene scene = bench::PaperSceneS1();
  scene.ego.lanes.right.reset();
  scene.ego.lanes.left->counter_traffic = true;
  Vehicle oncoming;
  oncoming.id = "oncoming";
  oncoming.state.x_m = 60.0;
  oncoming.state.y_m = 3.5;
  oncoming.state.yaw_rad = core::kPi;
  oncoming.state.speed_mps = 20.0;
  scene.vehicles = {oncoming};
  Params mild, strict;
  mild.counter_traffic_penalty = 1.0;
  strict.counter_traffic_penalty = 10.0;
  const Problem a = BuildProblem(scene, mild), b = BuildProblem(scene, strict);
  ASSERT_EQ(a.cos[0].n_paths, 5);  // its own lane (3) and the ego's (2), on its left
  auto into_ego_lane = [](int path) { return path >= 3; };
  const double pa = PathMass(a, 0, into_ego_lane), pb = PathMass(b, 0, into_ego_lane);
  EXPECT_GT(pa, 0.0);
  EXPECT_NEAR(pa / pb, 10.0, 0.1);  // both small: the normalisation barely moves
}

TEST(Problem, NaturalisticScoresConcentrateOnTheReference) {
  // A car at 20 m/s cruising: an emergency stop on the lane centre is rare (9.7 m/s^2 is 3.9
  // decel sigmas; its latency and ramp make it a little less in distance), full power too
  // (3.3 m/s^2 at 20 m/s, 3.3 sigmas of 1 m/s^2), gentle braking is not rare; a narrower
  // braking spread makes gentle braking less likely. The paper-literal scores keep about half
  // of the cruise score for the emergency stop.
  Params p;
  const Problem pb = BuildProblem(bench::PaperSceneS1(), p);
  const core::HypothesisSet& lead = pb.cos[0];
  auto prob = [&](const Problem& q, int profile) {
    return q.co_probability[q.co_offset[0] + profile * lead.n_paths + 3];
  };
  const int emergency = 0, gentle = 3, cruise = 4, full = 5;
  EXPECT_EQ(lead.profile_target[cruise], 0.0);
  EXPECT_LT(prob(pb, emergency) / prob(pb, cruise), 0.01);
  EXPECT_GT(prob(pb, emergency) / prob(pb, cruise), 1e-6);  // unlikely, not impossible
  EXPECT_LT(prob(pb, full) / prob(pb, cruise), 0.02);
  const Problem literal = BuildProblem(bench::PaperSceneS1(), ParamsPreset("paper-literal"));
  EXPECT_GT(prob(literal, emergency) / prob(literal, cruise), 0.3);
  EXPECT_GT(prob(pb, gentle) / prob(pb, cruise), 0.2);
  p.decel_score_sigma_mps2 = 1.0;
  const Problem narrow = BuildProblem(bench::PaperSceneS1(), p);
  EXPECT_LT(prob(narrow, gentle) / prob(narrow, cruise), 0.5 * prob(pb, gentle) / prob(pb, cruise));
  EXPECT_LT(prob(narrow, emergency) / prob(narrow, cruise), 1e-9);
}

TEST(Problem, TheCurrentAccelerationIsAProfile) {
  // Braking at 3 m/s^2 now: the profile nearest to it (-2.425) becomes -3, and the reference
  // hypothesis (holding it on the lane centre) is the most probable.
  Scene scene = bench::PaperSceneS1();
  scene.ego.state.accel_mps2 = -3.0;
  scene.vehicles[0].state.accel_mps2 = -3.0;
  const Problem pb = BuildProblem(scene, Params{});
  EXPECT_EQ(pb.cos[0].profile_target[3], -3.0);
  EXPECT_EQ(pb.ego_profile_accel[3], -3.0);
  const int i = pb.ego_reference_trajectory;
  EXPECT_EQ(i / pb.ego.n_paths, 3);
  for (int k = 0; k < pb.ego.n_instants; ++k)
    EXPECT_EQ(core::SectionOfPath(pb.ego, i % pb.ego.n_paths, k), 3);
  // The paper-literal profiles keep the zero profile.
  EXPECT_EQ(BuildProblem(scene, ParamsPreset("paper-literal")).cos[0].profile_target[4], 0.0);
}

// S1's ego alone, without its right lane, and a walker at 1.4 m/s, 20 m ahead and 1 m right of
// the ego lane's edge, heading `yaw` (0: along the road).
Scene WalkerBesideTheEgoLane(double yaw) {
  Scene scene = bench::PaperSceneS1();
  scene.vehicles.clear();
  scene.ego.lanes.right.reset();
  Pedestrian walker;
  walker.id = "walker";
  walker.state.x_m = 20.0;
  walker.state.y_m = -2.75;
  walker.state.yaw_rad = yaw;
  walker.state.speed_mps = 1.4;
  scene.pedestrians = {walker};
  return scene;
}

TEST(Problem, PedestriansStepOntoTheRoadRarely) {
  // A pedestrian walking along the kerb 1 m right of the ego lane: turning 51 deg towards the
  // road crosses the lane edge within its reach (1.4 m/s x 2 s), turning 51 deg away does not;
  // both score the same otherwise, so their ratio is the crossing penalty.
  const Scene scene = WalkerBesideTheEgoLane(0.0);
  const Problem pb = BuildProblem(scene, Params{});
  const int towards = 1, away = 6;  // headings +51 and -51 deg
  EXPECT_NEAR(PathMass(pb, 0, [&](int l) { return l == away; }) /
                  PathMass(pb, 0, [&](int l) { return l == towards; }),
              100.0, 1e-6);
  // Paper-literal: no such penalty.
  const Problem literal = BuildProblem(scene, ParamsPreset("paper-literal"));
  EXPECT_NEAR(PathMass(literal, 0, [&](int l) { return l == away; }) /
                  PathMass(literal, 0, [&](int l) { return l == towards; }),
              1.0, 1e-9);
}

TEST(Problem, APedestrianThatStaysOnTheFootwayIsExpectedToStayOffTheRoad) {
  // The walker 1 m right of the ego lane, heading 45 deg towards it: its straight-on line
  // crosses the lane edge within its reach (1.4 m/s x 2 s), turning 51 deg right (-6 deg)
  // does not. Counted against the straight-on heading, turning away is the manoeuvre; for a
  // walker that SUMO keeps on the footway, stepping onto the road is.
  Scene scene = WalkerBesideTheEgoLane(0.25 * core::kPi);
  const int straight_on = 0, away = 6;
  auto ratio = [&](const Problem& pb) {
    return PathMass(pb, 0, [&](int l) { return l == straight_on; }) /
           PathMass(pb, 0, [&](int l) { return l == away; });
  };
  const double stepping_out = ratio(BuildProblem(scene, Params{}));
  scene.pedestrians[0].stays_on_footway = true;
  const double staying = ratio(BuildProblem(scene, Params{}));
  // The two penalties of 100 swap sides.
  EXPECT_NEAR(stepping_out / staying, 1e4, 1e-6);
  EXPECT_GT(stepping_out, 1.0);
  EXPECT_LT(staying, 1.0);
  // Off in paper-literal and with Params::footway_pedestrians false.
  Params off;
  off.footway_pedestrians = false;
  EXPECT_EQ(ratio(BuildProblem(scene, off)), stepping_out);
  scene.pedestrians[0].stays_on_footway = false;
  const Problem literal = BuildProblem(scene, ParamsPreset("paper-literal"));
  scene.pedestrians[0].stays_on_footway = true;
  EXPECT_EQ(BuildProblem(scene, ParamsPreset("paper-literal")).co_probability,
            literal.co_probability);
  // Already inside the ego's lanes (SUMO's walking areas overlap a turn's lane): the straight-on
  // heading stays the reference, as for any walker.
  scene.pedestrians[0].state.y_m = -1.0;
  const Problem inside = BuildProblem(scene, Params{});
  scene.pedestrians[0].stays_on_footway = false;
  EXPECT_EQ(inside.co_probability, BuildProblem(scene, Params{}).co_probability);
}

// The ego entering a 90 degree right turn of radius r (lane 3.2 m wide), sampled at its start,
// middle and end as the SUMO driver samples a junction's turn.
Scene EgoEnteringRightTurn(double r, double speed) {
  Scene scene;
  auto divider = [&](double offset) {  // offset to the left of the centre line
    LaneDivider d;
    for (int i = 0; i < 3; ++i) {
      const double a = core::kPi / 4 * i;
      d.points[i] = Point2{(r + offset) * std::sin(a), -r + (r + offset) * std::cos(a)};
    }
    return d;
  };
  scene.ego.lanes.own = Lane{divider(1.6), divider(-1.6), false};
  scene.ego.state.speed_mps = speed;
  return scene;
}

double ReferenceProfileAccel(const Problem& pb) {
  return pb.ego_profile_accel[pb.ego_reference_trajectory / pb.ego.n_paths];
}

TEST(Problem, AReferenceTooFastForItsTurnBrakesForIt) {
  // 7.2 m/s into a 5.6 m turn asks 9.3 m/s^2 of lateral acceleration (what SUMO drives, beyond
  // what a tyre gives beside any acceleration): the reference brakes, at most normally.
  const Problem fast = BuildProblem(EgoEnteringRightTurn(5.6, 7.2), Params{});
  EXPECT_LT(ReferenceProfileAccel(fast), -2.0);
  EXPECT_GE(ReferenceProfileAccel(fast), -Params{}.curve_decel_max_mps2 - 1e-9);
  // 4 m/s asks about 3 m/s^2, within curve_lateral_accel_mps2: the current acceleration stays.
  Scene slow = EgoEnteringRightTurn(5.6, 4.0);
  slow.ego.state.accel_mps2 = 1.0;
  EXPECT_EQ(ReferenceProfileAccel(BuildProblem(slow, Params{})), 1.0);
  // An expectation lower still wins.
  Scene expecting = EgoEnteringRightTurn(5.6, 7.2);
  expecting.ego.state.expected_accel_mps2 = -6.0;
  EXPECT_EQ(ReferenceProfileAccel(BuildProblem(expecting, Params{})), -6.0);
  // Off: the current acceleration.
  Params off;
  off.curve_speed_reference = false;
  EXPECT_EQ(ReferenceProfileAccel(BuildProblem(EgoEnteringRightTurn(5.6, 7.2), off)), 0.0);
  EXPECT_FALSE(ParamsPreset("paper-literal").curve_speed_reference);
  // A gentle curve (radius 60 m) at 13.9 m/s asks 3.2 m/s^2: nothing changes.
  Scene gentle = EgoEnteringRightTurn(60.0, 13.9);
  EXPECT_EQ(ReferenceProfileAccel(BuildProblem(gentle, Params{})), 0.0);
}

TEST(Problem, PresetsAreNamed) {
  const Params literal = ParamsPreset("paper-literal");
  EXPECT_EQ(literal.scoring, Params::Scoring::kPaperLiteral);
  EXPECT_EQ(literal.steer_latency_s, 0.0);
  EXPECT_FALSE(literal.friction_limited_lateral);
  EXPECT_FALSE(literal.power_limited_drive);
  EXPECT_EQ(ParamsPreset("default").scoring, Params::Scoring::kNaturalistic);
  try {
    ParamsPreset("calibrated");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("preset = 'calibrated'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("default or paper-literal"), std::string::npos) << msg;
  }
}

// Params::hold_line_max_width_share: a narrow vehicle holds the line it rides in its lane.
// A cyclist `kerb_m` from the right divider of the ego's 3.5 m lane, 12 m ahead of the ego
// (which rides in the lane's middle), its lanes given in its own frame.
Scene CyclistAtTheKerb(double kerb_m) {
  Scene s = bench::PaperSceneS1();
  s.vehicles.resize(1);  // the lead car, 30 m ahead in the ego lane
  Vehicle bike;
  bike.id = "bike";
  bike.type.road_user = RoadUser::kBicycle;
  bike.state.x_m = 12.0;
  bike.state.y_m = -0.5 * bench::kLaneWidth + kerb_m;
  bike.state.speed_mps = 5.0;
  bike.length_m = 1.6;
  bike.width_m = 0.65;
  LaneSet lanes = bench::StraightThreeLanes();
  for (std::optional<Lane>* lane : {&lanes.own, &lanes.left, &lanes.right}) {
    for (LaneDivider* d : {&(*lane)->left, &(*lane)->right}) {
      for (Point2& q : d->points) q.y -= bike.state.y_m;  // seen from the cyclist
    }
  }
  bike.lanes = lanes;
  s.vehicles.push_back(bike);
  return s;
}

TEST(Problem, ANarrowVehicleHoldsTheLineItRidesInItsLaneACarHeadsForTheCentre) {
  const Params p;
  ASSERT_GT(p.hold_line_max_width_share, 0.0);
  const Problem pb = BuildProblem(CyclistAtTheKerb(0.5), p);
  ASSERT_EQ(pb.cos.size(), 2u);
  const core::HypothesisSet& bike = pb.cos[1];
  // Its reference path runs through it, parallel to the lane (the paper's: the lane's centre,
  // 1.25 m to its left).
  EXPECT_NEAR(bike.reference_path.Eval(0.0), 0.0, 1e-9);
  EXPECT_NEAR(bike.reference_path.Eval(30.0), 0.0, 1e-9);
  // Its own lane's samples (after the right lane's two): the one nearest to its line (a
  // quarter across) moved there, the middle and three quarters as in the paper.
  ASSERT_EQ(bike.n_lateral, 7);
  const double right = -0.5;  // its own lane's right divider, seen from it
  EXPECT_NEAR(bike.section[0][2].Eval(20.0), 0.0, 1e-9);
  EXPECT_NEAR(bike.section[0][3].Eval(20.0), right + 0.5 * bench::kLaneWidth, 1e-9);
  EXPECT_NEAR(bike.section[0][4].Eval(20.0), right + 0.75 * bench::kLaneWidth, 1e-9);
  // Its most probable path is the held line.
  const auto best = std::max_element(pb.co_probability.begin() + pb.co_offset[1],
                                     pb.co_probability.begin() + pb.co_offset[1 + 1]);
  EXPECT_EQ((best - (pb.co_probability.begin() + pb.co_offset[1])) % bike.n_paths, 2);
  // The lead car (1.8 m wide in a 3.5 m lane) is not narrow: its lane's centre.
  EXPECT_NEAR(pb.cos[0].reference_path.Eval(20.0), 0.0, 1e-9);
  EXPECT_NEAR(pb.cos[0].section[0][2].Eval(20.0), -0.25 * bench::kLaneWidth, 1e-9);

  // Closer to the kerb than its half width: held its half width inside the divider, and the
  // quarter sample (the nearest, though nearer the held line than the divider is) moves there.
  const Problem kerb = BuildProblem(CyclistAtTheKerb(0.1), p);
  EXPECT_NEAR(kerb.cos[1].reference_path.Eval(20.0), 0.325 - 0.1, 1e-9);
  EXPECT_NEAR(kerb.cos[1].section[0][2].Eval(20.0), 0.325 - 0.1, 1e-9);
  EXPECT_NEAR(kerb.cos[1].section[0][3].Eval(20.0), -0.1 + 0.5 * bench::kLaneWidth, 1e-9);

  // Off (and in paper-literal): the lane's centre, the paper's quarter samples.
  Params off = p;
  off.hold_line_max_width_share = 0.0;
  for (const Params& q : {off, ParamsPreset("paper-literal")}) {
    const Problem centre = BuildProblem(CyclistAtTheKerb(0.5), q);
    EXPECT_NEAR(centre.cos[1].reference_path.Eval(20.0), right + 0.5 * bench::kLaneWidth, 1e-9);
    EXPECT_NEAR(centre.cos[1].section[0][2].Eval(20.0), right + 0.25 * bench::kLaneWidth, 1e-9);
  }
}

// The consequence: the ego passing a cyclist who keeps 0.4 m from the kerb, 0.13 m clear of
// its right side, is judged far less likely to collide when the cyclist holds its line than
// when it is predicted into the lane's middle (0.66 against 0.87 when written).
TEST(Problem, ACarPassingACyclistAtTheKerbIsLessCriticalWhenTheCyclistHoldsItsLine) {
  Scene scene = CyclistAtTheKerb(0.4);
  scene.ego.state.speed_mps = 12.0;
  scene.vehicles[0].state.x_m = 80.0;  // the lead car far ahead
  Params off;
  off.hold_line_max_width_share = 0.0;
  const double held = testing::PCollision(scene), centre = testing::PCollision(scene, off);
  EXPECT_LT(held, centre - 0.15);
  EXPECT_LT(held, 0.9);  // below the driver's default warning threshold
}

}  // namespace
}  // namespace criticality::internal
