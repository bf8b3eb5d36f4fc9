// Street data processing (paper Sec. IV-A): the ego's lanes as another vehicle sees them
// (EgoLanesSeenBy): which lanes, expressed in its frame, left and right swapped for oncoming
// traffic, counter-traffic flags relative to it.
#include "src/street_data.h"

#include <gtest/gtest.h>

#include "bench/paper_scenes.h"
#include "core/geometry.h"
#include "core/lane_fit.h"
#include "criticality/errors.h"

namespace criticality::internal {
namespace {

// Lateral position of a divider in the observer's frame at forward distance x.
double YAt(const LaneDivider& d, double x) {
  double xs[3], ys[3];
  for (int i = 0; i < 3; ++i) xs[i] = d.points[i].x, ys[i] = d.points[i].y;
  core::Parabola p;
  EXPECT_TRUE(core::FitParabola(xs, ys, &p));
  return p.Eval(x);
}

TEST(EgoLanesSeenBy, SameDirectionNeighbourSeesTheEgoLaneOnItsRight) {
  const LaneSet ego = bench::StraightThreeLanes();  // lanes at y in [-5.25, 5.25], 3.5 m wide
  const core::Pose2 X_EV{20.0, 3.5, 0.0};           // in the ego's left lane, same heading
  const LaneSet seen = EgoLanesSeenBy(ego, X_EV, LaneIndex::kLeft);
  ASSERT_TRUE(seen.own && seen.right);
  EXPECT_FALSE(seen.left);  // nothing left of the ego's left lane
  // Its own lane is centred on it; the ego lane is the next one to its right.
  EXPECT_NEAR(YAt(seen.own->left, 0.0), 1.75, 1e-9);
  EXPECT_NEAR(YAt(seen.own->right, 0.0), -1.75, 1e-9);
  EXPECT_NEAR(YAt(seen.right->left, 0.0), -1.75, 1e-9);
  EXPECT_NEAR(YAt(seen.right->right, 0.0), -5.25, 1e-9);
  // Points moved into its frame: the ego's divider point at x = 40 is 20 m ahead of it.
  EXPECT_NEAR(seen.own->left.points[1].x, 20.0, 1e-9);
  EXPECT_FALSE(seen.own->counter_traffic);
  EXPECT_FALSE(seen.right->counter_traffic);
}

TEST(EgoLanesSeenBy, OncomingCarSwapsLeftAndRightAndFlagsTheEgoLaneAsCounterTraffic) {
  // A two-way road: the ego's lane and, on its left, the oncoming lane (counter traffic for the
  // ego). An oncoming car in that lane sees it as its own lane (not counter traffic for it) and
  // the ego's lane on ITS left, carrying traffic against it.
  LaneSet ego = bench::StraightThreeLanes();
  ego.right.reset();
  ego.left->counter_traffic = true;
  const core::Pose2 X_EV{40.0, 3.5, core::kPi};
  const LaneSet seen = EgoLanesSeenBy(ego, X_EV, LaneIndex::kLeft);
  ASSERT_TRUE(seen.own && seen.left);
  EXPECT_FALSE(seen.right);
  EXPECT_FALSE(seen.own->counter_traffic);
  EXPECT_TRUE(seen.left->counter_traffic);
  // In its frame (x forward = the ego's -x, y left = the ego's -y): its lane spans y in
  // [-1.75, 1.75], the ego's lane [1.75, 5.25] on its left; the left divider of each is the
  // one with the larger y in its frame, so the ego lane's RIGHT divider (y = -1.75 for the
  // ego) is its left lane's LEFT divider (5.25).
  EXPECT_NEAR(YAt(seen.own->left, 0.0), 1.75, 1e-9);
  EXPECT_NEAR(YAt(seen.own->right, 0.0), -1.75, 1e-9);
  EXPECT_NEAR(YAt(seen.left->right, 0.0), 1.75, 1e-9);
  EXPECT_NEAR(YAt(seen.left->left, 0.0), 5.25, 1e-9);
  // The ego's divider point at x = 0 is 40 m ahead of it.
  EXPECT_NEAR(seen.own->left.points[0].x, 40.0, 1e-9);
}

TEST(EgoLanesSeenBy, CounterTrafficIsRelativeToTheObserver) {
  // A car driving with the ego in its right lane, on a road whose left lane carries oncoming
  // traffic: from the ego's own lane (seen as its left lane) nothing is counter traffic for it.
  LaneSet ego = bench::StraightThreeLanes();
  ego.left->counter_traffic = true;
  const LaneSet seen = EgoLanesSeenBy(ego, core::Pose2{-15.0, -3.5, 0.0}, LaneIndex::kRight);
  ASSERT_TRUE(seen.own && seen.left);
  EXPECT_FALSE(seen.right);
  EXPECT_FALSE(seen.own->counter_traffic);
  EXPECT_FALSE(seen.left->counter_traffic);
  // And a car in the ego's lane sees the oncoming lane on its left as counter traffic.
  const LaneSet mid = EgoLanesSeenBy(ego, core::Pose2{30.0, 0.0, 0.0}, LaneIndex::kOwn);
  ASSERT_TRUE(mid.left && mid.right);
  EXPECT_TRUE(mid.left->counter_traffic);
  EXPECT_FALSE(mid.right->counter_traffic);
}

TEST(EgoLanesSeenBy, CrossingCarOrNoLaneGetsNothing) {
  const LaneSet ego = bench::StraightThreeLanes();
  // Crossing: the ego's dividers are vertical lines in its frame, not functions y(x).
  EXPECT_FALSE(EgoLanesSeenBy(ego, core::Pose2{20.0, 0.0, core::kPi / 2}, LaneIndex::kOwn).own);
  EXPECT_FALSE(EgoLanesSeenBy(ego, core::Pose2{20.0, 9.0, 0.0}, LaneIndex::kNone).own);
  LaneSet no_left = ego;
  no_left.left.reset();
  EXPECT_FALSE(EgoLanesSeenBy(no_left, core::Pose2{20.0, 3.5, 0.0}, LaneIndex::kLeft).own);
}


// A 90 degree right turn of radius 8 m from the observer (heading +x), 3.2 m wide, sampled at
// its start, middle and end (what the SUMO driver gives a car entering a junction's turn).
Lane RightTurnLane() {
  const double r = 8.0;
  auto divider = [&](double offset) {  // offset to the left of the centre line
    LaneDivider d;
    const double rr = r + offset;  // centre of the turn at (0, -r)
    for (int i = 0; i < 3; ++i) {
      const double a = core::kPi / 4 * i;
      d.points[i] = Point2{rr * std::sin(a), -r + rr * std::cos(a)};
    }
    return d;
  };
  return Lane{divider(1.6), divider(-1.6), false};
}

TEST(TurnLaneFrame, AJunctionTurnIsFittedAlongItsChordAndLeavesItStraight) {
  const LaneSet lanes{RightTurnLane(), std::nullopt, std::nullopt};
  Params p;
  const double frame = LaneFrameAngle(lanes, p);
  EXPECT_NEAR(frame, -core::kPi / 4, 1e-9);  // the chord from (0, 0) to (8, -8)
  const FittedLanes turned = FitLanes(lanes, "lanes", p);
  const core::Parabola centre = turned.own->Centre();
  // Beyond the turn the lane runs on along the exit (x = 8): a parabola through three points
  // of the arc leaves it less than 5 degrees off (8 cm per metre).
  double xr, yr;
  centre.ToFrame(8.0, -8.0, &xr, &yr);
  for (double beyond = 0.0; beyond <= 15.0; beyond += 1.0) {
    double x, y;
    centre.PointAt(xr + beyond * std::cos(core::kPi / 4), &x, &y);
    EXPECT_NEAR(x, 8.0, 0.1 + 0.08 * beyond) << beyond << " m beyond the turn";
  }
  // It leaves the turn heading along the exit (-90 degrees), within 5 degrees.
  EXPECT_NEAR(centre.Direction(xr + 5.0), -core::kPi / 2, 0.0873);
  // Paper-literal keeps the observer's frame.
  Params paper = p;
  paper.turn_lane_frame = false;
  EXPECT_EQ(LaneFrameAngle(lanes, paper), 0.0);
  // Association in the turned frame: a point on the arc's middle is in the lane, one 2.5 m
  // outside the arc is not.
  const double m = core::kPi / 8;
  EXPECT_EQ(AssociateLane(turned, 8.0 * std::sin(m), -8.0 + 8.0 * std::cos(m)), LaneIndex::kOwn);
  EXPECT_EQ(AssociateLane(turned, 10.5 * std::sin(m), -8.0 + 10.5 * std::cos(m)),
            LaneIndex::kNone);
}

TEST(TurnLaneFrame, StraightLanesAndLanesAgainstTheHeadingKeepThePapersFrame) {
  Params p;
  LaneSet straight;
  straight.own = Lane{LaneDivider{{Point2{0, 1.6}, Point2{20, 1.7}, Point2{40, 1.9}}},
                      LaneDivider{{Point2{0, -1.6}, Point2{20, -1.5}, Point2{40, -1.3}}}, false};
  EXPECT_EQ(LaneFrameAngle(straight, p), 0.0);
  // Sampled against the direction of travel (a car overtaking on the oncoming lane): the chord
  // points backwards; no frame makes it a lane ahead, and the paper's fit rejects it.
  LaneSet backwards;
  backwards.own = Lane{LaneDivider{{Point2{4.5, -1.75}, Point2{2, -1.75}, Point2{-0.5, -1.75}}},
                       LaneDivider{{Point2{4.5, 1.75}, Point2{2, 1.75}, Point2{-0.5, 1.75}}}, false};
  EXPECT_EQ(LaneFrameAngle(backwards, p), 0.0);
  EXPECT_THROW(FitLanes(backwards, "lanes", p), InputError);
}

}  // namespace
}  // namespace criticality::internal
