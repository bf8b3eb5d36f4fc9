// Street data processing: the Gauss-Jordan lane-divider fit (paper Sec. IV-A).
#include "core/lane_fit.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <random>

#include "criticality/errors.h"
#include "criticality/params.h"
#include "src/street_data.h"

namespace criticality::core {
namespace {

TEST(LaneFit, ReproducesAKnownParabola) {
  const Parabola truth{0.002, -0.05, 1.75};
  const double x[3] = {0.0, 35.0, 70.0};
  const double y[3] = {truth.Eval(x[0]), truth.Eval(x[1]), truth.Eval(x[2])};
  Parabola fit;
  ASSERT_TRUE(FitParabola(x, y, &fit));
  EXPECT_NEAR(fit.a, truth.a, 1e-12);
  EXPECT_NEAR(fit.b, truth.b, 1e-10);
  EXPECT_NEAR(fit.c, truth.c, 1e-9);
}

TEST(LaneFit, PointOrderDoesNotMatter) {
  const double x[3] = {60.0, -10.0, 25.0};
  const double y[3] = {3.0, 1.0, -2.0};
  Parabola fit;
  ASSERT_TRUE(FitParabola(x, y, &fit));
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(fit.Eval(x[i]), y[i], 1e-9);
}

TEST(LaneFit, AgreesWithEigenOnSeededRandomPoints) {
  std::mt19937_64 rng(20190609);
  std::uniform_real_distribution<double> ux(-20.0, 120.0), uy(-10.0, 10.0);
  int solved = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    double x[3], y[3];
    for (int i = 0; i < 3; ++i) {
      x[i] = ux(rng);
      y[i] = uy(rng);
    }
    if (std::abs(x[0] - x[1]) < 1.0 || std::abs(x[0] - x[2]) < 1.0 || std::abs(x[1] - x[2]) < 1.0) {
      continue;  // keep the systems well conditioned for a tight comparison
    }
    Eigen::Matrix3d m;
    Eigen::Vector3d rhs;
    for (int i = 0; i < 3; ++i) {
      m.row(i) << x[i] * x[i], x[i], 1.0;
      rhs(i) = y[i];
    }
    const Eigen::Vector3d expected = m.colPivHouseholderQr().solve(rhs);
    Parabola fit;
    ASSERT_TRUE(FitParabola(x, y, &fit));
    EXPECT_NEAR(fit.a, expected(0), 1e-9 * (1.0 + std::abs(expected(0))));
    EXPECT_NEAR(fit.b, expected(1), 1e-7 * (1.0 + std::abs(expected(1))));
    EXPECT_NEAR(fit.c, expected(2), 1e-6 * (1.0 + std::abs(expected(2))));
    ++solved;
  }
  EXPECT_GT(solved, 1000);
}

TEST(LaneFit, FailsCleanlyOnVerticalCollinearPoints) {
  // A divider running straight "up" the local frame: every point at the same forward distance.
  const double x[3] = {12.0, 12.0, 12.0};
  const double y[3] = {-5.0, 0.0, 5.0};
  Parabola fit{9.0, 9.0, 9.0};
  EXPECT_FALSE(FitParabola(x, y, &fit));
  EXPECT_EQ(fit.a, 9.0);  // untouched
}

TEST(LaneFit, FailsCleanlyOnRepeatedPoints) {
  const double x[3] = {0.0, 30.0, 30.0};
  const double y[3] = {1.0, 2.0, 2.0};
  Parabola fit;
  EXPECT_FALSE(FitParabola(x, y, &fit));
  const double x2[3] = {30.0, 30.0 + 1e-12, 60.0};
  EXPECT_FALSE(FitParabola(x2, y, &fit));
}

TEST(LaneFit, NonFiniteInputFails) {
  const double x[3] = {0.0, 30.0, 60.0};
  const double y[3] = {1.0, std::nan(""), 2.0};
  Parabola fit;
  EXPECT_FALSE(FitParabola(x, y, &fit));
}

// A road straight for 20 m that then turns left: the paper's parabola through the three samples
// bends right first (1.25 m at 10 m); fitted straight to the middle sample it does not.
TEST(LaneFit, StraightThenParabolaKeepsTheStraightBeforeTheTurn) {
  const double x[3] = {0.0, 20.0, 40.0};
  const double y[3] = {1.6, 1.6, 11.6};
  Parabola paper;
  ASSERT_TRUE(FitParabola(x, y, &paper));
  EXPECT_LT(paper.Eval(10.0), 1.6 - 1.2);  // the dip this fit removes
  Parabola fit;
  ASSERT_TRUE(FitStraightThenParabola(x, y, x[1], &fit));
  EXPECT_EQ(fit.x_start, 20.0);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(fit.Eval(x[i]), y[i], 1e-9);
  for (double xi = -10.0; xi < 20.0; xi += 2.5) {
    EXPECT_NEAR(fit.Eval(xi), 1.6, 1e-9) << xi;
    EXPECT_NEAR(fit.Slope(xi), 0.0, 1e-12) << xi;
    EXPECT_EQ(fit.Curvature(xi), 0.0) << xi;
  }
  // Beyond the straight: the parabola 1.6 + k (x - 20)^2 with k = 10 / 400, turning left.
  EXPECT_NEAR(fit.Eval(30.0), 1.6 + 2.5, 1e-9);
  EXPECT_NEAR(fit.Slope(30.0), 0.5, 1e-12);
  EXPECT_NEAR(fit.Curvature(20.0), 0.05, 1e-12);
  EXPECT_GT(fit.a, 0.0);
}

TEST(LaneFit, StraightThenParabolaFollowsASlopedStraight) {
  // The straight need not run along x (a vehicle at an angle to its lane).
  const double x[3] = {1.0, 15.0, 35.0};
  const double y[3] = {0.5, 2.6, -4.4};
  Parabola fit;
  ASSERT_TRUE(FitStraightThenParabola(x, y, x[1], &fit));
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(fit.Eval(x[i]), y[i], 1e-9);
  EXPECT_NEAR(fit.Slope(5.0), 0.15, 1e-12);
  EXPECT_NEAR(fit.Eval(8.0), 0.5 + 0.15 * 7.0, 1e-9);
  EXPECT_NEAR(fit.Slope(15.0 + 1e-9), 0.15, 1e-6);  // tangent where the turn starts
  EXPECT_LT(fit.a, 0.0);                            // turning right
}

TEST(LaneFit, StraightThenParabolaTurnsWhereItIsTold) {
  // The straight may end before or after the middle point; all three points stay on the curve.
  const double x[3] = {0.0, 20.0, 40.0};
  const double y[3] = {1.6, 1.7, 11.6};
  for (double xs : {15.0, 19.0, 20.0, 21.0, 30.0}) {
    Parabola fit;
    ASSERT_TRUE(FitStraightThenParabola(x, y, xs, &fit)) << xs;
    EXPECT_EQ(fit.x_start, xs);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(fit.Eval(x[i]), y[i], 1e-9) << xs << " point " << i;
    EXPECT_EQ(fit.Curvature(xs - 1.0), 0.0) << xs;
    EXPECT_GT(fit.Curvature(xs + 1.0), 0.0) << xs;
    // Straight before x_start, the line through point 0 with the tangent's slope.
    EXPECT_NEAR(fit.Eval(xs - 5.0) - fit.Eval(xs - 10.0), 5.0 * fit.Slope(xs), 1e-9) << xs;
  }
  Parabola fit;
  EXPECT_FALSE(FitStraightThenParabola(x, y, 0.0, &fit));   // no straight
  EXPECT_FALSE(FitStraightThenParabola(x, y, 40.0, &fit));  // no turn
}

TEST(LaneFit, StraightThenParabolaNeedsIncreasingX) {
  Parabola fit{9.0, 9.0, 9.0};
  const double y[3] = {0.0, 0.0, 5.0};
  for (const auto& x : {std::array<double, 3>{0, 30, 20}, std::array<double, 3>{10, 5, 20},
                        std::array<double, 3>{0, 0, 20}, std::array<double, 3>{0, 20, 20}}) {
    EXPECT_FALSE(FitStraightThenParabola(x.data(), y, x[1], &fit)) << x[0] << " " << x[1] << " " << x[2];
  }
  const double x[3] = {0.0, 10.0, 20.0};
  const double bad[3] = {0.0, std::nan(""), 5.0};
  EXPECT_FALSE(FitStraightThenParabola(x, bad, 10.0, &fit));
  EXPECT_EQ(fit.a, 9.0);  // untouched
  EXPECT_EQ(fit.x_start, -HUGE_VAL);
}

// A corner: straight along y = 0 to x = 6, a parabola tangent to both straights, the straight
// y = x - 10 from x = 14 (the corner at x = 10 is halfway). Catches a wrong tangent slope,
// a parabola that does not meet the second straight, one that curves on beyond x_end or
// starts before x_start, and a fit that accepts points that do not run forward.
TEST(LaneFit, CornerFollowsBothStraights) {
  const double x[3] = {0.0, 10.0, 20.0}, y[3] = {0.0, 0.0, 10.0};
  Parabola p;
  ASSERT_TRUE(FitCorner(x, y, 6.0, 14.0, &p));
  EXPECT_NEAR(p.Eval(-5.0), 0.0, 1e-12);
  EXPECT_NEAR(p.Eval(6.0), 0.0, 1e-12);
  EXPECT_NEAR(p.Slope(6.0), 0.0, 1e-12);
  EXPECT_NEAR(p.Eval(14.0), 4.0, 1e-12);
  EXPECT_NEAR(p.Slope(14.0), 1.0, 1e-12);
  EXPECT_NEAR(p.Eval(20.0), 10.0, 1e-12);
  EXPECT_NEAR(p.Eval(40.0), 30.0, 1e-12);
  EXPECT_NEAR(p.Eval(10.0), 1.0, 1e-12);  // halfway between the corner and the chord's middle
  EXPECT_EQ(p.Curvature(20.0), 0.0);
  EXPECT_GT(p.Curvature(10.0), 0.0);
  const double back[3] = {0.0, 25.0, 20.0};
  EXPECT_FALSE(FitCorner(back, y, 6.0, 14.0, &p));
  EXPECT_FALSE(FitCorner(x, y, 14.0, 6.0, &p));
}

// The host fit of a corner lane: both dividers turn over the same x and the centre follows
// the road's straights. Catches dividers fitted over their own spans (their blend would leave
// the straights), a corner flag the fit ignores, and a frame not across the bisector.
TEST(LaneFit, HostFitOfACornerLane) {
  // A 90 degree left turn: straight along y = 0 to the corner (20, 0), then north.
  LaneSet lanes;
  Lane lane;
  lane.left.points = {Point2{0, 1.6}, Point2{18.4, 1.6}, Point2{18.4, 20}};
  lane.right.points = {Point2{0, -1.6}, Point2{21.6, -1.6}, Point2{21.6, 20}};
  lane.corner_tangent_m = 8.0;
  lanes.own = lane;
  Params p;
  EXPECT_NEAR(internal::LaneFrameAngle(lanes, p), 0.25 * kPi, 1e-9);
  const internal::FittedLanes fitted = internal::FitLanes(lanes, "lanes", p);
  EXPECT_EQ(fitted.own->left.x_start, fitted.own->right.x_start);
  EXPECT_EQ(fitted.own->left.x_end, fitted.own->right.x_end);
  const Parabola centre = fitted.own->Centre();
  auto offset = [&](double x, double y) { return centre.OffsetFrom(x, y); };
  EXPECT_NEAR(offset(0.0, 0.0), 0.0, 1e-9);  // on the first straight
  EXPECT_NEAR(offset(8.0, 0.0), 0.0, 1e-9);
  EXPECT_NEAR(offset(20.0, 15.0), 0.0, 1e-9);  // on the second straight
  EXPECT_NEAR(offset(20.0, 30.0), 0.0, 1e-9);
  // Without the flag the three points (two of them off the road) give another curve.
  lanes.own->corner_tangent_m = 0.0;
  EXPECT_GT(std::fabs(internal::FitLanes(lanes, "lanes", p).own->Centre().OffsetFrom(8.0, 0.0)),
            0.5);
}

TEST(LaneFit, HostFitHonoursStraightToMiddleOnlyWhenAsked) {
  LaneSet lanes;
  Lane lane;
  lane.left.points = {Point2{0, 1.6}, Point2{20, 1.6}, Point2{40, 11.6}};
  lane.right.points = {Point2{0, -1.6}, Point2{20, -1.6}, Point2{40, 8.4}};
  lane.straight_to_middle = true;
  lanes.own = lane;
  Params p;
  const internal::FittedLanes fitted = internal::FitLanes(lanes, "lanes", p);
  EXPECT_NEAR(fitted.own->Centre().Eval(10.0), 0.0, 1e-9);
  EXPECT_NEAR(fitted.own->Centre().Eval(40.0), 10.0, 1e-9);
  p.straight_before_turn = false;  // the mark ignored: the paper's parabola and its dip
  EXPECT_LT(internal::FitLanes(lanes, "lanes", p).own->Centre().Eval(10.0), -1.2);
  EXPECT_FALSE(ParamsPreset("paper-literal").straight_before_turn);
  // Samples that do not run forward cannot be straight to the middle: a clear error.
  lanes.own->left.points[1].x = 50.0;
  try {
    internal::FitLanes(lanes, "scene.ego.lanes", Params{});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("scene.ego.lanes.own.left: straight to the middle"),
              std::string::npos)
        << e.what();
  }
}

TEST(LaneFit, HostFitNamesTheFieldOfADegenerateDivider) {
  LaneSet lanes;
  Lane lane;
  lane.right.points = {Point2{0, -1.75}, Point2{40, -1.75}, Point2{80, -1.75}};
  lane.left.points = {Point2{10, 1.75}, Point2{10, 2.0}, Point2{80, 1.75}};
  lanes.left = lane;
  try {
    internal::FitLanes(lanes, "scene.ego.lanes");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("scene.ego.lanes.left.left"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("distinct x"), std::string::npos) << e.what();
  }
}

TEST(LaneFit, HostFitRejectsSwappedDividers) {
  LaneSet lanes;
  Lane lane;
  lane.left.points = {Point2{0, -1.75}, Point2{40, -1.75}, Point2{80, -1.75}};
  lane.right.points = {Point2{0, 1.75}, Point2{40, 1.75}, Point2{80, 1.75}};
  lanes.own = lane;
  EXPECT_THROW(internal::FitLanes(lanes, "scene.ego.lanes"), InputError);
}

}  // namespace
}  // namespace criticality::core
