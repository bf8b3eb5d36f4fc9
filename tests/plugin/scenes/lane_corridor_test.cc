// Lane corridors (SUMO lane centre lines) -> the estimator's LaneSet in the vehicle frame.
#include "plugin/scenes/lane_corridor.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/geometry.h"
#include "criticality/estimator.h"
#include "src/street_data.h"

namespace criticality::plugin {
namespace {

// The traced corridor of a car 14.5 m before a sharp junction turn (SUMO's shapes, lane -9_2
// into :1_3_0 and :1_21_0; bench/RESULTS.md, tenth stop), and the car's centre on it.
LaneCorridor TracedTurnCorridor() {
  LaneCorridor c;
  c.centre = {{861.18, 663.5},  {786.92, 552.74}, {785.75, 549.79}, {784.31, 546.13},
              {785.93, 540.87}, {791.04, 536.55}, {798.9, 532.77},  {976.9, 460.42}};
  c.position_m = std::hypot(861.18 - 795.007, 663.5 - 564.802);
  c.width_m = 3.2;
  c.left = c.right = NeighbourLane{3.2, false};
  return c;
}
const Pose2 kTracedTurnPose{795.007, 564.802, -2.1614};

TEST(LaneCorridor, NorthboundLaneBecomesStraightLanesInTheVehicleFrame) {
  // A north-going lane (vertical in the world) with a neighbour on each side: in the vehicle's
  // frame the dividers must be horizontal lines at +-1.6 and +-1.6 + 3.2.
  LaneCorridor c;
  c.centre = {{50, 0}, {50, 500}};
  c.position_m = 100.0;
  c.width_m = 3.2;
  c.left = NeighbourLane{3.2, true};
  c.right = NeighbourLane{3.2, false};
  const Pose2 X_WV{50.0, 100.0, kPi / 2};
  const LaneSet set = SampleLaneSet(c, 60.0, X_WV);
  ASSERT_TRUE(set.own && set.left && set.right);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(set.own->left.points[i].x, 30.0 * i, 1e-9);
    EXPECT_NEAR(set.own->left.points[i].y, 1.6, 1e-9);
    EXPECT_NEAR(set.own->right.points[i].y, -1.6, 1e-9);
    EXPECT_NEAR(set.left->left.points[i].y, 4.8, 1e-9);
    EXPECT_NEAR(set.right->right.points[i].y, -4.8, 1e-9);
  }
  EXPECT_TRUE(set.left->counter_traffic);
  EXPECT_FALSE(set.right->counter_traffic);
}

TEST(LaneCorridor, ContinuesAroundABendIntoTheNextLane) {
  LaneCorridor c;
  c.centre = {{0, 0}, {20, 0}, {120, 100}};  // a 45 deg left bend 10 m ahead of the vehicle
  c.position_m = 10.0;
  c.width_m = 3.0;
  const LaneSet set = SampleLaneSet(c, 20.0, Pose2{10.0, 0.0, 0.0});
  ASSERT_TRUE(set.own);
  // The farthest sample lies 10 m past the bend: 7 m to the vehicle's left.
  EXPECT_NEAR(set.own->left.points[2].y, 10.0 / std::sqrt(2.0) + 1.5 / std::sqrt(2.0), 1e-9);
  // A right angle cannot be a lane y(x) in the vehicle's frame: the samples stop before it
  // (SampledReach), and the lane is the straight part up to the corner.
  c.centre = {{0, 0}, {20, 0}, {20, 100}};
  const LaneSet corner =
      SampleLaneSet(c, 20.0, Pose2{10.0, 0.0, 0.0}, LaneSampling{false, 0.35});
  ASSERT_TRUE(corner.own);
  EXPECT_LE(corner.own->left.points[2].x, 10.0);
  EXPECT_GE(corner.own->left.points[2].x, 9.0);
  for (const Point2& p : corner.own->left.points) EXPECT_NEAR(p.y, 1.5, 1e-9);
}

TEST(LaneCorridor, SamplesStopWhereAJunctionTurnLeavesTheVehiclesHeading) {
  // A right turn of radius 8 m starting at the vehicle (heading +x), then straight on in -y:
  // reach 33 m would put the farthest sample 25 m past the turn, where a parabola y(x) through
  // it first bends left. The samples stop where the turn passes 60 degrees.
  LaneCorridor c;
  const double r = 8.0;
  for (int i = 0; i <= 90; i += 5) {
    const double a = i * kPi / 180.0;
    c.centre.push_back({r * std::sin(a), -r * (1.0 - std::cos(a))});
  }
  c.centre.push_back({r, -r - 40.0});
  c.position_m = 0.0;
  c.width_m = 3.2;
  const double arc60 = r * kPi / 3.0;  // 8.4 m of arc turn the heading by 60 degrees
  const double reach = SampledReach(c, 33.0, 0.0);
  EXPECT_LE(reach, arc60 + 0.5);
  EXPECT_GE(reach, arc60 - 1.0);
  const LaneSet set =
      SampleLaneSet(c, 33.0, Pose2{0.0, 0.0, 0.0}, LaneSampling{false, 0.35});
  ASSERT_TRUE(set.own);
  // Every sample curves right, never left of the start (the fit through a sample past the
  // turn did).
  for (const Point2& p : set.own->left.points) EXPECT_LE(p.y, 1.6 + 1e-9);
  EXPECT_LT(set.own->left.points[2].y, set.own->left.points[1].y);
  // A straight lane keeps the whole reach.
  LaneCorridor straight;
  straight.centre = {{0, 0}, {100, 0}};
  EXPECT_EQ(SampledReach(straight, 33.0, 0.0), 33.0);
  EXPECT_EQ(SampledReach(straight, 33.0, 0.0, /*turn_lane_frame=*/true), 33.0);
  // In the estimator's turn frame the samples go to the end of the turn (90 degrees of arc,
  // 12.6 m) and no further: the lane then leaves the turn straight along its exit.
  const double arc90 = r * kPi / 2;
  const double turn_reach = SampledReach(c, 33.0, 0.0, /*turn_lane_frame=*/true);
  EXPECT_GE(turn_reach, arc90 - 1.0);
  EXPECT_LE(turn_reach, arc90 + 1.0);
  const LaneSet turn = SampleLaneSet(c, 33.0, Pose2{0.0, 0.0, 0.0});
  ASSERT_TRUE(turn.own);
  EXPECT_NEAR(turn.own->right.points[2].x, r - 1.6, 0.3);  // the inner divider at the exit...
  EXPECT_LT(turn.own->right.points[2].y, -r + 1.0);        // ... at the end of the turn
  EXPECT_NEAR(LaneFrameAngle(turn, Params{}), -kPi / 4, 0.1);
  // A turn of less than 60 degrees ahead keeps the whole reach.
  LaneCorridor gentle;
  gentle.centre = {{0, 0}, {10, 0}, {10 + 30 * std::cos(0.7), -30 * std::sin(0.7)}};
  EXPECT_EQ(SampledReach(gentle, 33.0, 0.0, /*turn_lane_frame=*/true), 33.0);
}

TEST(LaneCorridor, DividersThatCrossInATightTurnAreLeftOut) {
  // A 90 deg right turn with a 1.5 m radius 8 m ahead of the vehicle.
  LaneCorridor c;
  c.centre = {{0, 0}, {8, 0}};
  for (int k = 1; k <= 18; ++k) {
    const double a = kPi / 2 * k / 18.0;
    c.centre.push_back(Point2{8 + 1.5 * std::sin(a), -1.5 + 1.5 * std::cos(a)});
  }
  c.centre.push_back(Point2{9.5, -40});
  c.position_m = 0.0;
  c.width_m = 3.2;
  c.right = NeighbourLane{3.2, false};
  // Sampled up to 60 degrees into the arc (SampledReach), the right neighbour's far divider,
  // 4.8 m right of the centre line (more than the 1.5 m radius), folds back behind its middle
  // sample: that lane is left out; the own lane (+-1.6 m) stays.
  const LaneSet set =
      SampleLaneSet(c, 14.0, Pose2{0.0, 0.0, 0.0}, LaneSampling{false, 0.35});
  ASSERT_TRUE(set.own);
  for (int i = 0; i < 3; ++i) EXPECT_GT(set.own->left.points[i].y, set.own->right.points[i].y);
  EXPECT_EQ(LaneProblem(*set.own), "");
  EXPECT_FALSE(set.right);
  // On a straight corridor the same neighbour is kept: it was left out for its crossing
  // dividers, not for being a right lane.
  c.centre = {{0, 0}, {100, 0}};
  const LaneSet straight = SampleLaneSet(c, 14.0, Pose2{0.0, 0.0, 0.0});
  ASSERT_TRUE(straight.right);
  EXPECT_NEAR(straight.right->right.points[2].y, -4.8, 1e-9);
}

// A road straight for 30 m that then turns left through 90 degrees (radius 10 m).
LaneCorridor StraightThenLeftTurn() {
  LaneCorridor c;
  c.centre = {{0, 0}, {30, 0}};
  for (int k = 1; k <= 18; ++k) {
    const double a = kPi / 2 * k / 18.0;
    c.centre.push_back(Point2{30 + 10 * std::sin(a), 10 - 10 * std::cos(a)});
  }
  c.centre.push_back(Point2{40, 60});
  c.width_m = 3.2;
  c.right = NeighbourLane{3.2, false};
  return c;
}

TEST(LaneCorridor, AStraightBeforeATurnIsSampledToWhereTheTurnStarts) {
  const LaneCorridor c = StraightThenLeftTurn();
  EXPECT_NEAR(StraightBeforeTurn(c, 45.0), 30.5, 0.5);
  const LaneSet set = SampleLaneSet(c, 45.0, Pose2{0.0, 0.0, 0.0});
  ASSERT_TRUE(set.own && set.right);
  EXPECT_TRUE(set.own->straight_to_middle);
  EXPECT_TRUE(set.right->straight_to_middle);
  // Where the straight ends: the centre line's first 5 degree segment of the arc still counts
  // (its chord turns 2.5 degrees).
  EXPECT_NEAR(set.own->left.points[1].x, 30.5, 0.5);
  EXPECT_NEAR(set.own->left.points[1].y, 1.6, 0.05);
  // As the estimator fits it, the lane's centre stays on the straight up to the turn and then
  // turns left; sampled at 0, reach/2 and reach (paper-literal sampling), the parabola bends
  // more than a metre to the right on the straight first.
  const core::Parabola centre = internal::FitLanes(set, "lanes", Params{}).own->Centre();
  for (double x = 0.0; x <= 30.0; x += 2.5) EXPECT_NEAR(centre.Eval(x), 0.0, 0.05) << x;
  EXPECT_GT(centre.Eval(38.0), 5.0);
  LaneSampling paper;
  paper.straight_before_turn = false;
  paper.centre_within_lane = false;
  const LaneSet halves = SampleLaneSet(c, 45.0, Pose2{0.0, 0.0, 0.0}, paper);
  ASSERT_TRUE(halves.own);
  EXPECT_FALSE(halves.own->straight_to_middle);
  EXPECT_NEAR(halves.own->left.points[1].x, 22.5, 1e-9);
  const core::Parabola dipping = internal::FitLanes(halves, "lanes", Params{}).own->Centre();
  double lowest = 0.0;
  for (double x = 0.0; x <= 30.0; x += 0.5) lowest = std::fmin(lowest, dipping.Eval(x));
  EXPECT_LT(lowest, -1.0);
  EXPECT_FALSE(LaneSamplingFor(ParamsPreset("paper-literal")).straight_before_turn);
  EXPECT_TRUE(LaneSamplingFor(Params{}).straight_before_turn);
}

// The traced case (a user-style netgenerate run, 0.2 s steps, bench/RESULTS.md): car16 at
// 7.3 m/s, 14.5 m before the end of its lane -9_2, turning left through SUMO's internal lanes
// :1_3_0 and :1_21_0 (which first veer 12 degrees right) onto 19_2, a truck waiting in the
// lane to its right. Sampled over 36 m, the parabola through the three samples swings out of
// the lane to the right; the car's reference followed it into the truck (p 0.96, no collision
// followed). With LaneSampling::centre_within_lane the lane is sampled over a shorter reach.
TEST(LaneCorridor, ALaneWhoseFitLeavesItIsSampledShorter) {
  const LaneCorridor c = TracedTurnCorridor();
  const Pose2 X_WV = kTracedTurnPose;
  constexpr double kReach = 36.0;
  const std::vector<Point2> centre = CentreLineAhead(c, X_WV, kReach);
  const std::vector<Point2> approach(centre.begin(), centre.begin() + 15);  // the straight
  auto deviation = [](const LaneSet& set, const std::vector<Point2>& line) {
    return LaneCentreDeviation(*set.own, LaneFrameAngle(set, Params{}), line);
  };
  LaneSampling unchecked;
  unchecked.centre_within_lane = false;
  unchecked.straight_by_fit = false;
  const LaneSet full = SampleLaneSet(c, kReach, X_WV, unchecked);
  ASSERT_TRUE(full.own);
  EXPECT_NEAR(full.own->left.points[1].x, 16.6, 0.1);  // the recorded scene's samples
  EXPECT_NEAR(full.own->left.points[2].y, 12.4, 0.1);
  EXPECT_GT(deviation(full, centre), 0.5 * c.width_m);
  LaneSampling checking;
  checking.straight_by_fit = false;
  const LaneSet checked = SampleLaneSet(c, kReach, X_WV, checking);
  ASSERT_TRUE(checked.own);
  EXPECT_LT(checked.own->left.points[2].y, full.own->left.points[2].y - 3.0);  // shorter
  // Along the straight the car is on, the shorter fit strays less.
  EXPECT_LT(deviation(checked, approach), deviation(full, approach) - 0.5);
  // By default (LaneSampling::straight_by_fit) the car at its speed, 7.3 m/s, gets the straight
  // to the turn and the turn over the full reach: within the lane, and on the straight closer
  // than either.
  LaneCorridor at_speed = c;
  at_speed.speed_mps = 7.3;
  const LaneSet chosen = SampleLaneSet(at_speed, kReach, X_WV);
  ASSERT_TRUE(chosen.own);
  EXPECT_TRUE(chosen.own->straight_to_middle);
  EXPECT_NEAR(chosen.own->left.points[2].y, full.own->left.points[2].y, 1e-9);  // full reach
  EXPECT_LT(deviation(chosen, centre), 0.5 * c.width_m);
  EXPECT_LT(deviation(chosen, approach), 0.05);
  // A lane that the fit follows keeps its reach: the straight road.
  LaneCorridor straight;
  straight.centre = {{0, 0}, {100, 0}};
  const LaneSet road = SampleLaneSet(straight, 33.0, Pose2{});
  ASSERT_TRUE(road.own);
  EXPECT_NEAR(road.own->left.points[2].x, 33.0, 1e-9);
  EXPECT_FALSE(LaneSamplingFor(ParamsPreset("paper-literal")).centre_within_lane);
  EXPECT_TRUE(LaneSamplingFor(Params{}).centre_within_lane);
}

// A road east, a 90 degree left turn of radius 10 m, a road north: the corner is where the
// roads' lines meet, the turn begins and ends R tan(45 deg) = 10 m from it. Catches a corner
// from the wrong headings, a tangent length measured from the wrong end, and a corner
// reported for a road that does not turn enough.
TEST(LaneCorridor, CornerOfAStraightATurnAndAStraight) {
  std::vector<Point2> line{{0, 0}, {20, 0}};
  for (int i = 1; i <= 90; ++i) {
    const double a = i * kPi / 180.0;
    line.push_back(Point2{20 + 10 * std::sin(a), 10 - 10 * std::cos(a)});
  }
  line.push_back(Point2{30, 40});
  const double arc = 10.0 * kPi / 2.0;
  const std::optional<Corner> c = CornerOf(line, 0.0, 20.0 + arc + 20.0);
  ASSERT_TRUE(c);
  EXPECT_NEAR(c->corner.x, 30.0, 0.05);
  EXPECT_NEAR(c->corner.y, 0.0, 0.05);
  EXPECT_NEAR(c->in_m, 30.0, 0.05);
  EXPECT_NEAR(c->out_m, 30.0, 0.05);
  EXPECT_NEAR(c->tangent_m, 10.0, 0.6);  // the line's headings are read every 0.5 m
  // 2 m before the turn: still a corner; in the turn: none (the parabola through the turn).
  EXPECT_TRUE(CornerOf(line, 17.5, 20.0 + arc + 20.0));
  EXPECT_FALSE(CornerOf(line, 20.0 + 0.5 * arc, 20.0 + arc + 20.0));
  EXPECT_FALSE(CornerOf(line, 19.0, 20.0 + arc + 20.0));
  EXPECT_FALSE(CornerOf(line, 0.0, 19.0));                            // straight
  EXPECT_FALSE(CornerOf(line, 0.0, 20.0 + 10.0 * 0.2));               // turned 11 degrees
  EXPECT_FALSE(CornerOf(line, 20.0 + arc + 1.0, 20.0 + arc + 20.0));  // straight again
}

// The traced corridor of ALaneWhoseFitLeavesItIsSampledShorter (a 14 m straight into a sharp
// junction turn), sampled as a corner over the full reach: its fitted centre is the straight
// on the straight and stays within the lane, where three samples on the road left it.
// Catches corner samples that are not the straights' meeting point, a tangent not chosen by
// its fit, and a corner the sampler does not mark.
TEST(LaneCorridor, ACornerFollowsAShortStraightIntoASharpTurn) {
  const LaneCorridor c = TracedTurnCorridor();
  const Pose2 X_WV = kTracedTurnPose;
  constexpr double kReach = 36.0;
  const std::vector<Point2> centre = CentreLineAhead(c, X_WV, kReach);
  LaneSampling corners;
  corners.corners = true;
  corners.centre_within_lane = false;
  const LaneSet set = SampleLaneSet(c, kReach, X_WV, corners);
  ASSERT_TRUE(set.own && set.left && set.right);
  EXPECT_GT(set.own->corner_tangent_m, 0.0);
  EXPECT_EQ(set.left->corner_tangent_m, set.own->corner_tangent_m);
  EXPECT_FALSE(set.own->straight_to_middle);
  EXPECT_NEAR(set.own->left.points[2].y, 12.4, 0.1);  // the full reach
  Params params;
  params.lane_corners = true;
  const std::vector<Point2> approach(centre.begin(), centre.begin() + 15);  // the straight
  auto deviation = [&](const LaneSet& lanes, const std::vector<Point2>& line) {
    return LaneCentreDeviation(*lanes.own, LaneFrameAngle(lanes, params), line);
  };
  LaneSampling samples;
  samples.centre_within_lane = false;
  samples.straight_by_fit = false;
  const LaneSet three = SampleLaneSet(c, kReach, X_WV, samples);
  ASSERT_TRUE(three.own);
  // Over the whole reach the corner keeps within the lane (the lane-fit check takes it at the
  // full reach) and strays less than half as far as three samples on the road; on the
  // straight it keeps within 0.1 m of it.
  EXPECT_LT(deviation(set, centre), 0.5 * c.width_m);
  EXPECT_LT(deviation(set, centre), 0.5 * deviation(three, centre));
  EXPECT_LT(deviation(set, approach), 0.1);
  EXPECT_GT(deviation(three, approach), 0.5);
  // The tangent length sent is the one whose fit keeps closest to the road: here closer than
  // CornerOf's first estimate from where the road's heading changes.
  const std::optional<Corner> first = CornerOf(c.centre, c.position_m, c.position_m + kReach);
  ASSERT_TRUE(first);
  EXPECT_NE(set.own->corner_tangent_m, first->tangent_m);
  LaneSet estimate = set;
  estimate.own->corner_tangent_m = first->tangent_m;
  EXPECT_LT(deviation(set, centre), deviation(estimate, centre));
  EXPECT_FALSE(LaneSamplingFor(Params{}).corners);
  EXPECT_TRUE(LaneSamplingFor(params).corners);
}

TEST(LaneCorridor, OnlyAStraightFollowedByATurnIsSampledToItsEnd) {
  // Straight all the way, turning from the start (a constant curve), or a straight that ends
  // too close to the reach: the paper's sampling.
  LaneCorridor straight;
  straight.centre = {{0, 0}, {100, 0}};
  EXPECT_EQ(StraightBeforeTurn(straight, 45.0), 0.0);
  EXPECT_FALSE(SampleLaneSet(straight, 45.0, Pose2{}).own->straight_to_middle);
  LaneCorridor curve;
  for (int k = 0; k <= 60; ++k) {
    const double a = 1.2 * k / 60.0;  // radius 40 m, turning from the start
    curve.centre.push_back(Point2{40 * std::sin(a), 40 - 40 * std::cos(a)});
  }
  EXPECT_EQ(StraightBeforeTurn(curve, 45.0), 0.0);
  const LaneCorridor c = StraightThenLeftTurn();
  EXPECT_EQ(StraightBeforeTurn(c, 33.0), 0.0);  // 3 m of turn within the reach
  EXPECT_EQ(StraightBeforeTurn(c, 30.0), 0.0);  // no turn within the reach
  LaneCorridor later = c;
  later.position_m = 20.0;  // 10 m of straight left: a junction turn, sampled as the paper does
  EXPECT_EQ(StraightBeforeTurn(later, 30.0), 0.0);
  later.position_m = 12.0;  // 18 m of straight left
  EXPECT_NEAR(StraightBeforeTurn(later, 30.0), 18.0, 0.5);
}

// LaneSampling::straight_by_fit: 2-15 m of straight before a turn (StraightBeforeTurn leaves
// those to the parabola through the reach's middle). At each place on the approach the set
// sent keeps at least as close to the road as the plain one; at some the straight's end wins,
// at others the plain samples; and a vehicle too fast to steer in within kSteerLeadS keeps the
// plain samples. Catches a choice that ignores the fits (always or never the straight), one
// that compares the wrong fits, and an ignored speed.
TEST(LaneCorridor, AShortStraightBeforeATurnIsSampledToItsEndWhereThatFitsBetter) {
  constexpr double kReach = 30.0;
  LaneSampling plain;
  plain.straight_by_fit = false;
  auto deviation = [](const LaneSet& set, const std::vector<Point2>& line) {
    return LaneCentreDeviation(*set.own, LaneFrameAngle(set, Params{}), line);
  };
  int to_the_straights_end = 0, plain_kept = 0;
  // (StraightBeforeTurn measures up to 1 m more: the arc's first segment turns by 5 degrees.)
  for (double straight = 2.5; straight < 13.5; straight += 0.5) {
    LaneCorridor c = StraightThenLeftTurn();
    c.position_m = 30.0 - straight;
    const Pose2 X_WV{c.position_m, 0.0, 0.0};
    const std::vector<Point2> road = CentreLineAhead(c, X_WV, kReach);
    const LaneSet sent = SampleLaneSet(c, kReach, X_WV);
    const LaneSet three = SampleLaneSet(c, kReach, X_WV, plain);
    ASSERT_TRUE(sent.own && three.own) << straight;
    EXPECT_FALSE(three.own->straight_to_middle) << straight;
    EXPECT_LE(deviation(sent, road), deviation(three, road) + 1e-12) << straight;
    if (sent.own->straight_to_middle) {
      ++to_the_straights_end;
      EXPECT_NEAR(sent.own->left.points[1].x, straight, 0.5) << straight;
      EXPECT_LT(deviation(sent, road), deviation(three, road)) << straight;
    } else {
      ++plain_kept;
      EXPECT_EQ(sent.own->left.points[1].x, three.own->left.points[1].x) << straight;
    }
    // Too fast to steer into the turn before the straight ends: the plain samples.
    c.speed_mps = (straight + 2.0) / kSteerLeadS;
    const LaneSet fast = SampleLaneSet(c, kReach, X_WV);
    ASSERT_TRUE(fast.own) << straight;
    EXPECT_FALSE(fast.own->straight_to_middle) << straight;
  }
  EXPECT_GT(to_the_straights_end, 0);
  EXPECT_GT(plain_kept, 0);
  EXPECT_TRUE(LaneSamplingFor(Params{}).straight_by_fit);
  EXPECT_FALSE(LaneSamplingFor(ParamsPreset("paper-literal")).straight_by_fit);
  Params off;
  off.straight_before_turn_by_fit = false;
  EXPECT_FALSE(LaneSamplingFor(off).straight_by_fit);
  off = Params{};
  off.straight_before_turn = false;  // the estimator would ignore the mark
  EXPECT_FALSE(LaneSamplingFor(off).straight_by_fit);
}

TEST(LaneCorridor, LaneYawRateFollowsTheLaneNotThePast) {
  LaneCorridor c = StraightThenLeftTurn();  // radius 10 m from 30 m on
  c.position_m = 10.0;
  EXPECT_EQ(LaneYawRate(c, 8.0, 2.5), 0.0);  // on the straight
  // Halfway through the turn: v / r, within the polyline's 5 degree segments (a 5 m window
  // sees 25-30 degrees of them).
  c.position_m = 30.0 + 10.0 * kPi / 4;
  EXPECT_NEAR(LaneYawRate(c, 8.0, 2.5), 8.0 / 10.0, 0.11);
  c.position_m = 30.0;  // entering it: half the window turns
  EXPECT_NEAR(LaneYawRate(c, 8.0, 2.5), 0.4, 0.06);
  // A car that has just left a turn onto a straight lane: the corridor starts with that lane,
  // and what lies behind its start counts as straight.
  LaneCorridor exit;
  exit.centre = {{0, 0}, {0, 100}};
  exit.position_m = 1.0;
  EXPECT_EQ(LaneYawRate(exit, 5.0, 2.5), 0.0);
  EXPECT_EQ(LaneYawRate(LaneCorridor{}, 5.0, 2.5), 0.0);
}

// LaneSampling::corner_in_turn, traced on a netgenerate grid (bench/RESULTS.md, seventeenth
// stop): a car whose front has entered SUMO's right turn :D3_3_0 (1.6 m radius on 3.2 m lanes,
// so the inner divider, offset by half the width, folds to a point) and whose centre is 0.47 m
// before it, 27.6 m of reach, its heading already 13 degrees into the turn. No reach of three
// samples gives a usable own lane; the corner from where it is does, and keeps within 0.1 m
// of the road. Catches a fallback that never runs (no lanes), one that runs where three samples
// work (the set would change), and one that sends a corner leaving the lane.
TEST(LaneCorridor, ATurnTooTightForThreeSamplesIsSentAsACornerFromWhereTheVehicleIs) {
  LaneCorridor c;
  c.centre = {{590.4, 592.0}, {591.1, 591.9}, {591.6, 591.6},
              {591.9, 591.1}, {592.0, 590.4}, {592.0, 413.6}};
  c.position_m = -0.471;
  c.width_m = 3.2;
  c.left = NeighbourLane{3.2, false};
  const Pose2 X_WV{589.4882, 591.5167, -0.23051};
  LaneSampling without;
  LaneSampling with;
  with.corner_in_turn = true;
  EXPECT_FALSE(SampleLaneSet(c, 27.616, X_WV, without).own);
  const LaneSet set = SampleLaneSet(c, 27.616, X_WV, with);
  ASSERT_TRUE(set.own);
  EXPECT_GT(set.own->corner_tangent_m, 0.0);
  Params params;
  const std::vector<Point2> road = CentreLineAhead(c, X_WV, 5.0);
  EXPECT_LT(LaneCentreDeviation(*set.own, LaneFrameAngle(set, params), road), 0.1);
  // Where three samples work (the same car 20 m before the turn) nothing changes.
  LaneCorridor before = c;
  before.centre.insert(before.centre.begin(), Point2{560.4, 592.0});
  before.position_m = 10.0;
  const Pose2 X_WB{570.4, 592.0, 0.0};
  const LaneSet plain = SampleLaneSet(before, 27.616, X_WB, without);
  const LaneSet sent = SampleLaneSet(before, 27.616, X_WB, with);
  ASSERT_TRUE(plain.own && sent.own);
  EXPECT_EQ(sent.own->corner_tangent_m, 0.0);
  EXPECT_EQ(sent.own->left.points[2].x, plain.own->left.points[2].x);
  EXPECT_FALSE(LaneSamplingFor(Params{}).corner_in_turn);  // an experiment: off
  params.lane_corner_in_turn = true;
  EXPECT_TRUE(LaneSamplingFor(params).corner_in_turn);
}

TEST(LaneCorridor, VehicleAcrossItsLaneGetsNoLanes) {
  LaneCorridor c;
  c.centre = {{0, 0}, {100, 0}};
  c.position_m = 20.0;
  // Heading north while the lane runs east: the samples do not run forward.
  EXPECT_FALSE(SampleLaneSet(c, 40.0, Pose2{20.0, 0.0, kPi / 2}).own);
  EXPECT_FALSE(SampleLaneSet(LaneCorridor{}, 40.0, Pose2{}).own);
}

TEST(LaneCorridor, ARightTurnEndingAcrossTheHeadingIsSampledShorterInsteadOfDropped) {
  // A car westbound 30 m before a junction where its lane turns right (through two short segments) to the north,
  // as in a netgenerate grid: sampled to the turn's end, both dividers' far samples lie across
  // its heading at the same y, which no parabola y(x) can pass through. The lane is then
  // sampled where the paper's frame can still follow the turn, not dropped (a vehicle without
  // lanes is predicted straight on, through the junction).
  LaneCorridor c;
  // SUMO's internal lane of the turn has few points; its far sample lies on the northbound lane.
  c.centre = {{200.0, 0.0}, {170.0, 0.0}, {166.0, 2.0}, {164.0, 6.0}, {164.0, 60.0}};
  c.position_m = 0.0;
  c.width_m = 3.2;
  const LaneSet set = SampleLaneSet(c, 40.0, Pose2{200.0, 0.0, kPi});
  ASSERT_TRUE(set.own.has_value());
  // The lane's centre at the far sample: into the turn, beyond the straight, turning right
  // (the vehicle's -y).
  const Point2 far{0.5 * (set.own->left.points[2].x + set.own->right.points[2].x),
                   0.5 * (set.own->left.points[2].y + set.own->right.points[2].y)};
  EXPECT_LT(far.y, -0.5);
  EXPECT_GT(far.x, 30.0);
  EXPECT_LT(far.x, 40.0);
  EXPECT_EQ(LaneProblem(*set.own, LaneFrameAngle(set, Params{})), "");
}

}  // namespace
}  // namespace criticality::plugin
