#include "tools/campaign/scenario_files.h"

#include <gtest/gtest.h>

#include "tests/tools/campaign/campaign_test_util.h"
#include "tools/campaign/campaign_error.h"
#include "tools/campaign/xml_scan.h"

namespace criticality::campaign {
namespace {

using testing::TempDir;
using testing::WriteFile;

const char* kSumocfg = R"(<?xml version="1.0"?>
<!-- <net-file value="commented.net.xml"/> -->
<configuration>
  <input>
    <net-file value="net/grid.net.xml"/>
    <route-files value="a.rou.xml, b.rou.xml"/>
  </input>
</configuration>
)";

const char* kRoutesA = R"(<routes>
  <vType id="car" accel="2.6"/>
  <vType id="bus"/>
  <vehicle id="v0" type="car" depart="0"/>
  <vehicle id="v1" type="bus" depart="1"/>
  <trip id="t&amp;2" type="car" depart="2" from="a" to="b"/>
  <vehicle id="d0" depart="3"/>
</routes>
)";

const char* kRoutesB = R"(<routes>
  <flow id="f" type="car" number="3" begin="0" end="10"/>
  <flow id="g" type="car" period="2" begin="0" end="10"/>
</routes>
)";

CampaignSpec Spec(const TempDir& dir, const std::string& scenarios, const std::string& rest = "") {
  return ParseCampaign("output: out\nscenarios:\n" + scenarios + rest,
                       dir.path() / "campaign.yaml");
}

TEST(XmlScan, TagsAttributesEntitiesAndComments) {
  std::vector<std::pair<std::string, XmlAttributes>> tags;
  ScanXmlTags(kRoutesA,
              [&](const std::string& n, const XmlAttributes& a) { tags.emplace_back(n, a); });
  ASSERT_EQ(tags.size(), 7u);
  EXPECT_EQ(tags[0].first, "routes");
  EXPECT_EQ(tags[1].second.at("accel"), "2.6");
  EXPECT_EQ(tags[5].second.at("id"), "t&2");
  int nets = 0;
  ScanXmlTags(kSumocfg,
              [&](const std::string& n, const XmlAttributes&) { nets += n == "net-file"; });
  EXPECT_EQ(nets, 1);  // the commented one is skipped
}

TEST(ScenarioFiles, SumoConfigFilesAreRelativeToTheConfig) {
  TempDir d;
  const auto cfg = WriteFile(d / "s/x.sumocfg", kSumocfg);
  const auto nets = SumoConfigFiles(cfg, "net-file");
  ASSERT_EQ(nets.size(), 1u);
  EXPECT_EQ(nets[0], d.path() / "s/net/grid.net.xml");
  const auto routes = SumoConfigFiles(cfg, "route-files");
  ASSERT_EQ(routes.size(), 2u);
  EXPECT_EQ(routes[1], d.path() / "s/b.rou.xml");
}

TEST(ScenarioFiles, VehiclesOfATypeIncludingFlowsWithANumber) {
  TempDir d;
  const auto a = WriteFile(d / "a.rou.xml", kRoutesA);
  const auto b = WriteFile(d / "b.rou.xml", kRoutesB);
  EXPECT_EQ(VehiclesOfType({a, b}, "car"),
            (std::vector<std::string>{"v0", "t&2", "f.0", "f.1", "f.2"}));
  EXPECT_EQ(VehiclesOfType({a, b}, "DEFAULT_VEHTYPE"), std::vector<std::string>{"d0"});
  EXPECT_TRUE(VehiclesOfType({a, b}, "tram").empty());
}

TEST(ScenarioFiles, GlobsExpandSortedAndKindsAndNames) {
  TempDir d;
  WriteFile(d / "sc/b_case/scenario.cfg", "sumo-config = x.sumocfg\n");
  WriteFile(d / "sc/a_case/scenario.cfg", "sumo-config = x.sumocfg\n");
  WriteFile(d / "nets/town.sumocfg", kSumocfg);
  const auto s = ResolveScenarios(
      Spec(d, "  - sc/*/scenario.cfg\n  - nets/town.sumocfg\n", "egos: [ego1, ego2]\n"));
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[0].name, "a_case");
  EXPECT_EQ(s[1].name, "b_case");
  EXPECT_EQ(s[0].rel_path, "sc/a_case/scenario.cfg");
  EXPECT_EQ(s[0].kind, ScenarioKind::kDriverConfig);
  EXPECT_FALSE(s[0].has_egos);  // a scenario.cfg names its own egos
  EXPECT_EQ(s[2].name, "town");
  EXPECT_EQ(s[2].kind, ScenarioKind::kSumoConfig);
  ASSERT_TRUE(s[2].has_egos);
  EXPECT_EQ(s[2].egos.ids, (std::vector<std::string>{"ego1", "ego2"}));
  EXPECT_EQ(SumoConfigOf(s[0]), d.path() / "sc/a_case/x.sumocfg");
}

TEST(ScenarioFiles, TypeEgosResolveFromTheRouteFiles) {
  TempDir d;
  WriteFile(d / "n/x.sumocfg", kSumocfg);
  WriteFile(d / "n/a.rou.xml", kRoutesA);
  WriteFile(d / "n/b.rou.xml", kRoutesB);
  const auto s = ResolveScenarios(Spec(d, "  - path: n/x.sumocfg\n    egos: {type: bus}\n"));
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].egos.kind, EgoSelection::Kind::kIds);
  EXPECT_EQ(s[0].egos.ids, std::vector<std::string>{"v1"});
  try {
    ResolveScenarios(Spec(d, "  - path: n/x.sumocfg\n    egos: {type: tram}\n"));
    FAIL() << "a type without vehicles must be an error";
  } catch (const CampaignError& e) {
    EXPECT_NE(std::string(e.what()).find("campaign.yaml:4: egos.type: no vehicle of type 'tram'"),
              std::string::npos)
        << e.what();
  }
}

TEST(ScenarioFiles, ErrorsNameTheEntryAndLine) {
  TempDir d;
  WriteFile(d / "n/x.sumocfg", kSumocfg);
  WriteFile(d / "n/notes.txt", "");
  auto error = [&](const std::string& scenarios) {
    try {
      ResolveScenarios(Spec(d, scenarios));
    } catch (const CampaignError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error("  - n/x.sumocfg\n")
                .find("campaign.yaml:3: scenarios[0]: n/x.sumocfg is a plain "
                      ".sumocfg: say which vehicles are egos"),
            std::string::npos);
  // Egos given as driver options are enough; given both ways, they are an error (which?).
  EXPECT_NO_THROW(
      ResolveScenarios(Spec(d, "  - n/x.sumocfg\n", "driver:\n  all-vehicles: true\n")));
  EXPECT_NO_THROW(ResolveScenarios(Spec(d, "  - n/x.sumocfg\n", "driver:\n  ego: [v0]\n")));
  EXPECT_NE(error("  - n/x.sumocfg\negos: {type: bus}\ndriver:\n  all-vehicles: true\n")
                .find("campaign.yaml:4: egos: the driver options choose the egos too"),
            std::string::npos);
  EXPECT_NE(error("  - path: n/x.sumocfg\n    egos: all\ndriver:\n  ego: [v0]\n")
                .find("campaign.yaml:4: scenarios[0].egos: the driver options choose the egos too"),
            std::string::npos);
  EXPECT_NE(error("  - missing/*.cfg\n")
                .find("campaign.yaml:3: scenarios[0]: 'missing/*.cfg' "
                      "matches no file"),
            std::string::npos);
  EXPECT_NE(error("  - n/notes.txt\n").find("expected a driver scenario.cfg"), std::string::npos);
  EXPECT_NE(error("  - path: n/x.sumocfg\n    egos: all\n  - n/*.sumocfg\n")
                .find("campaign.yaml:5: scenarios[1]: n/x.sumocfg is already in the campaign"),
            std::string::npos);
  // A name given must be the only one of its kind; names from paths that clash get the paths.
  WriteFile(d / "m/x.sumocfg", kSumocfg);
  EXPECT_NE(error("  - path: n/x.sumocfg\n    egos: all\n  - path: m/x.sumocfg\n    name: x\n"
                  "    egos: all\n")
                .find("campaign.yaml:5: scenarios[1].name: 'x' is also the name of n/x.sumocfg"),
            std::string::npos);
  const auto both =
      ResolveScenarios(Spec(d,
                            "  - path: n/x.sumocfg\n    egos: all\n  - path: m/x.sumocfg\n"
                            "    egos: all\n"));
  ASSERT_EQ(both.size(), 2u);
  EXPECT_EQ(both[0].name, "n/x");
  EXPECT_EQ(both[1].name, "m/x");
}

}  // namespace
}  // namespace criticality::campaign
