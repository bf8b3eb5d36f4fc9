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

namespace {

using Clock = std::chrono::steady_clock;

// One run: SUMO, the results database and the five stages, stepped until the run ends.
class CoSimulation {
 public:
  CoSimulation(const DriverOptions& options, RunSummary* summary)
      : o_(options), sum_(*summary), wall0_(Clock::now()) {
    sum_.category = o_.category;
  }
  ~CoSimulation() {
    if (world_) world_->Close();
  }

  int Run() {
    try {
      Start();
      while (!Ended()) Step();
      End();
    } catch (...) {
      std::string message;
      sum_.exit_code = ExitCodeFor(std::current_exception(), &message);
      sum_.end_reason = "error";
      Finish("failed", message);
    }
    return sum_.exit_code;
  }

 private:
  // The scene folder, the database, SUMO, the stages; named egos checked before any step.
  void Start() {
    if (!o_.record_scenes.empty()) PrepareSceneFolder(o_.record_scenes);
    db_ = std::make_unique<ResultsDb>(o_.output);
    sum_.output = o_.output;
    world_ = Open(o_);
    dt_ = world_->StepLength();
    db_->BeginRun(o_.command_line, world_->Version(), o_.all_vehicles ? "*" : Join(o_.egos), dt_);
    db_->SetScenario(o_.expect, o_.expect_partner, o_.quiet_until_s, o_.category);
    ExtractionConfig cfg;
    cfg.range_m = o_.range_m;
    cfg.horizon_s = o_.params.horizon_s;
    cfg.max_accel_mps2 = o_.params.vehicle_accel_max_mps2;
    cfg.whole_network = o_.all_vehicles;
    cfg.lane_sampling = LaneSamplingFor(o_.params);
    observe_ = std::make_unique<ObserveStage>(o_, world_.get(), cfg);
    // SUMO moves vehicles by x += v_new * dt unless told to use the ballistic update: the
    // estimator predicts the positions that update gives (Scene::euler_update_step_s).
    const bool ballistic = world_->Option("step-method.ballistic") == "true";
    scenes_ = std::make_unique<SceneStage>(o_, ballistic ? 0.0 : dt_);
    estimate_ = std::make_unique<EstimateStage>(o_);
    act_ = std::make_unique<ActStage>(o_, world_.get());
    record_ = std::make_unique<RecordStage>(o_, db_.get());
    script_ = std::make_unique<EventScript>(o_.events, world_.get());
    observe_->CheckNamedEgos();
    // libsumo does not stop at the configuration's end time by itself.
    const double sumo_end = world_->EndTime();
    end_option_ = o_.end_time_s >= 0.0 && (sumo_end < 0.0 || o_.end_time_s < sumo_end);
    end_ = end_option_ ? o_.end_time_s : sumo_end;
    tty_ = o_.progress && isatty(2);
  }

  // Whether the run ends before the next step; sets the summary's end reason.
  bool Ended() {
    if (g_signal) {
      sum_.end_reason = "interrupted";
    } else if (end_ >= 0.0 && world_->Time() >= end_ - 1e-9) {
      sum_.end_reason = end_option_ ? "end-option" : "sumo-end";
    } else if (world_->ExpectedObjects() <= 0) {
      sum_.end_reason = "sumo-end";
    } else if (observe_->AllNamedEgosDone() && sum_.steps > 0) {
      sum_.end_reason = "egos-arrived";
    }
    return !sum_.end_reason.empty();
  }

  // One step: SUMO moves, then observe -> scenes -> estimate -> act -> record.
  void Step() {
    script_->ApplyDue(world_->Time(), dt_);
    StepTimeRow times;
    const auto t0 = Clock::now();
    world_->Step();
    stepped_ = true;
    const auto t1 = Clock::now();
    const Observation obs = observe_->Run();
    t_ = times.time_s = obs.time_s;
    script_->Left(obs.arrived);
    const auto t2 = Clock::now();
    const SceneBatch batch = scenes_->Run(obs);
    const auto t3 = Clock::now();
    const std::vector<Result> results = estimate_->Run(batch);
    const auto t4 = Clock::now();
    const ActOutcome acted = act_->Run(obs, batch, results);
    const auto t5 = Clock::now();
    record_->Run(obs, batch, acted);
    times.sumo_ms = 1e3 * Seconds(t1 - t0);
    times.observe_ms = 1e3 * Seconds(t2 - t1);
    times.scenes_ms = 1e3 * Seconds(t3 - t2);
    times.estimate_ms = 1e3 * Seconds(t4 - t3);
    times.act_ms = 1e3 * Seconds(t5 - t4);
    times.record_ms = 1e3 * Seconds(Clock::now() - t5);
    times.estimates = static_cast<int>(acted.steps.size());
    for (const EgoStep& s : acted.steps) times.shortcut_estimates += s.shortcut ? 1 : 0;
    if (Seconds(t5 - last_rss_) >= 2.0 || sum_.steps == 0) {
      rss_mb_ = RssMb();
      last_rss_ = t5;
    }
    times.rss_mb = rss_mb_;
    record_->Commit(times);
    const auto t6 = Clock::now();
    StageTimes& st = sum_.times;
    st.sumo_s += Seconds(t1 - t0);
    st.observe_s += Seconds(t2 - t1);
    st.scenes_s += Seconds(t3 - t2);
    st.estimate_s += Seconds(t4 - t3);
    st.act_s += Seconds(t5 - t4);
    st.record_s += Seconds(t6 - t5);
    Account(obs, acted);
    Progress(t6, batch.scenes.size());
  }

  // The step's counts into the summary.
  void Account(const Observation& obs, const ActOutcome& acted) {
    sum_.steps += 1;
    sum_.sim_time_s = t_;
    sum_.egos = observe_->EgosSeen();
    sum_.invalid_objects = scenes_->invalid_objects();
    sum_.ego_events += static_cast<long long>(obs.ego_events.size());
    for (const CollisionEvent& c : obs.collisions) {
      ++sum_.collisions;
      if (!c.involves_ego) continue;
      ++sum_.ego_collisions;
      if (o_.expect == "collision" &&
          (o_.expect_partner.empty() || c.sumo.collider == o_.expect_partner ||
           c.sumo.victim == o_.expect_partner)) {
        sum_.expectation_met = true;
      }
    }
    for (const EgoStep& s : acted.steps) {
      ++sum_.estimates;
      sum_.shortcut_estimates += s.shortcut ? 1 : 0;
      sum_.objects_out_of_reach += s.objects - s.objects_in_reach;
      sum_.estimator_ms_sum += s.estimator_ms;
      sum_.estimator_ms_max = std::max(sum_.estimator_ms_max, s.estimator_ms);
    }
    for (const WarningEvent& w : acted.warnings) sum_.warnings += w.change == WarningChange::kOpen;
    sum_.actions += static_cast<long long>(acted.actions.size());
  }

  void Progress(Clock::time_point now, size_t egos) {
    if (!tty_ || now - last_print_ < std::chrono::milliseconds(500)) return;
    std::fprintf(
        stderr, "\r  t = %.1f s  %.0f steps/s  egos %zu  warnings %lld  collisions %lld   ", t_,
        sum_.steps / std::max(Seconds(now - wall0_), 1e-9), egos, sum_.warnings, sum_.collisions);
    last_print_ = now;
  }

  // The run ended without an error (SUMO, --end, the egos, or a signal).
  void End() {
    if (tty_) std::fprintf(stderr, "\n");
    if (o_.expect == "collision" && !sum_.expectation_met) sum_.expectation_met = false;
    if (o_.expect == "no-collision") sum_.expectation_met = sum_.ego_collisions == 0;
    for (const std::string& e : script_->Pending()) {
      std::fprintf(stderr,
                   "sumo-criticality: warning: event '%s' was never applied (its target never "
                   "entered the network before the run ended)\n",
                   e.c_str());
    }
    if (g_signal) {
      sum_.exit_code = g_signal == SIGTERM ? kExitSigterm : kExitSigint;
      Finish("interrupted", "");
      return;
    }
    const std::string never = observe_->NeverDeparted(t_);
    if (!never.empty()) throw EgoError(never);
    sum_.exit_code = kExitDone;
    Finish("completed", "");
  }

  // The summary's last fields, and the database's end (or no database at all when the run
  // failed before its first step).
  void Finish(const std::string& status, const std::string& error) {
    if (tty_ && status == "failed") std::fprintf(stderr, "\n");
    sum_.status = status;
    sum_.error = error;
    sum_.sim_time_s = t_;
    sum_.wall_s = Seconds(Clock::now() - wall0_);
    sum_.max_rss_mb = MaxRssMb();
    sum_.cpu_s = CpuSeconds();
    if (!db_) return;
    if (!stepped_ && status != "completed") {
      db_->Discard();
      sum_.output.clear();
      return;
    }
    try {
      if (act_ && record_) {
        for (const std::string& ego : act_->OpenEpisodes()) record_->CloseEpisode(ego, t_);
      }
      db_->EndRun(status, sum_.end_reason, error, SummaryJson(sum_));
    } catch (const std::exception&) {
      // the database itself failed (e.g. disk full): what was committed stays readable
    }
  }

  const DriverOptions& o_;
  RunSummary& sum_;
  const Clock::time_point wall0_;
  std::unique_ptr<ResultsDb> db_;
  std::unique_ptr<SumoWorld> world_;
  // The stages of a step, in the order data flows.
  std::unique_ptr<ObserveStage> observe_;
  std::unique_ptr<SceneStage> scenes_;
  std::unique_ptr<EstimateStage> estimate_;
  std::unique_ptr<ActStage> act_;
  std::unique_ptr<RecordStage> record_;
  std::unique_ptr<EventScript> script_;
  double dt_{0.1}, t_{0.0}, end_{-1.0};
  bool end_option_{false}, tty_{false};
  bool stepped_{false};  ///< a step was made: from then on the database is kept
  Clock::time_point last_print_{}, last_rss_{};
  double rss_mb_{0.0};
};

}  // namespace

int RunDriver(const DriverOptions& o, RunSummary* summary) {
  // Without SUMO_HOME, SUMO may try slow web lookups for XML schemas (DESIGN.md).
  if (!std::getenv("SUMO_HOME") && fs::exists("/usr/share/sumo"))
    setenv("SUMO_HOME", "/usr/share/sumo", 0);
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  CoSimulation run(o, summary);
  return run.Run();
}

}  // namespace criticality::plugin
