// Long bodies as chains of boxes: how a SUMO vehicle is cut (its vType's carriage parameters,
// or equal carriages) and where the carriages stand (along the lanes the vehicle came by).
#include "plugin/scenes/carriages.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "../fake_sumo_world.h"

namespace criticality::plugin {
namespace {

using testing::FakeSumoWorld;

double Total(const BodyPlan& p) {
  double t = p.head_length_m;
  for (double l : p.carriage_lengths_m) t += p.gap_m + l;
  return t;
}

TEST(Carriages, SumosCarriageParametersCutTheBody) {
  VehicleTypeReport freight;  // SUMO's rail demo: locomotive 12 m, carriages 10 m, gaps 0.3 m
  freight.locomotive_length_m = 12.0;
  freight.carriage_length_m = 10.0;
  freight.carriage_gap_m = 0.3;
  const BodyPlan p = PlanBody(72.0, 2.8, freight);
  EXPECT_DOUBLE_EQ(p.head_length_m, 12.0);
  ASSERT_EQ(p.carriage_lengths_m.size(), 6u);
  for (int k = 0; k < 5; ++k) EXPECT_DOUBLE_EQ(p.carriage_lengths_m[k], 10.0);
  EXPECT_NEAR(p.carriage_lengths_m[5], 8.2, 1e-9);  // the last one: what is left
  EXPECT_NEAR(Total(p), 72.0, 1e-9);
}

TEST(Carriages, WithoutThemALongBodyIsCutIntoEqualCarriagesAndAShortOneIsOneBox) {
  const VehicleTypeReport plain;
  const BodyPlan tram = PlanBody(45.0, 2.4, plain);
  ASSERT_EQ(tram.carriage_lengths_m.size(), 2u);  // three boxes of 14.33 m, 1 m apart
  EXPECT_NEAR(tram.head_length_m, 43.0 / 3.0, 1e-9);
  EXPECT_NEAR(tram.carriage_lengths_m[0], 43.0 / 3.0, 1e-9);
  EXPECT_NEAR(Total(tram), 45.0, 1e-9);
  const BodyPlan truck = PlanBody(16.5, 2.55, plain);
  EXPECT_DOUBLE_EQ(truck.head_length_m, 16.5);
  EXPECT_TRUE(truck.carriage_lengths_m.empty());
  // A 700 m freight train: many boxes, none longer than kMaxBoxLengthM, still 700 m.
  const BodyPlan freight = PlanBody(700.0, 3.0, plain);
  EXPECT_LE(freight.head_length_m, kMaxBoxLengthM);
  EXPECT_LE(freight.carriage_lengths_m.size(), static_cast<size_t>(kMaxCarriages));
  EXPECT_NEAR(Total(freight), 700.0, 1e-6);
}

TEST(Carriages, ABodyThatWouldNeedTooManyCarriagesGetsLongerOnes) {
  VehicleTypeReport freight;
  freight.locomotive_length_m = 12.0;
  freight.carriage_length_m = 10.0;
  freight.carriage_gap_m = 0.3;
  const BodyPlan p = PlanBody(700.0, 3.0, freight);  // 67 carriages of 10 m would be needed
  EXPECT_EQ(p.carriage_lengths_m.size(), static_cast<size_t>(kMaxCarriages));
  EXPECT_NEAR(Total(p), 700.0, 1e-6);
}

// D runs north from (100, -100) to (100, 0), E east from there to (300, 0); one lane each.
FakeSumoWorld Corner() {
  FakeSumoWorld w;
  w.AddEdge("D", 100, -100, 100, 0, 1);
  w.AddEdge("E", 100, 0, 300, 0, 1);
  w.AddLink("D_0", "E_0");
  return w;
}

VehicleOnLane Train(double lane_pos, double head_length) {
  VehicleOnLane v;
  v.lane = "E_0";
  v.lane_position_m = lane_pos;
  v.route = {"D", "E"};
  v.route_index = 1;
  v.speed_mps = 10.0;
  v.length_m = head_length;
  v.centre = Pose2{100.0 + lane_pos - 0.5 * head_length, 0.0, 0.0};
  return v;
}

TEST(Carriages, CarriagesStandAlongTheLanesTheVehicleCameBy) {
  FakeSumoWorld w = Corner();
  const BodyPlan plan = PlanBody(45.0, 2.4, VehicleTypeReport{});
  const double box = plan.head_length_m;  // 14.33 m
  // Its front 60 m into E: every box still on E, straight behind one another.
  std::vector<Carriage> c = PlaceCarriages(plan, Train(60.0, box), 2.4, SceneConfig{}, 0.1, &w);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_NEAR(c[0].x_m, 160.0 - box - 1.0 - 0.5 * box, 1e-9);
  EXPECT_NEAR(c[0].y_m, 0.0, 1e-9);
  EXPECT_NEAR(c[0].yaw_rad, 0.0, 1e-12);
  EXPECT_NEAR(c[0].yaw_rate_radps, 0.0, 1e-12);
  EXPECT_NEAR(c[1].x_m, 160.0 - 2.0 * box - 2.0 - 0.5 * box, 1e-9);
  EXPECT_TRUE(c[0].lanes && c[0].lanes->own);
  // Its front 5 m into E: the last carriage is still on D, heading north, beside the corner.
  c = PlaceCarriages(plan, Train(5.0, box), 2.4, SceneConfig{}, 0.1, &w);
  ASSERT_EQ(c.size(), 2u);
  const double s_last = 105.0 - 2.0 * box - 2.0 - 0.5 * box;  // along D then E
  EXPECT_NEAR(c[1].x_m, 100.0, 1e-9);
  EXPECT_NEAR(c[1].y_m, s_last - 100.0, 1e-9);
  EXPECT_NEAR(c[1].yaw_rad, kPi / 2, 1e-12);
  EXPECT_DOUBLE_EQ(c[1].length_m, box);
  EXPECT_DOUBLE_EQ(c[1].width_m, 2.4);
}

TEST(Carriages, CarriagesFollowBothPartsOfATurnThatAnInternalJunctionSplits) {
  // N north to (0, 0); the turn's internal lane in two parts, (0, 0) -> (0, 5) and
  // (0, 5) -> (5, 5) (TraCI: N_0 to E_0 via the first, the first to E_0 via the second); E east.
  FakeSumoWorld w;
  w.AddEdge("N", 0, -100, 0, 0, 1);
  w.AddLaneShape(":J_1", {Point2{0, 0}, Point2{0, 5}});
  w.AddLaneShape(":J_2", {Point2{0, 5}, Point2{5, 5}});
  w.AddEdge("E", 5, 5, 105, 5, 1);
  w.AddLinkVia("N_0", "E_0", ":J_1_0", "r");
  w.AddLinkVia(":J_1_0", "E_0", ":J_2_0", "r");
  w.AddLink(":J_2_0", "E_0", "M", false, "r");
  VehicleTypeReport tram;  // a 4 m head, 4 m carriages 0.5 m apart
  tram.locomotive_length_m = 4.0;
  tram.carriage_length_m = 4.0;
  tram.carriage_gap_m = 0.5;
  const BodyPlan plan = PlanBody(13.0, 2.4, tram);
  ASSERT_EQ(plan.carriage_lengths_m.size(), 2u);
  VehicleOnLane v;
  v.lane = "E_0";
  v.lane_position_m = 1.0;  // front at (6, 5)
  v.route = {"N", "E"};
  v.route_index = 1;
  v.speed_mps = 5.0;
  v.length_m = plan.head_length_m;
  v.centre = Pose2{4.0, 5.0, 0.0};
  const std::vector<Carriage> c = PlaceCarriages(plan, v, 2.4, SceneConfig{}, 0.1, &w);
  ASSERT_EQ(c.size(), 2u);
  // The first carriage's centre 6.5 m behind the front: 1 m of E, 5 m of the second part,
  // 0.5 m up the first, pointing north; the second's 11 m behind, on N.
  EXPECT_NEAR(c[0].x_m, 0.0, 1e-9);
  EXPECT_NEAR(c[0].y_m, 4.5, 1e-9);
  EXPECT_NEAR(c[0].yaw_rad, kPi / 2, 1e-9);
  EXPECT_NEAR(c[1].x_m, 0.0, 1e-9);
  EXPECT_NEAR(c[1].y_m, 0.0, 1e-9);
}

TEST(Carriages, AtTheStartOfItsRouteTheBodyGoesOnStraightBehind) {
  FakeSumoWorld w = Corner();
  const BodyPlan plan = PlanBody(45.0, 2.4, VehicleTypeReport{});
  VehicleOnLane v = Train(20.0, plan.head_length_m);
  v.route = {"E"};  // it started on E: no lane behind to follow
  v.route_index = 0;
  const std::vector<Carriage> c = PlaceCarriages(plan, v, 2.4, SceneConfig{}, 0.1, &w);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_LT(c[1].x_m, 100.0);  // behind E's start, along E's direction
  EXPECT_NEAR(c[1].y_m, 0.0, 1e-9);
  EXPECT_NEAR(c[1].yaw_rad, 0.0, 1e-12);
}

}  // namespace
}  // namespace criticality::plugin
