#include "tools/campaign/report.h"

#include <gtest/gtest.h>

#include <map>
#include <utility>

#include "tests/tools/campaign/campaign_test_util.h"
#include "tools/campaign/hotspots.h"
#include "tools/campaign/merge.h"
#include "tools/campaign/run_campaign.h"

namespace criticality::campaign {
namespace {

using testing::ReadFile;
using testing::StandInDriver;
using testing::TempDir;
using testing::WriteFile;

// The stand-in collides at t = 1.0 unless it brakes; it warns at 0.6 (until 1.1): a warned
// run has one ego collision anticipated by 0.4 s, a braking run none (one avoided).
CampaignFolder RunCampaignOf(const TempDir& d, const std::string& driver_extra,
                             bool collide = true) {
  WriteFile(d / "a/scenario.cfg", "sumo-config = x.sumocfg\n");
  WriteFile(d / "b/scenario.cfg", "sumo-config = x.sumocfg\n");
  WriteFile(d / "c.yaml",
            std::string("output: out\nscenarios: [a/scenario.cfg, b/scenario.cfg]\ndriver:\n") +
                (collide ? "  stand-in-collide: 1.0\n" : "") + "  stand-in-warn: 0.6\n" +
                driver_extra +
                "grid:\n  driver:\n    act: [warn, brake]\n  sumo:\n    seed: [1, 2]\n");
  const Plan p(LoadCampaignFile(d / "c.yaml"));
  RunOptions o;
  o.jobs = 2;
  o.driver = StandInDriver();
  o.progress = nullptr;
  RunCampaign(p, d / "out", o);
  CampaignFolder f = CampaignFolder::Open(d / "out");
  MergeCampaign(f);
  return f;
}

// CSV rows as maps (no quoting in these tables).
std::vector<std::map<std::string, std::string>> Csv(const std::filesystem::path& file) {
  std::vector<std::map<std::string, std::string>> rows;
  std::istringstream in(ReadFile(file));
  std::string line;
  std::vector<std::string> header;
  auto split = [](const std::string& l) {
    std::vector<std::string> out;
    std::string cell;
    std::istringstream s(l);
    while (std::getline(s, cell, ',')) out.push_back(cell);
    if (!l.empty() && l.back() == ',') out.push_back("");
    return out;
  };
  while (std::getline(in, line)) {
    if (header.empty()) {
      header = split(line);
      continue;
    }
    const auto cells = split(line);
    std::map<std::string, std::string> row;
    for (std::size_t k = 0; k < header.size(); ++k)
      row[header[k]] = k < cells.size() ? cells[k] : "";
    rows.push_back(row);
  }
  return rows;
}

ReportOptions NoPlots() {
  ReportOptions o;
  o.plots = false;
  return o;
}

TEST(Report, TablesHoldTheKnownNumbers) {
  TempDir d;
  const CampaignFolder f = RunCampaignOf(d, "");
  const ReportResult r = MakeReport(f, NoPlots());
  const auto rows = Csv(r.dir / "summary.csv");
  ASSERT_EQ(rows.size(), 4u);  // (a, b) x (warn, brake); seeds aggregated
  const auto& warn = rows[0];
  EXPECT_EQ(warn.at("scenario"), "a");
  EXPECT_EQ(warn.at("act"), "warn");
  EXPECT_EQ(warn.at("runs"), "2");
  EXPECT_EQ(warn.at("ok"), "2");
  EXPECT_EQ(warn.at("collisions"), "2");
  EXPECT_EQ(warn.at("ego_collisions"), "2");
  EXPECT_EQ(warn.at("warned_collisions"), "2");
  EXPECT_EQ(warn.at("anticipation_mean_s"), "0.4");
  EXPECT_EQ(warn.at("anticipation_median_s"), "0.4");
  EXPECT_EQ(warn.at("anticipation_min_s"), "0.4");
  EXPECT_EQ(warn.at("warnings"), "2");
  EXPECT_EQ(warn.at("false_alarms"), "0");
  EXPECT_EQ(warn.at("collisions_avoided"), "");
  EXPECT_EQ(warn.at("estimator_ms_mean"), "1.1");
  EXPECT_EQ(warn.at("estimator_ms_max"), "1.2");
  EXPECT_EQ(warn.at("steps"), "20");
  const auto& brake = rows[1];
  EXPECT_EQ(brake.at("act"), "brake");
  EXPECT_EQ(brake.at("collisions"), "0");
  // Its warnings are not false alarms: the same run with act=warn collides (braking avoided it).
  EXPECT_EQ(brake.at("false_alarms"), "0");
  EXPECT_EQ(brake.at("collisions_avoided"), "2");
  EXPECT_EQ(brake.at("anticipation_mean_s"), "");
  EXPECT_EQ(rows[2].at("scenario"), "b");

  const auto by = Csv(r.dir / "by_parameter.csv");
  ASSERT_EQ(by.size(), 6u);  // act=warn: all, a, b; act=brake: all, a, b
  EXPECT_EQ(by[0].at("parameter"), "act");
  EXPECT_EQ(by[0].at("scenario"), "(all)");
  EXPECT_EQ(by[0].at("ego_collisions"), "4");
  EXPECT_EQ(by[3].at("collisions_avoided"), "4");

  const auto hot = Csv(r.dir / "hotspots.csv");
  ASSERT_EQ(hot.size(), 2u);
  EXPECT_EQ(hot[0].at("kind"), "edge");
  EXPECT_EQ(hot[0].at("id"), "e1");
  EXPECT_EQ(hot[0].at("collisions"), "2");
  // Older run files: no warning locations, and the report says so.
  bool noted = false;
  for (const auto& n : r.notes) noted = noted || n.find("warning locations") != std::string::npos;
  EXPECT_TRUE(noted);
  // 4 ego collisions: fewer than the default 5 for a reliability diagram.
  EXPECT_FALSE(std::filesystem::exists(r.dir / "reliability.csv"));
  EXPECT_NE(ReadFile(r.dir / "summary.md").find("4 egos collided in successful runs; at least 5"),
            std::string::npos);
  EXPECT_EQ(r.figures_missing, "--no-plots");
}

TEST(Report, AWarningWithoutACollisionInEitherRunIsAFalseAlarm) {
  TempDir d;
  const ReportResult r = MakeReport(RunCampaignOf(d, "", /*collide=*/false), NoPlots());
  const auto rows = Csv(r.dir / "summary.csv");
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0].at("false_alarms"), "2");  // warn
  EXPECT_EQ(rows[1].at("false_alarms"), "2");  // brake: nothing to avoid either
  EXPECT_EQ(rows[1].at("collisions_avoided"), "0");
}

TEST(Report, AWarningFollowedByItsEgosOverlapIsNoFalseAlarm) {
  // The warning runs 0.6-1.1 s, the report's grace is 1 s: an overlap of the ego's body at
  // 1.8 s follows it, one at 2.5 s does not.
  using Case = std::pair<const char*, const char*>;
  for (const auto& [at, expected] : {Case{"1.8", "0"}, Case{"2.5", "2"}}) {
    TempDir d;
    const ReportResult r = MakeReport(
        RunCampaignOf(d, std::string("  stand-in-overlap: ") + at + "\n", /*collide=*/false),
        NoPlots());
    const auto rows = Csv(r.dir / "summary.csv");
    ASSERT_EQ(rows.size(), 4u);
    EXPECT_EQ(rows[0].at("false_alarms"), expected) << "overlap at " << at;  // warn
    EXPECT_EQ(rows[1].at("false_alarms"), expected) << "overlap at " << at;  // brake
  }
}

TEST(Report, ReliabilityCountsStepsBeforeTheCrash) {
  TempDir d;
  const CampaignFolder f = RunCampaignOf(d, "");
  ReportOptions o = NoPlots();
  o.reliability_min_collisions = 3;
  const ReportResult r = MakeReport(f, o);
  const auto bins = Csv(r.dir / "reliability.csv");
  ASSERT_EQ(bins.size(), 10u);
  long long steps = 0;
  for (const auto& b : bins) steps += std::stoll(b.at("steps"));
  // 4 colliding runs x 9 steps before t = 1.0, 4 braking runs x 10 steps.
  EXPECT_EQ(steps, 76);
  const std::string md = ReadFile(r.dir / "summary.md");
  EXPECT_NE(md.find("76 estimates of egos in successful runs (up to each ego's first collision), 4 "
                    "egos collided; 36 estimates were followed"),
            std::string::npos)
      << md;
}

TEST(Report, ReliabilityUsesEachRunsHorizon) {
  TempDir d;
  ReportOptions o = NoPlots();
  o.reliability_min_collisions = 3;
  // --horizon 0.5 on every command line: of the 9 steps before t = 1.0, t = 0.5 .. 0.9 count.
  const ReportResult r = MakeReport(RunCampaignOf(d, "  horizon: 0.5\n"), o);
  EXPECT_NE(testing::ReadFile(r.dir / "summary.md").find("4 egos collided; 20 estimates were"),
            std::string::npos);
}

TEST(Report, NewerRunFilesLocateWarningsAndMissingColumnsAreNoted) {
  TempDir d;
  const CampaignFolder newer = RunCampaignOf(d, "  stand-in-newer: true\n");
  const ReportResult r = MakeReport(newer, NoPlots());
  const auto hot = Csv(r.dir / "hotspots.csv");
  ASSERT_FALSE(hot.empty());
  EXPECT_EQ(hot[0].at("id"), "e1");
  EXPECT_EQ(hot[0].at("warnings"), "4");  // per scenario: 2 warn + 2 brake runs
  EXPECT_EQ(hot[0].at("collisions"), "2");
  for (const auto& n : r.notes) EXPECT_EQ(n.find("warning locations"), std::string::npos) << n;

  TempDir d2;
  const CampaignFolder old = RunCampaignOf(d2, "  stand-in-no-anticipation: true\n");
  const ReportResult r2 = MakeReport(old, NoPlots());
  const auto rows = Csv(r2.dir / "summary.csv");
  EXPECT_EQ(rows[0].at("ego_collisions"), "2");
  EXPECT_EQ(rows[0].at("warned_collisions"), "");
  EXPECT_EQ(rows[0].at("anticipation_mean_s"), "");
  bool noted = false;
  for (const auto& n : r2.notes) noted = noted || n.find("anticipation_s") != std::string::npos;
  EXPECT_TRUE(noted);
}

TEST(Hotspots, LanesAndInternalLanesMapToEdgesAndJunctions) {
  EXPECT_EQ(NetworkElement("e1_0", true), (std::pair<std::string, std::string>{"edge", "e1"}));
  EXPECT_EQ(NetworkElement("a_b_2", true), (std::pair<std::string, std::string>{"edge", "a_b"}));
  EXPECT_EQ(NetworkElement(":C_3_0", true), (std::pair<std::string, std::string>{"junction", "C"}));
  EXPECT_EQ(NetworkElement(":J_1_w0_0", true),
            (std::pair<std::string, std::string>{"junction", "J_1"}));
  EXPECT_EQ(NetworkElement(":C_c0", false), (std::pair<std::string, std::string>{"junction", "C"}));
  EXPECT_EQ(NetworkElement("e1", false), (std::pair<std::string, std::string>{"edge", "e1"}));
}

}  // namespace
}  // namespace criticality::campaign
