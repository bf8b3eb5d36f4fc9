// Street data processing: the Gauss-Jordan lane-divider fit (paper Sec. IV-A).
#include "core/lane_fit.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "criticality/errors.h"
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
