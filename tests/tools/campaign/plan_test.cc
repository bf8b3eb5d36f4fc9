#include "tools/campaign/plan.h"

#include <gtest/gtest.h>

#include <set>

#include "tests/tools/campaign/campaign_test_util.h"
#include "tools/campaign/campaign_error.h"

namespace criticality::campaign {
namespace {

using testing::TempDir;
using testing::WriteFile;

struct Fixture {
  TempDir dir;
  Fixture() {
    WriteFile(dir / "s1/scenario.cfg", "sumo-config = x.sumocfg\n");
    WriteFile(dir / "s2/scenario.cfg", "sumo-config = x.sumocfg\n");
    WriteFile(dir / "town.sumocfg", "<configuration/>\n");
  }
  Plan Make(const std::string& text) const {
    return Plan(ParseCampaign(text, dir.path() / "c.yaml"));
  }
};

const char* kGrid = R"(output: out
scenarios: [s1/scenario.cfg, s2/scenario.cfg]
driver: {act: warn, all-vehicles: false}
sumo: {step-length: 0.1}
grid:
  driver:
    profiles: [6, 3, 1]
    record-everything: [true, false]
  sumo:
    seed: [1, 2]
repetitions: 2
)";

TEST(Plan, SizeIsTheProductOfScenariosAxesAndRepetitions) {
  Fixture f;
  const Plan p = f.Make(kGrid);
  EXPECT_EQ(p.size(), 2u * 3u * 2u * 2u * 2u);
}

TEST(Plan, IndexDecodesScenarioSlowestRepetitionFastest) {
  Fixture f;
  const Plan p = f.Make(kGrid);
  PlanRun r = p.Run(0);
  EXPECT_EQ(r.scenario, 0u);
  EXPECT_EQ(r.value, (std::vector<std::size_t>{0, 0, 0}));
  EXPECT_EQ(r.repetition, 0);
  r = p.Run(1);
  EXPECT_EQ(r.repetition, 1);
  EXPECT_EQ(r.value, (std::vector<std::size_t>{0, 0, 0}));
  r = p.Run(2);  // next seed
  EXPECT_EQ(r.value, (std::vector<std::size_t>{0, 0, 1}));
  r = p.Run(24);  // second scenario
  EXPECT_EQ(r.scenario, 1u);
  EXPECT_EQ(r.value, (std::vector<std::size_t>{0, 0, 0}));
  r = p.Run(47);
  EXPECT_EQ(r.scenario, 1u);
  EXPECT_EQ(r.value, (std::vector<std::size_t>{2, 1, 1}));
  EXPECT_EQ(r.repetition, 1);
  // Every run is a distinct combination.
  std::set<std::tuple<std::size_t, std::vector<std::size_t>, int>> seen;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const PlanRun x = p.Run(i);
    EXPECT_EQ(x.index, i);
    seen.insert({x.scenario, x.value, x.repetition});
  }
  EXPECT_EQ(seen.size(), p.size());
}

TEST(Plan, CommandPutsOptionsInOrderAndSumoAfterDashes) {
  Fixture f;
  const Plan p = f.Make(kGrid);
  const auto argv = p.Command(p.Run(47), "/bin/drv", "run.sqlite");
  const std::vector<std::string> want{"/bin/drv",
                                      "--config",
                                      (f.dir / "s2/scenario.cfg").string(),
                                      "--act",
                                      "warn",
                                      "--profiles",
                                      "1",
                                      "--output",
                                      "run.sqlite",
                                      "--no-progress",
                                      "--",
                                      "--step-length",
                                      "0.1",
                                      "--seed",
                                      "2"};
  // all-vehicles: false and record-everything: false are left out (switches).
  EXPECT_EQ(argv, want);
  const auto first = p.Command(p.Run(0), "/bin/drv", "run.sqlite");
  EXPECT_NE(std::find(first.begin(), first.end(), "--record-everything"), first.end());
  EXPECT_EQ(p.Label(p.Run(47)), "profiles=1 record-everything=false seed=2");
}

TEST(Plan, PlainSumocfgGetsEgosAndSumoBooleansAreValues) {
  Fixture f;
  const Plan all = f.Make(
      "output: o\nscenarios: [town.sumocfg]\negos: all\nsumo: {collision.check-junctions: true}\n");
  EXPECT_EQ(all.Command(all.Run(0), "d", "r"),
            (std::vector<std::string>{"d", "--sumo-config", (f.dir / "town.sumocfg").string(),
                                      "--all-vehicles", "--output", "r", "--no-progress", "--",
                                      "--collision.check-junctions", "true"}));
  const Plan ids = f.Make("output: o\nscenarios: [town.sumocfg]\negos: [a, b]\n");
  EXPECT_EQ(
      ids.Command(ids.Run(0), "d", "r"),
      (std::vector<std::string>{"d", "--sumo-config", (f.dir / "town.sumocfg").string(), "--ego",
                                "a", "--ego", "b", "--output", "r", "--no-progress"}));
  EXPECT_EQ(ids.Label(ids.Run(0)), "-");
}

TEST(Plan, SameFileSamePlanAndFingerprint) {
  Fixture f;
  const Plan a = f.Make(kGrid);
  const Plan b = f.Make(kGrid);
  EXPECT_EQ(a.fingerprint(), b.fingerprint());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a.Command(a.Run(i), "d", "r"), b.Command(b.Run(i), "d", "r"));
  }
  EXPECT_EQ(a.FingerprintHex().size(), 16u);
}

TEST(Plan, FingerprintFollowsWhatDecidesRunsOnly) {
  Fixture f;
  const Plan base = f.Make(kGrid);
  std::string other_output = kGrid;
  other_output.replace(other_output.find("output: out"), 11, "output: elsewhere");
  other_output += "limits: {time_s: 5}\nslurm: {mem: 1G}\n";
  EXPECT_EQ(f.Make(other_output).fingerprint(), base.fingerprint());
  std::string other_grid = kGrid;
  other_grid.replace(other_grid.find("[6, 3, 1]"), 9, "[6, 3, 2]");
  EXPECT_NE(f.Make(other_grid).fingerprint(), base.fingerprint());
  std::string other_reps = kGrid;
  other_reps.replace(other_reps.find("repetitions: 2"), 14, "repetitions: 3");
  EXPECT_NE(f.Make(other_reps).fingerprint(), base.fingerprint());
}

TEST(Plan, HundredThousandRunsDecodeWithoutMaterialising) {
  Fixture f;
  const Plan p = f.Make(
      "output: o\nscenarios: [s1/scenario.cfg, s2/scenario.cfg]\ngrid:\n  driver:\n    "
      "profiles: {range: [1, 50]}\n  sumo:\n    seed: {range: [1, 1000]}\n");
  ASSERT_EQ(p.size(), 100000u);
  const PlanRun last = p.Run(99999);
  EXPECT_EQ(last.scenario, 1u);
  EXPECT_EQ(p.Label(last), "profiles=50 seed=1000");
  EXPECT_EQ(p.Label(p.Run(50000)), "profiles=1 seed=1");
}

TEST(Plan, RefusesAbsurdlyLargePlans) {
  Fixture f;
  EXPECT_THROW(f.Make("output: o\nscenarios: [s1/scenario.cfg]\ngrid:\n  sumo:\n    a: {range: "
                      "[1, 100000]}\n    b: {range: [1, 100000]}\n"),
               CampaignError);
}

}  // namespace
}  // namespace criticality::campaign
