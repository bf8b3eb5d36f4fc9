// Which IDs route files define, read without SUMO (early ego checks).
#include "plugin/sumo/route_ids.h"

#include <gtest/gtest.h>

#include <fstream>

namespace criticality::plugin {
namespace {

std::string Write(const char* name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

TEST(RouteIds, VehiclesTripsFlowsAndPersons) {
  const std::string routes = Write("r.rou.xml", R"(<routes>
  <vType id="car"/>
  <!-- <vehicle id="commented"/> -->
  <vehicle id="v1" depart="0"><route edges="a b"/></vehicle>
  <trip id='t1' depart="1" from="a" to="b"/>
  <flow id="f" begin="0" end="10" number="3" from="a" to="b"/>
  <person   id="walker" depart="0"><walk edges="a"/></person>
  <personFlow id="pf" begin="0" number="2"><walk edges="a"/></personFlow>
</routes>)");
  const std::string more =
      Write("a.add.xml", R"(<additional><vehicle id="v2" depart="3"/></additional>)");
  const RouteIds ids = ScanRouteIds({routes + "," + more});
  EXPECT_TRUE(ids.unscanned.empty());
  EXPECT_EQ(Classify(ids, "v1"), RouteIdKind::kVehicle);
  EXPECT_EQ(Classify(ids, "v2"), RouteIdKind::kVehicle);
  EXPECT_EQ(Classify(ids, "t1"), RouteIdKind::kVehicle);
  EXPECT_EQ(Classify(ids, "f.2"), RouteIdKind::kVehicle);
  EXPECT_EQ(Classify(ids, "walker"), RouteIdKind::kPerson);
  EXPECT_EQ(Classify(ids, "pf.0"), RouteIdKind::kPerson);
  EXPECT_EQ(Classify(ids, "commented"), RouteIdKind::kAbsent);
  EXPECT_EQ(Classify(ids, "car"), RouteIdKind::kAbsent);  // a type, not a vehicle
  EXPECT_EQ(Classify(ids, "f"), RouteIdKind::kAbsent);
  EXPECT_EQ(Classify(ids, "f.x"), RouteIdKind::kAbsent);
  EXPECT_EQ(Classify(ids, "v"), RouteIdKind::kAbsent);
}

TEST(RouteIds, WhatCannotBeScannedProvesNothing) {
  const std::string routes = Write("s.rou.xml", R"(<routes><vehicle id="v1"/></routes>)");
  const std::string gz = Write("c.rou.xml.gz", "binary");
  const std::string incl = Write("i.rou.xml", R"(<routes><xi:include href="x.xml"/></routes>)");
  for (const std::string& other : {gz, incl, ::testing::TempDir() + "missing.rou.xml"}) {
    const RouteIds ids = ScanRouteIds({routes, other});
    EXPECT_EQ(ids.unscanned.size(), 1u) << other;
    EXPECT_EQ(Classify(ids, "v1"), RouteIdKind::kVehicle);
    EXPECT_EQ(Classify(ids, "typo"), RouteIdKind::kCannotTell) << other;
  }
}

}  // namespace
}  // namespace criticality::plugin
