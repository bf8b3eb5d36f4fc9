#include "plugin/driver.h"

#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include "plugin/act_stage.h"
#include "plugin/estimate_stage.h"
#include "plugin/event_script.h"
#include "plugin/observe_stage.h"
#include "plugin/record_stage.h"
#include "plugin/results_db.h"
#include "plugin/scene_stage.h"
#include "plugin/sumo_world.h"

namespace fs = std::filesystem;

namespace criticality::plugin {
namespace {

std::atomic<int> g_signal{0};
extern "C" void OnSignal(int sig) {
  g_signal = sig;
  std::signal(sig, SIG_DFL);  // a second one ends the process at once
}

std::string Join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ",") + x;
  return s;
}

std::string OneLine(std::string s) {
  for (char& c : s) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return s;
}

double Seconds(std::chrono::steady_clock::duration d) {
  return std::chrono::duration<double>(d).count();
}

// Resident memory now, from /proc (0 where there is none).
double RssMb() {
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  if (!f) return 0.0;
  long pages = 0, resident = 0;
  const int n = std::fscanf(f, "%ld %ld", &pages, &resident);
  std::fclose(f);
  return n == 2 ? resident * (sysconf(_SC_PAGESIZE) / 1048576.0) : 0.0;
}

double MaxRssMb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;  // KiB on Linux
}

double CpuSeconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

std::unique_ptr<SumoWorld> Open(const DriverOptions& o) {
  if (!o.connect.empty()) {
    const auto colon = o.connect.rfind(':');  // validated by ParseDriverOptions
    return ConnectLibtraci(o.connect.substr(0, colon), std::stoi(o.connect.substr(colon + 1)));
  }
  std::vector<std::string> args{"-c",   o.sumo_config,      "--no-step-log",
                                "true", "--xml-validation", "never"};
  args.insert(args.end(), o.sumo_args.begin(), o.sumo_args.end());
  return StartLibsumo(args);
}

// --record-scenes: a new or empty folder (scene files of different runs must not mix).
void PrepareSceneFolder(const std::string& dir) {
  std::error_code ec;
  if (fs::exists(dir, ec)) {
    if (!fs::is_directory(dir, ec))
      throw std::invalid_argument("--record-scenes '" + dir + "' is a file, not a folder");
    if (!fs::is_empty(dir, ec)) {
      throw std::invalid_argument("--record-scenes '" + dir +
                                  "' is not empty; give a new or empty folder");
    }
  }
  fs::create_directories(dir, ec);
  if (ec) throw std::invalid_argument("--record-scenes '" + dir + "': " + ec.message());
}

}  // namespace

int ExitCodeFor(std::exception_ptr error, std::string* message) {
  try {
    std::rethrow_exception(error);
  } catch (const std::invalid_argument& e) {  // options, scenario content, estimator input
    *message = OneLine(e.what());
    return kExitBadInput;
  } catch (const SumoError& e) {
    *message = "SUMO error: " + OneLine(e.what());
    return kExitSumo;
  } catch (const ResultsError& e) {
    *message = OneLine(e.what());
    return kExitResults;
  } catch (const EgoError& e) {
    *message = OneLine(e.what());
    return kExitEgo;
  } catch (const std::exception& e) {
    *message = "internal error: " + OneLine(e.what());
    return kExitInternal;
  } catch (...) {
    *message = "internal error: unknown exception";
    return kExitInternal;
  }
}

int RunDriver(const DriverOptions& o, RunSummary* summary) {
  const auto wall0 = std::chrono::steady_clock::now();
  RunSummary& sum = *summary;
  sum.category = o.category;
  // Without SUMO_HOME, SUMO may try slow web lookups for XML schemas (DESIGN.md).
  if (!std::getenv("SUMO_HOME") && fs::exists("/usr/share/sumo"))
    setenv("SUMO_HOME", "/usr/share/sumo", 0);
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);

  std::unique_ptr<ResultsDb> db;
  std::unique_ptr<SumoWorld> world;
  bool stepped = false;  // a step was made: from then on the database is kept
  double t = 0.0;
  std::unique_ptr<ActStage> act;
  std::unique_ptr<RecordStage> record;
  auto finish = [&](const std::string& status, const std::string& error) {
    sum.status = status;
    sum.error = error;
    sum.sim_time_s = t;
    sum.wall_s = Seconds(std::chrono::steady_clock::now() - wall0);
    sum.max_rss_mb = MaxRssMb();
    sum.cpu_s = CpuSeconds();
    if (!db) return;
    if (!stepped && status != "completed") {  // failed before its first step: leave no file
      db->Discard();
      sum.output.clear();
      return;
    }
    try {
      if (act && record) {
        for (const std::string& ego : act->OpenEpisodes()) record->CloseEpisode(ego, t);
      }
      db->EndRun(status, sum.end_reason, error, SummaryJson(sum));
    } catch (const std::exception&) {
      // the database itself failed (e.g. disk full): what was committed stays readable
    }
  };

  try {
    if (!o.record_scenes.empty()) PrepareSceneFolder(o.record_scenes);
    db = std::make_unique<ResultsDb>(o.output);
    sum.output = o.output;
    world = Open(o);
    const double dt = world->StepLength();
    db->BeginRun(o.command_line, world->Version(), o.all_vehicles ? "*" : Join(o.egos), dt);
    db->SetScenario(o.expect, o.expect_partner, o.quiet_until_s, o.category);

    ExtractionConfig cfg;
    cfg.range_m = o.range_m;
    cfg.horizon_s = o.params.horizon_s;
    cfg.max_accel_mps2 = o.params.vehicle_accel_max_mps2;
    cfg.whole_network = o.all_vehicles;
    // The stages of a step, in the order data flows.
    ObserveStage observe(o, world.get(), cfg);
    SceneStage scenes(o);
    EstimateStage estimate(o);
    act = std::make_unique<ActStage>(o, world.get());
    record = std::make_unique<RecordStage>(o, db.get());
    EventScript script(o.events, world.get());
    observe.CheckNamedEgos();

    // libsumo does not stop at the configuration's end time by itself.
    const double sumo_end = world->EndTime();
    double end = sumo_end;
    const bool end_option = o.end_time_s >= 0.0 && (sumo_end < 0.0 || o.end_time_s < sumo_end);
    if (end_option) end = o.end_time_s;
    const bool tty = o.progress && isatty(2);
    auto last_print = wall0, last_rss = wall0;
    double rss_mb = 0.0;
    using Clock = std::chrono::steady_clock;
    while (true) {
      const double next = world->Time();
      if (g_signal) {
        sum.end_reason = "interrupted";
        break;
      }
      if (end >= 0.0 && next >= end - 1e-9) {
        sum.end_reason = end_option ? "end-option" : "sumo-end";
        break;
      }
      if (world->ExpectedObjects() <= 0) {
        sum.end_reason = "sumo-end";
        break;
      }
      script.ApplyDue(next, dt);
      StepTimeRow times;
      auto t0 = Clock::now();
      world->Step();
      stepped = true;
      auto t1 = Clock::now();
      times.sumo_ms = 1e3 * Seconds(t1 - t0);
      const Observation obs = observe.Run();
      t = obs.time_s;
      times.time_s = t;
      script.Left(obs.arrived);
      auto t2 = Clock::now();
      times.observe_ms = 1e3 * Seconds(t2 - t1);
      const SceneBatch batch = scenes.Run(obs);
      auto t3 = Clock::now();
      times.scenes_ms = 1e3 * Seconds(t3 - t2);
      const std::vector<Result> results = estimate.Run(batch);
      auto t4 = Clock::now();
      times.estimate_ms = 1e3 * Seconds(t4 - t3);
      const ActOutcome acted = act->Run(obs, batch, results);
      auto t5 = Clock::now();
      times.act_ms = 1e3 * Seconds(t5 - t4);
      record->Run(obs, batch, acted);
      times.estimates = static_cast<int>(acted.steps.size());
      for (const EgoStep& s : acted.steps) times.shortcut_estimates += s.shortcut ? 1 : 0;
      times.record_ms = 1e3 * Seconds(Clock::now() - t5);
      if (Seconds(t5 - last_rss) >= 2.0 || sum.steps == 0) {
        rss_mb = RssMb();
        last_rss = t5;
      }
      times.rss_mb = rss_mb;
      record->Commit(times);
      auto t6 = Clock::now();

      sum.steps += 1;
      sum.sim_time_s = t;
      sum.times.sumo_s += Seconds(t1 - t0);
      sum.times.observe_s += Seconds(t2 - t1);
      sum.times.scenes_s += Seconds(t3 - t2);
      sum.times.estimate_s += Seconds(t4 - t3);
      sum.times.act_s += Seconds(t5 - t4);
      sum.times.record_s += Seconds(t6 - t5);
      sum.egos = observe.EgosSeen();
      sum.invalid_objects = scenes.invalid_objects();
      sum.ego_events += static_cast<long long>(obs.ego_events.size());
      for (const CollisionEvent& c : obs.collisions) {
        ++sum.collisions;
        if (c.involves_ego) ++sum.ego_collisions;
        if (o.expect == "collision" && !sum.expectation_met.value_or(false) && c.involves_ego &&
            (o.expect_partner.empty() || c.sumo.collider == o.expect_partner ||
             c.sumo.victim == o.expect_partner)) {
          sum.expectation_met = true;
        }
      }
      for (const EgoStep& s : acted.steps) {
        ++sum.estimates;
        sum.shortcut_estimates += s.shortcut ? 1 : 0;
        sum.objects_out_of_reach += s.objects - s.objects_in_reach;
        sum.estimator_ms_sum += s.estimator_ms;
        sum.estimator_ms_max = std::max(sum.estimator_ms_max, s.estimator_ms);
      }
      for (const WarningEvent& w : acted.warnings) sum.warnings += w.change == WarningChange::kOpen;
      sum.actions += static_cast<long long>(acted.actions.size());
      if (tty && t6 - last_print > std::chrono::milliseconds(500)) {
        std::fprintf(stderr,
                     "\r  t = %.1f s  %.0f steps/s  egos %zu  warnings %lld  collisions %lld   ", t,
                     sum.steps / std::max(Seconds(t6 - wall0), 1e-9), batch.scenes.size(),
                     sum.warnings, sum.collisions);
        last_print = t6;
      }
      if (observe.AllNamedEgosDone()) {
        sum.end_reason = "egos-arrived";
        break;
      }
    }
    if (tty) std::fprintf(stderr, "\n");
    if (o.expect == "collision" && !sum.expectation_met) sum.expectation_met = false;
    if (o.expect == "no-collision") sum.expectation_met = sum.ego_collisions == 0;
    for (const std::string& e : script.Pending()) {
      std::fprintf(stderr,
                   "sumo-criticality: warning: event '%s' was never applied (its target "
                   "never entered the network before the run ended)\n",
                   e.c_str());
    }
    if (g_signal) {
      sum.exit_code = g_signal == SIGTERM ? kExitSigterm : kExitSigint;
      finish("interrupted", "");
    } else {
      const std::string never = observe.NeverDeparted(t);
      if (!never.empty()) throw EgoError(never);
      sum.exit_code = kExitDone;
      finish("completed", "");
    }
  } catch (...) {
    std::string message;
    sum.exit_code = ExitCodeFor(std::current_exception(), &message);
    sum.end_reason = "error";
    finish("failed", message);
  }
  if (world) world->Close();
  return sum.exit_code;
}

}  // namespace criticality::plugin
