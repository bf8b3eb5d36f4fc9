// The critical events an evaluation judges warnings by: body overlaps (once per contact) and
// braking harder than the vehicle's own normal maximum (once per spell).
#include "plugin/observe/critical_events.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "criticality/geometry.h"
#include "plugin/sumo/sumo_conventions.h"

namespace criticality::plugin {
namespace {

// A vehicle 4.5 x 1.8 m whose CENTRE is at (x, y) with math yaw `yaw`, as SUMO would report it
// (front bumper, navigation degrees).
SumoObject Vehicle(const std::string& id, double x, double y, double yaw = 0.0,
                   double accel = 0.0, double decel = 4.5) {
  SumoObject o;
  o.id = id;
  o.length_m = 4.5;
  o.width_m = 1.8;
  o.x_m = x + 0.5 * o.length_m * std::cos(yaw);
  o.y_m = y + 0.5 * o.length_m * std::sin(yaw);
  o.angle_deg = YawToNavigationDeg(yaw);
  o.speed_mps = 5.0;
  o.accel_mps2 = accel;
  o.decel_mps2 = decel;
  return o;
}

SumoObject Person(const std::string& id, double x, double y) {
  SumoObject o;
  o.id = id;
  o.person = true;
  o.x_m = x;
  o.y_m = y;
  return o;
}

// The first object is the only ego; every other one is near it.
SumoSurroundings Around(std::vector<SumoObject> objects) {
  SumoSurroundings s;
  s.objects = std::move(objects);
  SumoSurroundings::Ego e;
  e.self = 0;
  for (int k = 1; k < static_cast<int>(s.objects.size()); ++k) e.nearby.push_back(k);
  s.egos.push_back(e);
  return s;
}

std::string Describe(const std::vector<CriticalEvent>& events) {
  std::string out;
  for (const CriticalEvent& e : events) {
    out += (out.empty() ? "" : " ") + e.ego + ":" + CriticalEventName(e.kind) + ":" + e.other;
  }
  return out;
}

TEST(CriticalEvents, AnOverlapIsReportedOncePerContact) {
  CriticalEventDetector d;
  // Ego 4.5 x 1.8 at the origin; a person 1.1 m to its side (0.9 + 0.25 = 1.15: touching
  // would need 1.15 m or less) overlaps, one at 1.3 m does not.
  EXPECT_EQ(Describe(d.Run(0.0, Around({Vehicle("ego", 0, 0), Person("p", 1.0, 1.3)}))), "");
  EXPECT_EQ(Describe(d.Run(0.1, Around({Vehicle("ego", 0, 0), Person("p", 1.0, 1.1)}))),
            "ego:overlap:p");
  EXPECT_EQ(Describe(d.Run(0.2, Around({Vehicle("ego", 0, 0), Person("p", 1.0, 1.0)}))), "");
  EXPECT_EQ(Describe(d.Run(0.3, Around({Vehicle("ego", 0, 0), Person("p", 1.0, 2.0)}))), "");
  EXPECT_EQ(Describe(d.Run(0.4, Around({Vehicle("ego", 0, 0), Person("p", 1.0, 1.0)}))),
            "ego:overlap:p");  // a second contact
}

TEST(CriticalEvents, OverlapUsesTheHeadings) {
  CriticalEventDetector d;
  // A car pointing across, its centre 3.5 m ahead: its half width 0.9 ends 0.35 m before the
  // ego's front (2.25 m); at 3.0 m the two overlap. Parallel, its half length 2.25 reaches back
  // over the ego's front from 4.0 m.
  EXPECT_EQ(Describe(d.Run(0.0, Around({Vehicle("ego", 0, 0), Vehicle("v", 3.5, 0, M_PI / 2)}))),
            "");
  EXPECT_EQ(Describe(d.Run(0.1, Around({Vehicle("ego", 0, 0), Vehicle("v", 3.0, 0, M_PI / 2)}))),
            "ego:overlap:v");
  CriticalEventDetector e;
  EXPECT_EQ(Describe(e.Run(0.0, Around({Vehicle("ego", 0, 0), Vehicle("v", 4.0, 0, 0.0)}))),
            "ego:overlap:v");
}

TEST(CriticalEvents, AVehicleIsSumosBoxFromItsFrontToItsBack) {
  // A 7.1 m truck in a U-turn: its front at the origin, SUMO's angle pointing west from its
  // back 4 m east of it (body_length_m, measured by the observe stage). A car 6 m east stands
  // where a 7.1 m box along that angle would reach, but beyond the truck's back.
  SumoObject truck = Vehicle("truck", 0, 0, kPi);
  truck.length_m = 7.1;
  truck.x_m = 0.0;
  truck.y_m = 0.0;
  truck.body_length_m = 4.0;
  const SumoObject car = Vehicle("car", 6.0 + 2.25 - 0.3, 0, 0.0);  // its rear 6 - 0.3 m east
  CriticalEventDetector d;
  EXPECT_EQ(Describe(d.Run(0.0, Around({truck, car}))), "");
  truck.body_length_m = 0.0;  // not measured: the truck's length
  EXPECT_EQ(Describe(d.Run(0.1, Around({truck, car}))), "truck:overlap:car");
}

TEST(CriticalEvents, HardBrakingIsBeyondTheVehiclesOwnDecelOncePerSpell) {
  CriticalEventDetector d;
  EXPECT_EQ(Describe(d.Run(0.0, Around({Vehicle("ego", 0, 0, 0, -4.5)}))), "");  // normal
  const std::vector<CriticalEvent> hard = d.Run(0.1, Around({Vehicle("ego", 0, 0, 0, -9.0)}));
  ASSERT_EQ(Describe(hard), "ego:hard-braking:");
  EXPECT_DOUBLE_EQ(hard[0].value, 9.0);
  EXPECT_EQ(Describe(d.Run(0.2, Around({Vehicle("ego", 0, 0, 0, -8.0)}))), "");  // same spell
  EXPECT_EQ(Describe(d.Run(0.3, Around({Vehicle("ego", 0, 0, 0, 1.0)}))), "");
  EXPECT_EQ(Describe(d.Run(0.4, Around({Vehicle("ego", 0, 0, 0, -7.0)}))),
            "ego:hard-braking:");
  // A truck whose decel is 7.5 brakes normally at 7.0; no decel known (0): never hard.
  CriticalEventDetector e;
  EXPECT_EQ(Describe(e.Run(0.0, Around({Vehicle("truck", 0, 0, 0, -7.0, 7.5)}))), "");
  EXPECT_EQ(Describe(e.Run(0.1, Around({Vehicle("x", 0, 0, 0, -9.0, 0.0)}))), "");
}

// Two cars crossing at 20 m/s, 1 s steps: 10 m before the crossing point at one step, 10 m
// past it at the next; apart at both steps, through each other at 0.5 s. Catches a detector
// that looks only at the steps, one that interpolates a teleport (a jump farther than the
// speeds allow), and one that reports a pair that never met (one car still 10 m short).
TEST(CriticalEvents, BodiesThatPassThroughEachOtherBetweenStepsAreReported) {
  auto car = [](const std::string& id, double x, double y, double yaw, double speed) {
    SumoObject o = Vehicle(id, x, y, yaw);
    o.speed_mps = speed;
    return o;
  };
  CriticalEventDetector d;
  EXPECT_EQ(Describe(d.Run(0.0, Around({car("ego", -10, 0, 0, 20), car("v", 0, -10, kPi / 2, 20)}))),
            "");
  const std::vector<CriticalEvent> through =
      d.Run(1.0, Around({car("ego", 10, 0, 0, 20), car("v", 0, 10, kPi / 2, 20)}));
  ASSERT_EQ(Describe(through), "ego:pass-through:v");
  EXPECT_DOUBLE_EQ(through[0].value, 20.0);
  // The same motion with the crossing car 20 m behind: it reaches the crossing point only when
  // the ego is 10 m past it.
  CriticalEventDetector late;
  late.Run(0.0, Around({car("ego", -10, 0, 0, 20), car("v", 0, -30, kPi / 2, 20)}));
  EXPECT_EQ(Describe(late.Run(1.0, Around({car("ego", 10, 0, 0, 20), car("v", 0, -10, kPi / 2, 20)}))),
            "");
  // The crossing car at 5 m/s "moving" 20 m in 1 s: a teleport, not interpolated.
  CriticalEventDetector jump;
  jump.Run(0.0, Around({car("ego", -10, 0, 0, 20), car("v", 0, -10, kPi / 2, 5)}));
  EXPECT_EQ(Describe(jump.Run(1.0, Around({car("ego", 10, 0, 0, 20), car("v", 0, 10, kPi / 2, 5)}))),
            "");
}

// A car following a 10 m radius left turn, 60 degrees in one 1 s step (10.5 m/s): between
// the two poses it moves along the arc, which runs 1.34 m outside the chord at its middle. A
// person standing 0.5 m inside the chord's middle is passed; one on the arc is hit. Catches
// interpolation along the chord (it would cut the corner into the first person).
TEST(CriticalEvents, ATurningBodyIsInterpolatedAlongItsArc) {
  const double v = 10.0 * kPi / 3.0;
  auto turning = [&](double angle) {  // on the circle about the origin, heading along it
    SumoObject o = Vehicle("ego", 10.0 * std::sin(angle), -10.0 * std::cos(angle), angle);
    o.speed_mps = v;
    return o;
  };
  const double chord_x = 0.5 * 10.0 * std::sin(kPi / 3.0), chord_y = -0.5 * (10.0 + 5.0);
  const SumoObject inside = Person("inside", chord_x - 0.25, chord_y + 0.25 * std::sqrt(3.0));
  const SumoObject on_arc = Person("on_arc", 10.0 * std::sin(kPi / 6.0), -10.0 * std::cos(kPi / 6.0));
  CriticalEventDetector d;
  EXPECT_EQ(Describe(d.Run(0.0, Around({turning(0.0), inside}))), "");
  EXPECT_EQ(Describe(d.Run(1.0, Around({turning(kPi / 3.0), inside}))), "");
  CriticalEventDetector e;
  EXPECT_EQ(Describe(e.Run(0.0, Around({turning(0.0), on_arc}))), "");
  EXPECT_EQ(Describe(e.Run(1.0, Around({turning(kPi / 3.0), on_arc}))), "ego:pass-through:on_arc");
}

TEST(CriticalEvents, ObjectsWithoutAPositionAreSkipped) {
  CriticalEventDetector d;
  SumoObject lost = Person("p", NAN, NAN);  // SUMO 1.15 reports some like this
  EXPECT_EQ(Describe(d.Run(0.0, Around({Vehicle("ego", 0, 0), lost}))), "");
  // Only an ego's overlaps count: a person inside another vehicle near the ego is none.
  EXPECT_EQ(Describe(d.Run(0.1, Around({Vehicle("ego", 0, 0), Vehicle("v", 20, 0),
                                         Person("p", 20, 0)}))),
            "");
}

}  // namespace
}  // namespace criticality::plugin
