#include "tools/campaign/campaign_file.h"

#include <gtest/gtest.h>

#include "tools/campaign/campaign_error.h"

namespace criticality::campaign {
namespace {

const char* kFull = R"(# a complete campaign
name: sweep
output: out/sweep
scenarios:
  - a/scenario.cfg
  - path: nets/grid.sumocfg
    name: grid
    egos: {type: car}
egos: all
driver:
  act: warn
  threads: 1
  all-vehicles: false
  event: ["0 ego speed 10", "1 ego speed 5"]
sumo:
  step-length: 0.1
  collision.check-junctions: true
grid:
  driver:
    profiles: [6, 3]
    warn-threshold: [0.3, 0.5]
  sumo:
    seed: {range: [1, 5, 2]}
repetitions: 2
limits:
  time_s: 600
  kill_after_s: 5
slurm:
  time: "00:30:00"
  mem: 2G
  cpus_per_task: 2
  throttle: 8
  runs_per_task: 3
  extra: ["--account=traffic"]
)";

// The error message of parsing `text`, or "" when it parses.
std::string ErrorOf(const std::string& text) {
  try {
    ParseCampaign(text, "/tmp/c/camp.yaml");
  } catch (const CampaignError& e) {
    return e.what();
  }
  return "";
}

TEST(CampaignFile, ParsesEveryKey) {
  const CampaignSpec c = ParseCampaign(kFull, "/tmp/c/camp.yaml");
  EXPECT_EQ(c.name, "sweep");
  EXPECT_EQ(c.output, "/tmp/c/out/sweep");
  EXPECT_EQ(c.base_dir, "/tmp/c");
  ASSERT_EQ(c.scenarios.size(), 2u);
  EXPECT_EQ(c.scenarios[0].pattern, "a/scenario.cfg");
  EXPECT_EQ(c.scenarios[1].name, "grid");
  ASSERT_TRUE(c.scenarios[1].egos);
  EXPECT_EQ(c.scenarios[1].egos->kind, EgoSelection::Kind::kType);
  EXPECT_EQ(c.scenarios[1].egos->type, "car");
  ASSERT_TRUE(c.egos);
  EXPECT_EQ(c.egos->kind, EgoSelection::Kind::kAll);
  ASSERT_EQ(c.driver_options.size(), 4u);
  EXPECT_EQ(c.driver_options[2].name, "all-vehicles");
  EXPECT_TRUE(c.driver_options[2].boolean);
  EXPECT_EQ(c.driver_options[2].values, std::vector<std::string>{"false"});
  EXPECT_EQ(c.driver_options[3].values.size(), 2u);
  ASSERT_EQ(c.sumo_options.size(), 2u);
  EXPECT_TRUE(c.sumo_options[1].boolean);
  ASSERT_EQ(c.axes.size(), 3u);
  EXPECT_EQ(c.axes[0].name, "profiles");
  EXPECT_EQ(c.axes[0].values, (std::vector<std::string>{"6", "3"}));
  EXPECT_EQ(c.axes[0].target, Target::kDriver);
  EXPECT_EQ(c.axes[2].target, Target::kSumo);
  EXPECT_EQ(c.axes[2].values, (std::vector<std::string>{"1", "3", "5"}));
  EXPECT_EQ(c.axes[0].line, 20);
  EXPECT_EQ(c.repetitions, 2);
  EXPECT_DOUBLE_EQ(c.time_limit_s, 600);
  EXPECT_DOUBLE_EQ(c.kill_after_s, 5);
  EXPECT_EQ(c.slurm.time, "00:30:00");
  EXPECT_EQ(c.slurm.cpus_per_task, 2);
  EXPECT_EQ(c.slurm.throttle, 8);
  EXPECT_EQ(c.slurm.runs_per_task, 3);
  EXPECT_EQ(c.slurm.extra, std::vector<std::string>{"--account=traffic"});
}

TEST(CampaignFile, MinimalFileHasDefaults) {
  const CampaignSpec c = ParseCampaign("output: o\nscenarios: [x.cfg]\n", "/tmp/c/min.yaml");
  EXPECT_EQ(c.name, "min");
  EXPECT_EQ(c.repetitions, 1);
  EXPECT_TRUE(c.axes.empty());
  EXPECT_FALSE(c.egos);
  EXPECT_DOUBLE_EQ(c.time_limit_s, 0.0);
}

TEST(CampaignFile, UnknownKeysNameKeyAndLine) {
  EXPECT_EQ(ErrorOf("output: o\nscenarios: [x.cfg]\nrepetitons: 3\n"),
            "/tmp/c/camp.yaml:3: repetitons: unknown key (expected one of: driver, egos, grid, "
            "limits, name, output, repetitions, scenarios, slurm, sumo)");
  EXPECT_NE(ErrorOf("output: o\nscenarios: [x.cfg]\ngrid:\n  drivers:\n    profiles: [1]\n")
                .find("camp.yaml:4: grid.drivers: unknown key"),
            std::string::npos);
  EXPECT_NE(ErrorOf("output: o\nscenarios: [x.cfg]\nslurm:\n  tme: 1\n")
                .find("camp.yaml:4: slurm.tme: unknown key"),
            std::string::npos);
  EXPECT_NE(ErrorOf("output: o\nscenarios:\n  - path: x.cfg\n    egoz: all\n")
                .find("camp.yaml:4: scenarios[0].egoz: unknown key"),
            std::string::npos);
}

// YAML parsers keep the first of two equal keys in a mapping and drop the second silently.
TEST(CampaignFile, AKeyGivenTwiceIsAnErrorNamingBothLines) {
  EXPECT_EQ(ErrorOf("output: o\nscenarios: [x.cfg]\noutput: p\n"),
            "/tmp/c/camp.yaml:3: output: given twice (first at line 1); keep one");
  EXPECT_EQ(ErrorOf("output: o\nscenarios: [x.cfg]\ngrid:\n  driver:\n    warn-threshold: [0.5]\n"
                    "    warn-threshold: [0.7]\n"),
            "/tmp/c/camp.yaml:6: grid.driver.warn-threshold: given twice (first at line 5); keep "
            "one");
  EXPECT_NE(ErrorOf("output: o\nscenarios:\n  - path: x.cfg\n    name: a\n    name: b\n")
                .find("camp.yaml:5: scenarios[0].name: given twice (first at line 4)"),
            std::string::npos);
}

TEST(CampaignFile, EmptyGridsAreErrors) {
  EXPECT_NE(ErrorOf("output: o\nscenarios: [x.cfg]\ngrid:\n  driver:\n    profiles: []\n")
                .find("camp.yaml:5: grid.driver.profiles: empty grid axis"),
            std::string::npos);
  EXPECT_NE(
      ErrorOf("output: o\nscenarios: [x.cfg]\ngrid:\n  driver: {}\n").find("grid: empty grid"),
      std::string::npos);
  EXPECT_NE(ErrorOf("output: o\nscenarios: []\n").find("camp.yaml:2: scenarios: empty list"),
            std::string::npos);
  EXPECT_NE(ErrorOf("output: o\nscenarios: [x.cfg]\ngrid:\n  sumo:\n    seed: {range: [5, 1]}\n")
                .find("grid.sumo.seed.range: last is smaller than first"),
            std::string::npos);
}

TEST(CampaignFile, WrongTypesNameKeyAndLine) {
  EXPECT_NE(ErrorOf("output: o\nscenarios: [x.cfg]\nrepetitions: two\n")
                .find("camp.yaml:3: repetitions: expected a whole number, got 'two'"),
            std::string::npos);
  EXPECT_NE(ErrorOf("output: o\nscenarios: [x.cfg]\nrepetitions: 0\n")
                .find("repetitions: must be at least 1"),
            std::string::npos);
  EXPECT_NE(ErrorOf("output: o\nscenarios: x.cfg\n")
                .find("camp.yaml:2: scenarios: expected a list of files"),
            std::string::npos);
  EXPECT_NE(ErrorOf("output: o\nscenarios: [x.cfg]\ngrid:\n  driver:\n    profiles: 6\n")
                .find("camp.yaml:5: grid.driver.profiles: expected a list of values"),
            std::string::npos);
  EXPECT_NE(ErrorOf("output: o\nscenarios: [x.cfg]\ngrid:\n  driver:\n    profiles: [[6]]\n")
                .find("grid.driver.profiles: grid values must be single values"),
            std::string::npos);
  EXPECT_NE(ErrorOf("output: o\nscenarios: [x.cfg]\nlimits:\n  time_s: soon\n")
                .find("camp.yaml:4: limits.time_s: expected a number"),
            std::string::npos);
  EXPECT_NE(ErrorOf("output: o\nscenarios: [x.cfg]\ndriver:\n  act: {a: 1}\n")
                .find("camp.yaml:4: driver.act: expected a value"),
            std::string::npos);
  EXPECT_NE(ErrorOf("output: o\nscenarios: [x.cfg]\negos: {kind: car}\n")
                .find("camp.yaml:3: egos.kind: unknown key"),
            std::string::npos);
  EXPECT_NE(
      ErrorOf("output: [o]\nscenarios: [x.cfg]\n").find("camp.yaml:1: output: expected a text"),
      std::string::npos);
}

TEST(CampaignFile, MissingRequiredKeys) {
  EXPECT_NE(ErrorOf("scenarios: [x.cfg]\n").find("output: missing"), std::string::npos);
  EXPECT_NE(ErrorOf("output: o\n").find("scenarios: missing"), std::string::npos);
  EXPECT_NE(ErrorOf("").find("expected a campaign"), std::string::npos);
}

TEST(CampaignFile, OptionsTheCampaignOwnsAreRefused) {
  EXPECT_NE(ErrorOf("output: o\nscenarios: [x.cfg]\ndriver:\n  output: r.sqlite\n")
                .find("camp.yaml:4: driver.output: set by the campaign"),
            std::string::npos);
  EXPECT_NE(ErrorOf("output: o\nscenarios: [x.cfg]\ndriver:\n  --act: warn\n")
                .find("driver.--act: write option names without leading dashes"),
            std::string::npos);
  EXPECT_NE(
      ErrorOf("output: o\nscenarios: [x.cfg]\ndriver:\n  act: warn\ngrid:\n  driver:\n    act: "
              "[warn, brake]\n")
          .find("camp.yaml:7: grid.driver.act: also fixed at line 4"),
      std::string::npos);
}

TEST(CampaignFile, YamlSyntaxErrorsHaveTheLine) {
  EXPECT_NE(ErrorOf("output: o\nscenarios: [x.cfg\n").find("camp.yaml:3: YAML syntax error"),
            std::string::npos);
}

TEST(CampaignFile, BooleansOnlyFromPlainTrueFalse) {
  const CampaignSpec c = ParseCampaign(
      "output: o\nscenarios: [x.cfg]\nsumo:\n  a: \"true\"\n  b: yes\n  c: True\n", "/t/c.yaml");
  EXPECT_FALSE(c.sumo_options[0].boolean);
  EXPECT_FALSE(c.sumo_options[1].boolean);
  EXPECT_TRUE(c.sumo_options[2].boolean);
  EXPECT_EQ(c.sumo_options[2].values[0], "true");
  EXPECT_NE(ErrorOf("output: o\nscenarios: [x.cfg]\ngrid:\n  driver:\n    x: [true, 3]\n")
                .find("mixes true/false"),
            std::string::npos);
}

TEST(CampaignFile, DuplicateGridValuesAreErrors) {
  EXPECT_NE(ErrorOf("output: o\nscenarios: [x.cfg]\ngrid:\n  sumo:\n    seed: [1, 2, 1]\n")
                .find("value '1' appears twice"),
            std::string::npos);
}

}  // namespace
}  // namespace criticality::campaign
