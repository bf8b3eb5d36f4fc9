// `plan` proves that every run can start: the scenarios' files, every driver option set
// through the driver's parser (the stand-in's --check-options), every SUMO option set through
// SUMO (tests/tools/campaign/fake_sumo.sh); errors name the campaign file, the line and the key.
#include "tools/campaign/plan_check.h"

#include <gtest/gtest.h>

#include <set>

#include "tests/tools/campaign/campaign_test_util.h"

namespace criticality::campaign {
namespace {

using testing::ReadFile;
using testing::StandInDriver;
using testing::TempDir;
using testing::WriteFile;

TEST(OptionCombinations, EveryCombinationUpToTheLimitInMixedRadixOrder) {
  bool all = false;
  const auto c = OptionCombinations({2, 3}, 6, &all);
  EXPECT_TRUE(all);
  ASSERT_EQ(c.size(), 6u);
  EXPECT_EQ(c[0], (std::vector<std::size_t>{0, 0}));
  EXPECT_EQ(c[1], (std::vector<std::size_t>{0, 1}));
  EXPECT_EQ(c[5], (std::vector<std::size_t>{1, 2}));
  EXPECT_EQ(std::set<std::vector<std::size_t>>(c.begin(), c.end()).size(), 6u);
  EXPECT_EQ(OptionCombinations({}, 1, &all).size(), 1u);  // no axes: one empty set
}

TEST(OptionCombinations, BeyondTheLimitEveryValueOfEveryAxisAppears) {
  bool all = true;
  const std::vector<std::size_t> sizes{2, 3, 4};
  const auto c = OptionCombinations(sizes, 5, &all);
  EXPECT_FALSE(all);
  EXPECT_EQ(c.size(), 4u);  // as many as the longest axis has values
  for (std::size_t k = 0; k < sizes.size(); ++k) {
    std::set<std::size_t> seen;
    for (const auto& v : c) seen.insert(v[k]);
    EXPECT_EQ(seen.size(), sizes[k]) << "axis " << k;
  }
}

TEST(NamedOption, TheEarliestWholeOptionNameWins) {
  const std::vector<OptionSource> s = {{"warn-threshold", "0.9", "driver.warn-threshold", 3},
                                       {"warn-release", "0.95", "grid.driver.warn-release", 7},
                                       {"warn-release-after", "1", "driver.warn-release-after", 4},
                                       {"step-length", "0.1", "sumo.step-length", 9}};
  auto key = [&](const std::string& msg) {
    const OptionSource* o = NamedOption(msg, s);
    return o ? o->key : std::string("(none)");
  };
  EXPECT_EQ(key("--warn-release 0.95: must not exceed --warn-threshold 0.9"),
            "grid.driver.warn-release");
  EXPECT_EQ(key("--warn-release-after -1: must be a finite time >= 0 s"),
            "driver.warn-release-after");
  EXPECT_EQ(key("the minimum step-length is 0.001"), "sumo.step-length");
  EXPECT_EQ(key("While processing option 'step-length': 'x' is not a number."), "sumo.step-length");
  EXPECT_EQ(key("no option step-lengthy"), "(none)");
  EXPECT_EQ(key("File 'x.net.xml' is not accessible"), "(none)");
}

TEST(SumoErrors, TheFirstErrorWithItsContinuationLines) {
  EXPECT_EQ(SumoErrors("Warning: SUMO_HOME\nError: On processing option '--step-lenght':\n No "
                       "option with the name 'step-lenght' exists.\nError: The parameter '0.1' "
                       "is not allowed in this context.\n Switch or parameter name expected.\n"
                       "Error: Could not parse commandline options.\nQuitting (on error).\n"),
            "On processing option '--step-lenght': No option with the name 'step-lenght' "
            "exists.");
  EXPECT_EQ(SumoErrors("Warning: nothing wrong\nLoading net-file ... done.\n"), "");
}

TEST(WithoutOutputs, KeepsTheInputsAndDropsWhatWouldBeWrittenAndTheEnd) {
  const std::string saved =
      "<configuration>\n    <input>\n        <net-file value=\"/a/n.net.xml\"/>\n    </input>\n"
      "    <output>\n        <fcd-output value=\"fcd.xml\"/>\n        <tripinfo-output "
      "value=\"t.xml\"/>\n    </output>\n    <time>\n        <begin value=\"30\"/>\n        "
      "<end value=\"600\"/>\n    </time>\n    <report>\n        <log value=\"x.log\"/>\n        "
      "<no-warnings value=\"true\"/>\n    </report>\n    <ssm>\n        <device.ssm.file "
      "value=\"ssm.xml\"/>\n        <device.ssm.probability value=\"1\"/>\n    </ssm>\n"
      "</configuration>\n";
  std::string begin;
  const std::string dry = WithoutOutputs(saved, &begin);
  EXPECT_EQ(begin, "30");
  EXPECT_NE(dry.find("net-file"), std::string::npos);
  EXPECT_NE(dry.find("no-warnings"), std::string::npos);
  EXPECT_NE(dry.find("device.ssm.probability"), std::string::npos);
  for (const char* gone :
       {"<output>", "fcd-output", "tripinfo-output", "<log ", "device.ssm.file", "<end "})
    EXPECT_EQ(dry.find(gone), std::string::npos) << gone;
  EXPECT_NE(dry.find("</configuration>"), std::string::npos);
}

// Two scenarios with real files behind them (empty net and route files: the stand-ins do not
// read them), the stand-in driver and the fake SUMO.
struct Fixture {
  TempDir dir;
  Fixture() {
    for (const char* s : {"a", "b"}) {
      WriteFile(dir / (std::string(s) + "/scenario.cfg"), "sumo-config = x.sumocfg\n");
      WriteFile(dir / (std::string(s) + "/x.sumocfg"),
                "<configuration><input><net-file value=\"x.net.xml\"/><route-files "
                "value=\"x.rou.xml\"/></input></configuration>\n");
      WriteFile(dir / (std::string(s) + "/x.net.xml"), "<net/>\n");
      WriteFile(dir / (std::string(s) + "/x.rou.xml"), "<routes/>\n");
    }
  }
  PlanCheck Check(const std::string& yaml, std::size_t max_sets = 200) const {
    WriteFile(dir / "c.yaml", yaml);
    const Plan plan(LoadCampaignFile(dir / "c.yaml"));
    CheckSettings s;
    s.driver = StandInDriver();
    s.driver_checks = true;
    s.sumo = FAKE_SUMO;
    s.jobs = 2;
    s.max_sets = max_sets;
    return CheckPlan(plan, s);
  }
  std::string File() const { return (dir / "c.yaml").string(); }
};

std::string Joined(const std::vector<std::string>& v) {
  std::string s;
  for (const std::string& x : v) s += x + "\n";
  return s;
}

TEST(CheckPlan, AGoodPlanPassesAndSaysWhatWasChecked) {
  Fixture f;
  setenv("FAKE_SUMO_LOG", (f.dir / "sumo.log").c_str(), 1);
  const PlanCheck c = f.Check(
      "output: out\nscenarios: [a/scenario.cfg, b/scenario.cfg]\ndriver:\n  act: warn\n"
      "sumo:\n  collision.action: teleport\ngrid:\n  driver:\n    warn-threshold: [0.5, 0.9]\n"
      "  sumo:\n    seed: [1, 2, 3]\n");
  unsetenv("FAKE_SUMO_LOG");
  EXPECT_TRUE(c.errors.empty()) << Joined(c.errors);
  EXPECT_EQ(c.driver_sets, 4u);  // 2 scenarios x 2 thresholds
  EXPECT_EQ(c.driver_checked, 4u);
  EXPECT_EQ(c.sumo_sets, 6u);  // 2 configurations x 3 seeds
  EXPECT_EQ(c.sumo_checked, 6u);
  EXPECT_EQ(c.scenario_files, 6u);  // per scenario: .sumocfg, net, routes
  // Each SUMO set: saved once, then started dry from the saved configuration.
  const std::string calls = ReadFile(f.dir / "sumo.log");
  std::size_t saves = 0, dry = 0;
  for (std::size_t at = calls.find("--save-configuration"); at != std::string::npos;
       at = calls.find("--save-configuration", at + 1))
    ++saves;
  for (std::size_t at = calls.find("dry.sumocfg --end 5"); at != std::string::npos;
       at = calls.find("dry.sumocfg --end 5", at + 1))
    ++dry;
  EXPECT_EQ(saves, 6u);
  EXPECT_EQ(dry, 6u);
  EXPECT_NE(calls.find("--seed 3"), std::string::npos);
  EXPECT_NE(calls.find("--collision.action teleport"), std::string::npos);
}

TEST(CheckPlan, ADriverValueErrorNamesTheFileLineKeyAndValue) {
  Fixture f;
  const PlanCheck c = f.Check(
      "output: out\nscenarios: [a/scenario.cfg]\ndriver:\n  act: brak\ngrid:\n  driver:\n"
      "    warn-threshold: [0.5, 0.9]\n");
  ASSERT_EQ(c.errors.size(), 1u) << Joined(c.errors);
  EXPECT_EQ(
      c.errors[0].rfind(f.File() + ":4: driver.act: sumo-criticality says: --act 'brak': "
                                   "use none, warn or brake (run 0: a, warn-threshold=0.5 and "
                                   "1 more option set)",
                        0),
      0u)
      << c.errors[0];
  const PlanCheck g = f.Check(
      "output: out\nscenarios: [a/scenario.cfg, b/scenario.cfg]\ngrid:\n  driver:\n"
      "    warn-threshold: [-0.5, 0.9]\n  sumo:\n    seed: [1, 2]\n");
  ASSERT_EQ(g.errors.size(), 1u) << Joined(g.errors);
  // The grid value, and the first run that has it (its other scenario counted).
  EXPECT_EQ(g.errors[0], f.File() +
                             ":5: grid.driver.warn-threshold: '-0.5': sumo-criticality says: "
                             "--warn-threshold -0.5: must be in (0, 1] (run 0: a, "
                             "warn-threshold=-0.5 seed=1 and 1 more option set)");
}

TEST(CheckPlan, SumoErrorsNameTheirOptionEvenOnExitCodeZero) {
  Fixture f;
  const PlanCheck c =
      f.Check("output: out\nscenarios: [a/scenario.cfg]\nsumo:\n  step-lenght: 0.1\n");
  ASSERT_EQ(c.errors.size(), 1u) << Joined(c.errors);
  EXPECT_NE(c.errors[0].find(f.File() + ":4: sumo.step-lenght: sumo says: On processing option "
                                        "'--step-lenght': No option with the name 'step-lenght' "
                                        "exists."),
            std::string::npos)
      << c.errors[0];
  // An action SUMO does not know: found by the dry start (SUMO exits with 0 there).
  const PlanCheck d = f.Check(
      "output: out\nscenarios: [a/scenario.cfg]\ngrid:\n  sumo:\n    collision.action: [warn, "
      "explode]\n");
  ASSERT_EQ(d.errors.size(), 1u) << Joined(d.errors);
  EXPECT_NE(d.errors[0].find(":5: grid.sumo.collision.action: 'explode': sumo says: Invalid "
                             "collision.action 'explode'."),
            std::string::npos)
      << d.errors[0];
}

TEST(CheckPlan, AMissingScenarioFileNamesTheEntryAndSkipsItsProgramChecks) {
  Fixture f;
  std::filesystem::remove(f.dir / "b/x.net.xml");
  const PlanCheck c = f.Check("output: out\nscenarios:\n  - a/scenario.cfg\n  - b/scenario.cfg\n");
  ASSERT_EQ(c.errors.size(), 1u) << Joined(c.errors);
  EXPECT_EQ(c.errors[0].rfind(f.File() +
                                  ":4: scenarios[1] (b/scenario.cfg): x.sumocfg names "
                                  "net-file " +
                                  (f.dir / "b/x.net.xml").string() + ", which does not exist",
                              0),
            0u)
      << c.errors[0];
  EXPECT_EQ(c.driver_checked, 1u);  // scenario a only
  EXPECT_EQ(c.scenario_files, 5u);   // the files that exist: not b's net
}

TEST(CheckPlan, BeyondTheLimitACoverOfEveryValueIsCheckedAndSaidSo) {
  Fixture f;
  const PlanCheck c = f.Check(
      "output: out\nscenarios: [a/scenario.cfg]\ngrid:\n  driver:\n    warn-threshold: [0.5, "
      "0.6, 0.7]\n    profiles: [3, 4, 5, 6]\n",
      5);
  EXPECT_TRUE(c.errors.empty()) << Joined(c.errors);
  EXPECT_EQ(c.driver_sets, 12u);
  EXPECT_EQ(c.driver_checked, 4u);
  EXPECT_NE(Joined(c.checked).find("4 of 12 driver option sets"), std::string::npos);
  EXPECT_NE(Joined(c.checked).find("each grid value at least once"), std::string::npos);
  // A bad value is found even so: every value is in some checked set.
  const PlanCheck d = f.Check(
      "output: out\nscenarios: [a/scenario.cfg]\ngrid:\n  driver:\n    warn-threshold: [0.5, "
      "0.6, 7]\n    profiles: [3, 4, 5, 6]\n",
      5);
  ASSERT_EQ(d.errors.size(), 1u) << Joined(d.errors);
  EXPECT_NE(d.errors[0].find("grid.driver.warn-threshold: '7'"), std::string::npos);
}

TEST(CheckPlan, WithoutProgramsItSaysWhatWasNotChecked) {
  Fixture f;
  WriteFile(f.dir / "c.yaml", "output: out\nscenarios: [a/scenario.cfg]\n");
  const Plan plan(LoadCampaignFile(f.dir / "c.yaml"));
  CheckSettings s;
  s.driver = StandInDriver();  // no --check-options (an older driver), no sumo
  const PlanCheck c = CheckPlan(plan, s);
  EXPECT_TRUE(c.errors.empty());
  EXPECT_EQ(c.driver_checked, 0u);
  EXPECT_EQ(c.sumo_checked, 0u);
  ASSERT_EQ(c.unchecked.size(), 2u);
  EXPECT_NE(c.unchecked[0].find("has no --check-options"), std::string::npos);
  EXPECT_NE(c.unchecked[1].find("no sumo"), std::string::npos);
}

}  // namespace
}  // namespace criticality::campaign
