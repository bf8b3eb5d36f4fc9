// The whole co-simulation loop on a fake SUMO world, no SUMO: every stage runs each step and
// the results database holds what they produced; errors end the run with their exit code and
// no half-made file.
#include "plugin/run/co_simulation.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sqlite3.h>
#include <termios.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "../fake_sumo_world.h"
#include "../results_query.h"
#include "plugin/run/exit_codes.h"
#include "plugin/run/run_summary.h"

namespace criticality::plugin {
namespace {

using testing::FakeSumoWorld;

using testing::Query;

std::string Output(const char* name) {
  const std::string path = ::testing::TempDir() + name;
  for (const char* suffix : {"", "-wal", "-shm"}) std::remove((path + suffix).c_str());
  return path;
}

// An ego at 15 m/s on a straight two-lane road, a car standing 60 m ahead in its lane.
std::unique_ptr<SumoWorld> Road(const RunConfig&) {
  auto w = std::make_unique<FakeSumoWorld>(0.1);
  w->AddEdge("E", 0, 0, 1000, 0, 2);
  w->AddVehicle("ego", 100, -1.6, 90, 15, "E_0", 100, {"E"});
  w->AddVehicle("standing", 165, -1.6, 90, 0, "E_0", 165, {"E"});
  w->next_report.departed = {"ego", "standing"};
  return w;
}

DriverOptions Options(const std::string& output) {
  DriverOptions o;
  o.run.output = output;
  o.run.end_time_s = 2.0;
  o.run.progress = false;
  o.observe.egos = {"ego"};
  o.params.profiles = 3;  // a small hypothesis set: the loop, not the estimator, is tested
  o.estimator.threads = 1;
  o.estimator.reach_shortcut = true;
  o.act.act = Act::kWarn;
  return o;
}

TEST(CoSimulation, EveryStepGoesThroughEveryStageIntoTheDatabase) {
  const std::string db = Output("loop.sqlite");
  RunSummary summary;
  const int code = RunDriver(Options(db), &summary, Road);
  ASSERT_EQ(code, kExitDone) << summary.error;
  EXPECT_EQ(summary.status, "completed");
  EXPECT_EQ(summary.end_reason, "end-option");
  EXPECT_EQ(summary.steps, 20);  // 0.1 s steps up to 2.0 s
  EXPECT_EQ(summary.estimates, 20);
  EXPECT_EQ(summary.egos, 1);
  EXPECT_EQ(Query(db, "select status || ' ' || end_reason from runs"), "completed end-option");
  EXPECT_EQ(Query(db, "select count(*) from steps where ego = 'ego' and objects = 1"), "20");
  EXPECT_EQ(Query(db, "select count(*) from step_times"), "20");
  EXPECT_EQ(Query(db, "select event from ego_events"), "depart");
  // The stamps are SUMO's: the first step's state is stamped 0.
  EXPECT_EQ(Query(db, "select min(time_s) from steps"), "0.0");
  // Exposure: 20 estimates of 0.1 s, and the distance their speeds cover, as the steps say.
  EXPECT_NEAR(summary.vehicle_hours, 20 * 0.1 / 3600.0, 1e-12);
  EXPECT_NEAR(summary.vehicle_km,
              std::stod(Query(db, "select sum(speed_mps) * 0.1 / 1000 from steps")), 1e-9);
  EXPECT_GT(summary.vehicle_km, 0.0);
  const std::string json = SummaryJson(summary);
  EXPECT_NE(json.find("\"vehicle_hours\":"), std::string::npos) << json;
  EXPECT_NE(json.find("\"vehicle_km\":"), std::string::npos) << json;
  // The criticality rises as the ego closes in on the standing car (15 m/s, 60 m).
  EXPECT_LT(std::stod(Query(db, "select p_collision from steps order by time_s limit 1")),
            std::stod(Query(db, "select p_collision from steps order by time_s desc limit 1")));
}

// The same road with the standing car 25 m ahead: 1.3 s to impact at 15 m/s.
std::unique_ptr<SumoWorld> CloseCall(const RunConfig& run) {
  std::unique_ptr<SumoWorld> w = Road(run);
  static_cast<FakeSumoWorld*>(w.get())->Find("standing")->x_m = 130.0;
  return w;
}

TEST(CoSimulation, EachEgoIsRecordedWithItsClassAndEachWarningWithItsScene) {
  const std::string db = Output("closecall.sqlite");
  DriverOptions o = Options(db);
  o.run.end_time_s = 1.0;
  RunSummary summary;
  ASSERT_EQ(RunDriver(o, &summary, CloseCall), kExitDone) << summary.error;
  EXPECT_EQ(Query(db, "select ego || ' ' || vehicle_class || ' ' || first_s from egos"),
            "ego passenger 0.0");
  EXPECT_EQ(Query(db, "select count(*) from egos"), "1");  // once, not once per step
  ASSERT_GE(std::stoi(Query(db, "select count(*) from warnings")), 1);
  EXPECT_EQ(Query(db, "select count(*) from warnings w join warning_scenes s on s.warning_id = w.id "
                      "and s.time_s = w.start_s and s.ego = w.ego"),
            Query(db, "select count(*) from warnings"));
  // The stored scene is the ego's scene file: it names the standing car.
  const std::string scene = Query(db, "select scene from warning_scenes limit 1");
  EXPECT_EQ(scene.rfind("criticality-scene", 0), 0u) << scene.substr(0, 40);
  EXPECT_NE(scene.find("vehicle standing"), std::string::npos);
}

// The road with a car parked beside it (a parking area: SUMO's stop state 2 + 128) and a ship
// on a waterway nearby; the ego and the parked car are named egos.
std::unique_ptr<SumoWorld> RoadWithParkedCarAndShip(const RunConfig& run) {
  std::unique_ptr<SumoWorld> w = Road(run);
  auto* f = static_cast<FakeSumoWorld*>(w.get());
  f->AddVehicle("parked", 120, -5.6, 90, 0, "E_0", 120, {"E"}).stop_state = 2 | 128;
  f->AddVehicle("ship", 110, 30.0, 90, 3).vehicle_class = "ship";
  f->next_report.departed = {"ego", "standing", "parked", "ship"};
  return w;
}

TEST(CoSimulation, TheSummaryCountsParkedAndOtherClassReadsPerStep) {
  const std::string db = Output("parked.sqlite");
  DriverOptions o = Options(db);
  o.observe.egos = {"ego", "parked"};
  RunSummary summary;
  ASSERT_EQ(RunDriver(o, &summary, RoadWithParkedCarAndShip), kExitDone) << summary.error;
  EXPECT_EQ(summary.steps, 20);
  EXPECT_EQ(summary.estimates, 20);     // the ego only: the parked car is no ego
  EXPECT_EQ(summary.parked_egos, 20);   // once per step
  EXPECT_EQ(summary.parked_objects, 20);
  EXPECT_EQ(summary.other_class_objects, 20);
  EXPECT_EQ(summary.conditioned_states, 0);  // nothing implausible on this road
  EXPECT_EQ(Query(db, "select count(*) from steps where objects = 1"), "20");  // the standing car
  const std::string json = SummaryJson(summary);
  for (const char* key : {"\"parked_egos\":20", "\"parked_objects\":20",
                          "\"other_class_objects\":20", "\"conditioned_states\":0"}) {
    EXPECT_NE(json.find(key), std::string::npos) << key << " in " << json;
  }
}

TEST(CoSimulation, ASumoThatCannotStartIsExitThreeAndLeavesNoFile) {
  const std::string db = Output("nosumo.sqlite");
  RunSummary summary;
  const int code = RunDriver(Options(db), &summary, [](const RunConfig&) -> std::unique_ptr<SumoWorld> {
    throw SumoError("loading SUMO failed: no such network");
  });
  EXPECT_EQ(code, kExitSumo);
  EXPECT_EQ(summary.status, "failed");
  EXPECT_NE(summary.error.find("no such network"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(db));
  EXPECT_TRUE(summary.output.empty());
}

TEST(CoSimulation, ARunThatFailsBeforeItsFirstStepLeavesNoSceneFolderItMade) {
  const std::string db = Output("nosumo_scenes.sqlite");
  const std::string made = ::testing::TempDir() + "scenes_made_by_the_run";
  const std::string given = ::testing::TempDir() + "scenes_given_empty";
  std::filesystem::remove_all(made);
  std::filesystem::remove_all(given);
  std::filesystem::create_directories(given);
  auto no_sumo = [](const RunConfig&) -> std::unique_ptr<SumoWorld> {
    throw SumoError("loading SUMO failed: no such network");
  };
  for (const std::string& folder : {made, given}) {
    DriverOptions o = Options(db);
    o.record.scene_folder = folder;
    RunSummary summary;
    EXPECT_EQ(RunDriver(o, &summary, no_sumo), kExitSumo);
  }
  EXPECT_FALSE(std::filesystem::exists(made));  // made by the run: removed again
  EXPECT_TRUE(std::filesystem::is_directory(given));  // the user's own folder stays
  // A run that steps keeps the folder it made, with the scenes in it.
  DriverOptions o = Options(db);
  o.record.scene_folder = made;
  o.run.end_time_s = 0.5;
  RunSummary summary;
  ASSERT_EQ(RunDriver(o, &summary, CloseCall), kExitDone) << summary.error;
  EXPECT_TRUE(std::filesystem::is_directory(made));
}

TEST(CoSimulation, AScriptedEventForAVehicleNobodyDefinesIsBadInputAtItsTime) {
  const std::string db = Output("badevent.sqlite");
  DriverOptions o = Options(db);
  o.run.events.push_back(ParseEvent("0.5 ghost speed 3"));
  RunSummary summary;
  const int code = RunDriver(o, &summary, Road);
  EXPECT_EQ(code, kExitBadInput);
  EXPECT_NE(summary.error.find("ghost"), std::string::npos);
  // The steps before the event's time are kept.
  EXPECT_EQ(Query(db, "select status from runs"), "failed");
  EXPECT_EQ(Query(db, "select count(*) from steps"), "5");
}

// Every row the run recorded that does not measure time: the steps, warnings and ego events.
std::string Recorded(const std::string& db) {
  return Query(db,
               "select group_concat(r, ';') from (select time_s || ' ' || ego || ' ' || "
               "p_collision || ' ' || p_reference || ' ' || unavoidability || ' ' || objects || "
               "' ' || objects_in_reach || ' ' || speed_mps || ' ' || ifnull(main_object, '-') "
               "as r from steps order by time_s, ego)") +
         "|" +
         Query(db,
               "select group_concat(r, ';') from (select ego || ' ' || start_s || ' ' || "
               "ifnull(end_s, '-') || ' ' || peak_p || ' ' || ifnull(object, '-') as r from "
               "warnings order by id)") +
         "|" +
         Query(db,
               "select group_concat(r, ';') from (select time_s || ' ' || ego || ' ' || event as "
               "r from ego_events order by rowid)");
}

// The close call, the ego leaving the network (arriving) at 1.0 s while it is warned.
std::shared_ptr<std::vector<std::string>> g_published;
std::unique_ptr<SumoWorld> CloseCallEgoArrives(const RunConfig& run) {
  std::unique_ptr<SumoWorld> w = CloseCall(run);
  auto* f = static_cast<FakeSumoWorld*>(w.get());
  f->arrive_at["ego"] = 1.0;
  g_published = f->publish_log;
  return w;
}

// "<time> <rest>" -> {time, rest}.
std::pair<double, std::string> TimeAndRest(const std::string& line) {
  const size_t space = line.find(' ');
  return {std::stod(line.substr(0, space)), line.substr(space + 1)};
}

TEST(CoSimulation, PipelinedTheRunRecordsTheSameAndPublishesOneStepLaterToEgosStillThere) {
  std::string recorded[2];
  std::vector<std::string> published[2];
  RunSummary summary[2];
  for (int pipelined = 0; pipelined < 2; ++pipelined) {
    const std::string db = Output(pipelined ? "pipelined.sqlite" : "serial.sqlite");
    DriverOptions o = Options(db);
    o.run.pipeline = pipelined == 1;
    ASSERT_EQ(RunDriver(o, &summary[pipelined], CloseCallEgoArrives), kExitDone)
        << summary[pipelined].error;
    EXPECT_EQ(summary[pipelined].pipelined, pipelined == 1);
    EXPECT_EQ(summary[pipelined].end_reason, "egos-arrived");
    recorded[pipelined] = Recorded(db);
    published[pipelined] = *g_published;
  }
  EXPECT_EQ(recorded[1], recorded[0]);
  EXPECT_EQ(summary[1].steps, summary[0].steps);
  EXPECT_EQ(summary[1].estimates, summary[0].estimates);
  EXPECT_EQ(summary[1].warnings, summary[0].warnings);
  EXPECT_GE(summary[0].warnings, 1);
  EXPECT_NE(recorded[0].find(" arrive"), std::string::npos) << recorded[0];
  // Serial: each step's criticality reaches SUMO before its next step (the clock one step
  // past the stamp); pipelined, after it (two steps past). The last one, for the step before
  // the ego left, is not published: the ego is gone, and writing to it would fail.
  ASSERT_GE(published[0].size(), 5u);
  ASSERT_EQ(published[1].size(), published[0].size() - 1);
  EXPECT_EQ(published[0].back().substr(published[0].back().size() - 2), " 1")
      << "the ego left while warned: " << published[0].back();
  for (size_t k = 0; k < published[1].size(); ++k) {
    const auto [t_serial, serial] = TimeAndRest(published[0][k]);
    const auto [t_pipelined, pipelined] = TimeAndRest(published[1][k]);
    EXPECT_EQ(pipelined, serial) << k;
    EXPECT_NEAR(t_pipelined - t_serial, 0.1, 1e-9) << k;
  }
}

// The road, and a SUMO that fails when asked for the step to 0.6 s.
std::unique_ptr<SumoWorld> RoadThatFails(const RunConfig& run) {
  std::unique_ptr<SumoWorld> w = Road(run);
  static_cast<FakeSumoWorld*>(w.get())->fail_at_s = 0.6;
  return w;
}

TEST(CoSimulation, ASumoThatFailsWhileAStepIsEstimatedStillRecordsThatStep) {
  std::string recorded[2];
  for (int pipelined = 0; pipelined < 2; ++pipelined) {
    const std::string db = Output(pipelined ? "fails_pipelined.sqlite" : "fails_serial.sqlite");
    DriverOptions o = Options(db);
    o.run.pipeline = pipelined == 1;
    RunSummary summary;
    EXPECT_EQ(RunDriver(o, &summary, RoadThatFails), kExitSumo);
    EXPECT_NE(summary.error.find("fake SUMO fails"), std::string::npos) << summary.error;
    EXPECT_EQ(Query(db, "select status from runs"), "failed");
    // Steps 0.0 .. 0.4: the last one was being estimated when SUMO failed.
    EXPECT_EQ(Query(db, "select count(*) || ' ' || max(time_s) from steps"), "5 0.4");
    recorded[pipelined] = Recorded(db);
  }
  EXPECT_EQ(recorded[1], recorded[0]);
}

// Standard error on a pseudo terminal (raw: no line-ending translation) while it lives.
class TerminalStderr {
 public:
  TerminalStderr() {
    master_ = posix_openpt(O_RDWR | O_NOCTTY);
    grantpt(master_);
    unlockpt(master_);
    slave_ = ::open(ptsname(master_), O_RDWR | O_NOCTTY);
    termios raw{};
    tcgetattr(slave_, &raw);
    cfmakeraw(&raw);
    tcsetattr(slave_, TCSANOW, &raw);
    std::fflush(stderr);
    saved_ = ::dup(2);
    ::dup2(slave_, 2);
  }
  // Standard error back; what reached the terminal.
  std::string Stop() {
    std::fflush(stderr);
    ::dup2(saved_, 2);
    ::close(saved_);
    ::close(slave_);
    std::string out;
    char buf[4096];
    for (ssize_t n; (n = ::read(master_, buf, sizeof buf)) > 0;) out.append(buf, n);
    ::close(master_);
    return out;
  }

 private:
  int master_{-1}, slave_{-1}, saved_{-1};
};

TEST(ProgressLine, WhatAStepWritesStandsOnItsOwnLinesBetweenProgressLines) {
  TerminalStderr terminal;
  {
    ProgressLine line(true);
    ASSERT_TRUE(line.on());
    line.Show("t 1.0 / 10 s");
    line.Hold();  // a step: SUMO writes through its streams and straight to the descriptor
    std::fprintf(stderr, "Warning: Teleporting vehicle 'a'\n");
    ASSERT_EQ(::write(2, "Warning: no newline", 19), 19);
    EXPECT_TRUE(line.Release());
    line.Show("t 2.0 / 10 s");
    line.Hold();  // a quiet step
    EXPECT_FALSE(line.Release());
    line.End();
  }
  EXPECT_EQ(terminal.Stop(),
            "\r  t 1.0 / 10 s\033[K"                                           // the line
            "\r\033[KWarning: Teleporting vehicle 'a'\nWarning: no newline\n"  // cleared, then SUMO
            "\r  t 2.0 / 10 s\033[K"                                           // the line again
            "\n");                                                             // and it stays
}

TEST(ProgressLine, OffItLeavesStandardErrorAlone) {
  TerminalStderr terminal;
  {
    ProgressLine line(false);
    EXPECT_FALSE(line.on());
    line.Show("t 1.0 / 10 s");
    line.Hold();
    std::fprintf(stderr, "Warning: straight through\n");
    EXPECT_FALSE(line.Release());
    line.End();
  }
  EXPECT_EQ(terminal.Stop(), "Warning: straight through\n");
}

TEST(ProgressText, SaysSimulatedAndEndTimeShareDoneAndTimeLeft) {
  ProgressState p;
  p.begin_s = 0.0;
  p.time_s = 30.0;
  p.end_s = 120.0;
  p.wall_s = 10.0;  // 3 simulated s per wall s: 90 s left take 30 s
  p.steps = 300;
  p.egos = 4;
  p.warnings = 2;
  p.collisions = 1;
  const std::string t = ProgressText(p);
  EXPECT_NE(t.find("t 30.0 / 120 s"), std::string::npos) << t;
  EXPECT_NE(t.find(" 25 %"), std::string::npos) << t;
  EXPECT_NE(t.find("ETA 0:30"), std::string::npos) << t;
  EXPECT_NE(t.find("30 steps/s"), std::string::npos) << t;
  EXPECT_NE(t.find("egos 4  warnings 2  collisions 1"), std::string::npos) << t;
  EXPECT_EQ(t.find('\n'), std::string::npos);
  // A run that started later: the share counts from its begin.
  p.begin_s = 100.0;
  p.time_s = 110.0;
  p.end_s = 140.0;
  p.wall_s = 3600.0;  // 10 s in an hour: 30 s left take three hours
  EXPECT_NE(ProgressText(p).find(" 25 %  ETA 3:00:00"), std::string::npos) << ProgressText(p);
  // No end time known: no share, no ETA.
  p.end_s = -1.0;
  const std::string open = ProgressText(p);
  EXPECT_EQ(open.find('%'), std::string::npos) << open;
  EXPECT_EQ(open.find("ETA"), std::string::npos) << open;
  EXPECT_NE(open.find("ends when SUMO does"), std::string::npos) << open;
}

}  // namespace
}  // namespace criticality::plugin
