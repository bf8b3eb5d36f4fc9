#include "tools/campaign/report.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <utility>

#include "tests/tools/campaign/campaign_test_util.h"
#include "tools/campaign/hotspots.h"
#include "tools/campaign/merge.h"
#include "tools/campaign/run_campaign.h"
#include "tools/campaign/sqlite_db.h"

namespace criticality::campaign {
namespace {

using testing::ReadFile;
using testing::StandInDriver;
using testing::TempDir;
using testing::WriteFile;

// The stand-in collides at t = 1.0 unless it brakes; it warns at 0.6 (until 1.1): a warned
// run has one ego collision anticipated by 0.4 s, a braking run none (one avoided).
CampaignFolder RunCampaignOf(const TempDir& d, const std::string& driver_extra, bool collide = true,
                             const std::string& driver_axes = "") {
  WriteFile(d / "a/scenario.cfg", "sumo-config = x.sumocfg\n");
  WriteFile(d / "b/scenario.cfg", "sumo-config = x.sumocfg\n");
  WriteFile(d / "c.yaml",
            std::string("output: out\nscenarios: [a/scenario.cfg, b/scenario.cfg]\ndriver:\n") +
                (collide ? "  stand-in-collide: 1.0\n" : "") + "  stand-in-warn: 0.6\n" +
                driver_extra + "grid:\n  driver:\n    act: [warn, brake]\n" + driver_axes +
                "  sumo:\n    seed: [1, 2]\n");
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
  ASSERT_EQ(hot.size(), 4u);  // per scenario and setting
  EXPECT_EQ(hot[0].at("scenario"), "a");
  EXPECT_EQ(hot[0].at("parameters"), "act=warn");
  EXPECT_EQ(hot[0].at("id"), "e1");
  EXPECT_EQ(hot[0].at("warnings"), "2");  // its 2 seeds
  EXPECT_EQ(hot[0].at("collisions"), "2");
  EXPECT_EQ(hot[1].at("parameters"), "act=brake");
  EXPECT_EQ(hot[1].at("warnings"), "2");
  EXPECT_EQ(hot[1].at("collisions"), "0");  // braking avoided them
  const auto points = Csv(r.dir / "events.csv");
  bool collision_point = false;
  for (const auto& p : points) {
    if (p.at("event") != "collision") continue;
    collision_point = true;
    EXPECT_EQ(p.at("parameters"), "act=warn");
    EXPECT_EQ(p.at("time_s"), "1");
  }
  EXPECT_TRUE(collision_point);
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

double Number(const std::map<std::string, std::string>& row, const std::string& key) {
  return std::stod(row.at(key));
}

const std::map<std::string, std::string>& RateRow(
    const std::vector<std::map<std::string, std::string>>& rows, const std::string& breakdown,
    const std::string& measure, const std::string& parameters = "-",
    const std::string& vehicle_class = "(all)", const std::string& scenario = "(all)") {
  for (const auto& r : rows) {
    if (r.at("breakdown") == breakdown && r.at("measure") == measure &&
        r.at("parameters") == parameters && r.at("vehicle_class") == vehicle_class &&
        r.at("scenario") == scenario)
      return r;
  }
  static const std::map<std::string, std::string> none;
  ADD_FAILURE() << "no rates row " << breakdown << " / " << measure << " / " << parameters;
  return none;
}

// Each stand-in run: 10 estimates of 0.1 s at 10 m/s: 1/3600 h and 0.01 km. The 4 act=warn runs
// collide once each, the 4 act=brake runs do not.
TEST(Report, ExposureAndRatesWithIntervalsAcrossSeeds) {
  TempDir d;
  const CampaignFolder f = RunCampaignOf(d, "  stand-in-newer: true\n");
  const ReportResult r = MakeReport(f, NoPlots());
  const auto per_run = Csv(r.dir / "exposure.csv");
  ASSERT_EQ(per_run.size(), 8u);
  EXPECT_NEAR(Number(per_run[0], "vehicle_hours"), 1.0 / 3600, 1e-7);
  EXPECT_NEAR(Number(per_run[0], "vehicle_km"), 0.01, 1e-9);
  EXPECT_EQ(per_run[0].at("ego_collisions"), "1");
  const auto rates = Csv(r.dir / "rates.csv");
  const auto& all = RateRow(rates, "all runs", "ego collisions");
  EXPECT_EQ(all.at("events"), "4");
  EXPECT_EQ(all.at("runs"), "8");
  EXPECT_NEAR(Number(all, "per_vehicle_hour"), 4 / (8.0 / 3600), 1e-6);  // 1800
  // Runs of 1 and 0 collisions around a rate of 0.5 per run: SE = sqrt(8/7 * 8 * 0.25) / 8 per
  // run, t(7) = 2.365.
  const double half = 2.365 * std::sqrt(8.0 / 7 * 2) / 8 * 3600;
  EXPECT_NEAR(Number(all, "per_vehicle_hour_low"), 1800 - half, 2.0);
  EXPECT_NEAR(Number(all, "per_vehicle_hour_high"), 1800 + half, 2.0);
  EXPECT_EQ(all.at("interval"), "runs");
  EXPECT_NEAR(Number(all, "per_million_vehicle_km"), 4 / 0.08 * 1e6, 1.0);
  // Per setting: act=warn collides in each of its runs (no spread), act=brake never (Poisson).
  const auto& warn = RateRow(rates, "parameter", "ego collisions", "act=warn");
  EXPECT_NEAR(Number(warn, "per_vehicle_hour"), 3600, 1e-6);
  EXPECT_NEAR(Number(warn, "per_vehicle_hour_low"), 3600, 1e-6);
  EXPECT_NEAR(Number(warn, "per_vehicle_hour_high"), 3600, 1e-6);
  const auto& brake = RateRow(rates, "parameter", "ego collisions", "act=brake");
  EXPECT_EQ(brake.at("events"), "0");
  EXPECT_EQ(Number(brake, "per_vehicle_hour"), 0.0);
  EXPECT_NEAR(Number(brake, "per_vehicle_hour_high"), 3.689 / (4.0 / 3600), 2.0);
  EXPECT_EQ(brake.at("interval"), "poisson");
  // The braking runs' warnings are no false alarms (their twins collided).
  EXPECT_EQ(RateRow(rates, "parameter", "false alarms", "act=brake").at("events"), "0");
  // Per vehicle class, and the same in the campaign database.
  const auto classes = Csv(r.dir / "by_vehicle_class.csv");
  ASSERT_EQ(classes.size(), 1u);
  EXPECT_EQ(classes[0].at("vehicle_class"), "passenger");
  EXPECT_EQ(classes[0].at("runs"), "8");
  EXPECT_EQ(classes[0].at("ego_collisions"), "4");
  EXPECT_EQ(RateRow(rates, "vehicle class", "warnings", "-", "passenger").at("events"), "8");
  SqliteDb db((f.dir() / "campaign.sqlite").string(), false);
  Statement s = db.Prepare(
      "SELECT count(*), sum(vehicle_hours), sum(vehicle_km), sum(ego_collisions) FROM "
      "report_exposure");
  ASSERT_TRUE(s.Step());
  EXPECT_EQ(s.Int(0), 8);
  EXPECT_NEAR(s.Real(1), 8.0 / 3600, 1e-9);
  EXPECT_NEAR(s.Real(2), 0.08, 1e-9);
  EXPECT_EQ(s.Int(3), 4);
  const auto summary = Csv(r.dir / "summary.csv");
  EXPECT_NEAR(Number(summary[0], "vehicle_hours"), 2.0 / 3600, 1e-7);
  EXPECT_NE(ReadFile(r.dir / "summary.md").find("## Rates per exposure"), std::string::npos);
}

TEST(Report, RatesSplitByVehicleClass) {
  TempDir d;
  const CampaignFolder f = RunCampaignOf(d, "  stand-in-newer: true\n", true,
                                         "    stand-in-class: [passenger, truck]\n");
  const ReportResult r = MakeReport(f, NoPlots());
  const auto classes = Csv(r.dir / "by_vehicle_class.csv");
  ASSERT_EQ(classes.size(), 2u);
  EXPECT_EQ(classes[1].at("vehicle_class"), "truck");
  EXPECT_EQ(classes[1].at("runs"), "8");
  EXPECT_EQ(classes[1].at("ego_collisions"), "4");
  const auto rates = Csv(r.dir / "rates.csv");
  EXPECT_NEAR(
      Number(RateRow(rates, "vehicle class", "ego collisions", "-", "truck"), "per_vehicle_hour"),
      1800, 1e-6);
}

TEST(Report, OlderRunFilesSayExposureIsNotComputable) {
  TempDir d;
  const ReportResult r = MakeReport(RunCampaignOf(d, ""), NoPlots());
  bool noted = false;
  for (const auto& n : r.notes) noted = noted || n.find("runs.step_length_s") != std::string::npos;
  EXPECT_TRUE(noted);
  EXPECT_TRUE(Csv(r.dir / "rates.csv").empty());
  EXPECT_EQ(Csv(r.dir / "summary.csv")[0].at("vehicle_hours"), "");
  EXPECT_NE(ReadFile(r.dir / "summary.md").find("exposure (vehicle-hours, vehicle-km) and rates"),
            std::string::npos);
}

TEST(Report, TheWarningListSaysWhatFollowedEachWarningAndWhetherItsSceneWasKept) {
  TempDir d;
  const ReportResult r = MakeReport(RunCampaignOf(d, "  stand-in-newer: true\n"), NoPlots());
  const auto w = Csv(r.dir / "warnings.csv");
  ASSERT_EQ(w.size(), 8u);
  EXPECT_EQ(w[0].at("parameters"), "act=warn");
  EXPECT_EQ(w[0].at("outcome"), "collision");
  EXPECT_EQ(w[0].at("vehicle_class"), "passenger");
  EXPECT_EQ(w[0].at("start_s"), "0.6");
  EXPECT_EQ(w[0].at("warning_id"), "1");
  EXPECT_EQ(w[0].at("scene"), "yes");
  EXPECT_EQ(w[2].at("parameters"), "act=brake");
  EXPECT_EQ(w[2].at("outcome"), "avoided");  // its act=warn twin collided
  TempDir d2;
  const auto old = Csv(MakeReport(RunCampaignOf(d2, "", false), NoPlots()).dir / "warnings.csv");
  ASSERT_EQ(old.size(), 8u);
  EXPECT_EQ(old[0].at("outcome"), "false alarm");
  EXPECT_EQ(old[0].at("scene"), "no");  // older run files keep no scenes
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
