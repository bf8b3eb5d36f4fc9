#include "plugin/run/co_simulation.h"

#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include "plugin/act/act_stage.h"
#include "plugin/estimate/estimate_ahead.h"
#include "plugin/estimate/estimate_stage.h"
#include "plugin/network/road_network.h"
#include "plugin/observe/observe_stage.h"
#include "plugin/record/record_stage.h"
#include "plugin/record/results_db.h"
#include "plugin/run/exit_codes.h"
#include "plugin/scenes/scene_stage.h"
#include "plugin/script/event_script.h"

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

using Clock = std::chrono::steady_clock;

double Seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

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

// --record-scenes: a new or empty folder (scene files of different runs must not mix). Returns
// whether it made the folder.
bool PrepareSceneFolder(const std::string& dir) {
  std::error_code ec;
  if (fs::exists(dir, ec)) {
    if (!fs::is_directory(dir, ec))
      throw std::invalid_argument("--record-scenes '" + dir + "' is a file, not a folder");
    if (!fs::is_empty(dir, ec)) {
      throw std::invalid_argument("--record-scenes '" + dir +
                                  "' is not empty; give a new or empty folder");
    }
    return false;
  }
  fs::create_directories(dir, ec);
  if (ec) throw std::invalid_argument("--record-scenes '" + dir + "': " + ec.message());
  return true;
}

// The wall time of each stage of one step (ms), and where they go. Pipelined, the estimate's is
// its own thread's, overlapping SUMO's next step.
struct StepDurations {
  double sumo{0.0}, observe{0.0}, scenes{0.0}, estimate{0.0}, act{0.0}, record{0.0};
  void Into(StepTimeRow* row) const {
    row->sumo_ms = sumo;
    row->observe_ms = observe;
    row->scenes_ms = scenes;
    row->estimate_ms = estimate;
    row->act_ms = act;
    row->record_ms = record;
  }
  void Into(StageTimes* st) const {
    st->sumo_s += 1e-3 * sumo;
    st->observe_s += 1e-3 * observe;
    st->scenes_s += 1e-3 * scenes;
    st->estimate_s += 1e-3 * estimate;
    st->act_s += 1e-3 * act;
    st->record_s += 1e-3 * record;
  }
};

// Milliseconds since *t; *t becomes now.
double Lap(Clock::time_point* t) {
  const Clock::time_point now = Clock::now();
  const double ms = 1e3 * Seconds(now - *t);
  *t = now;
  return ms;
}

// The egos of `next` (the step after the one being acted on) that SUMO no longer lets us
// publish to: they left the simulation or began a teleport.
PublishTo AllBut(const Observation& next) {
  PublishTo to;
  to.gone.insert(next.left.begin(), next.left.end());
  for (const EgoEvent& e : next.ego_events) {
    if (LeavesTheRoad(e.kind)) to.gone.insert(e.ego);
  }
  return to;
}

// One run: SUMO, the results database and the five stages, stepped until the run ends.
class CoSimulation {
 public:
  CoSimulation(const DriverOptions& options, RunSummary* summary, const OpenWorld& open)
      : o_(options), sum_(*summary), open_(open), wall0_(Clock::now()) {
    sum_.category = o_.run.category;
  }
  ~CoSimulation() {
    if (world_) world_->Close();
  }

  int Run() {
    try {
      Start();
      while (!Ended()) Step();
      if (InFlight()) FinishInFlight(PublishTo{});  // no step since: every ego is there
      End();
    } catch (...) {
      std::string message;
      sum_.exit_code = ExitCodeFor(std::current_exception(), &message);
      RecordInFlight();
      sum_.end_reason = "error";
      Finish("failed", message);
    }
    return sum_.exit_code;
  }

 private:
  // The scene folder, the database, SUMO, the stages; named egos checked before any step.
  void Start() {
    if (!o_.record.scene_folder.empty())
      made_scene_folder_ = PrepareSceneFolder(o_.record.scene_folder);
    db_ = std::make_unique<ResultsDb>(o_.run.output);
    sum_.output = o_.run.output;
    world_ = open_(o_.run);
    dt_ = world_->StepLength();
    db_->BeginRun(o_.run.command_line, world_->Version(),
                  o_.observe.all_vehicles ? "*" : Join(o_.observe.egos), dt_);
    db_->SetScenario(o_.run.expect, o_.run.expect_partner, o_.run.quiet_until_s,
                     o_.run.category);
    observe_ = std::make_unique<ObserveStage>(o_.observe, world_.get());
    // SUMO moves vehicles by x += v_new * dt unless it uses its ballistic update (told to, or
    // switched to it by an action step length): the estimator predicts the positions that
    // update gives (Scene::euler_update_step_s). SUMO may switch later (SwitchedToBallistic).
    euler_ = !world_->BallisticUpdate();
    const bool euler = euler_;
    WarnOfLanesOffShape();
    // Whether SUMO moves a vehicle into the next lane within one step (no sublane model,
    // lanechange.duration 0): the headings it reports then (ObjectReader::HeadingOf).
    SceneConfig scenes = o_.scenes;
    const LaneChanging lc = world_->LaneChangingModel();
    scenes.instant_lane_changes = !lc.sublane && !(lc.duration_s > 0.0);
    scenes_ = std::make_unique<SceneStage>(scenes, dt_, euler, world_.get(), world_.get());
    estimate_ = std::make_unique<EstimateStage>(o_.params, o_.estimator);
    // Under --act brake the closed loop needs step k's results before SUMO's step k+1.
    sum_.pipelined = o_.run.pipeline && o_.act.act != Act::kBrake;
    if (sum_.pipelined) ahead_ = std::make_unique<EstimateAhead>(estimate_.get());
    // The closed loop's hand-back check estimates between batches: only under --act brake,
    // which never pipelines.
    EstimateStage* one = estimate_.get();
    act_ = std::make_unique<ActStage>(
        o_.act, world_.get(), dt_,
        sum_.pipelined ? std::function<Result(const Scene&)>{}
                       : std::function<Result(const Scene&)>(
                             [one](const Scene& scene) { return one->One(scene); }));
    record_ = std::make_unique<RecordStage>(o_.record, db_.get());
    script_ = std::make_unique<EventScript>(o_.run.events, world_.get());
    observe_->CheckNamedEgos();
    // libsumo does not stop at the configuration's end time by itself.
    const double sumo_end = world_->EndTime();
    end_option_ = o_.run.end_time_s >= 0.0 && (sumo_end < 0.0 || o_.run.end_time_s < sumo_end);
    end_ = end_option_ ? o_.run.end_time_s : sumo_end;
    if (o_.run.progress && isatty(2)) progress_ = std::make_unique<ProgressLine>(true);
    begin_s_ = world_->Time();
  }

  // Whether the run ends before the next step; sets the summary's end reason.
  bool Ended() {
    if (g_signal) {
      sum_.end_reason = "interrupted";
    } else if (end_ >= 0.0 && world_->Time() >= end_ - 1e-9) {
      sum_.end_reason = end_option_ ? "end-option" : "sumo-end";
    } else if (world_->ExpectedObjects() <= 0) {
      sum_.end_reason = "sumo-end";
    } else if (observe_->AllNamedEgosDone() && stepped_) {
      sum_.end_reason = "egos-arrived";
    }
    return !sum_.end_reason.empty();
  }

  // One step: SUMO moves, then observe -> scenes -> estimate -> act -> record. Pipelined, the
  // estimate runs on its own thread while SUMO makes the next step and the driver observes it;
  // act and record of this step come after that (FinishInFlight), and the results are the same.
  void Step() {
    script_->ApplyDue(world_->Time(), dt_);
    if (progress_) progress_->Hold();
    StepDurations d;
    Clock::time_point t = Clock::now();
    world_->Step();
    stepped_ = true;
    d.sumo = Lap(&t);
    SwitchedToBallistic();
    Observation obs = observe_->Run();
    script_->Left(obs.arrived);
    d.observe = Lap(&t);
    if (InFlight()) FinishInFlight(AllBut(obs));  // the step before, published one step late
    t = Clock::now();
    SceneBatch batch = scenes_->Run(obs);
    d.scenes = Lap(&t);
    if (ahead_) {
      flight_.obs = std::move(obs);
      flight_.batch = std::move(batch);
      flight_.d = d;
      ahead_->Start(&flight_.batch);
    } else {
      const std::vector<Result> results = estimate_->Run(batch);
      d.estimate = Lap(&t);
      Complete(obs, batch, results, &d, PublishTo{});
    }
    Progress(Clock::now(), last_egos_);
  }

  bool InFlight() const { return ahead_ && ahead_->busy(); }

  // Lanes whose length differs from their drawn shape (explicit edge lengths): SUMO moves
  // vehicles by the length, the estimator predicts in the drawn coordinates (a warning, once).
  void WarnOfLanesOffShape() {
    const LanesOffShape off = LanesWithLengthOffShape(*world_);
    if (off.lanes == 0) return;
    std::fprintf(stderr,
                 "sumo-criticality: warning: %d lane(s) of the network have a length that differs "
                 "from their drawn shape by more than %.0f %% (most: '%s', length %.1f m, drawn "
                 "%.1f m; explicit edge lengths): SUMO moves vehicles along them by the length, "
                 "the estimator predicts their motion in the drawn coordinates, so its estimates "
                 "on those lanes are not to be trusted\n",
                 off.lanes, 100.0 * kLengthOffShapeShare, off.worst.c_str(), off.worst_length_m,
                 off.worst_shape_m);
  }

  // SUMO switches to its ballistic update when it loads a vehicle type whose action step
  // length differs from the step length: the scenes from then on predict continuous motion.
  void SwitchedToBallistic() {
    if (!euler_ || !world_->BallisticUpdate()) return;
    euler_ = false;
    scenes_->SwitchToBallistic();
    std::fprintf(stderr,
                 "sumo-criticality: note: SUMO moves vehicles by its ballistic update from "
                 "t = %.2f s (a vehicle type's actionStepLength differs from the step length); "
                 "the scenes predict continuous motion from then on\n",
                 world_->Time());
  }

  // The pipelined step's results, then its act and record.
  void FinishInFlight(const PublishTo& publish) {
    double wait_ms = 0.0;
    const std::vector<Result> results = ahead_->Finish(&flight_.d.estimate, &wait_ms);
    sum_.times.estimate_wait_s += 1e-3 * wait_ms;
    Complete(flight_.obs, flight_.batch, results, &flight_.d, publish);
  }

  // A run that fails with an estimate under way still records that step (nothing computed is
  // lost), publishing nothing: SUMO may be what failed.
  void RecordInFlight() {
    if (!InFlight() || !db_) return;
    try {
      PublishTo none;
      none.any = false;
      FinishInFlight(none);
    } catch (...) {
      // the estimate or the database failed as well: the first error is the one reported
    }
  }

  // Act and record of one step whose results are in.
  void Complete(const Observation& obs, const SceneBatch& batch, const std::vector<Result>& results,
                StepDurations* d, const PublishTo& publish) {
    t_ = obs.time_s;
    Clock::time_point t = Clock::now();
    const ActOutcome acted = act_->Run(obs, batch, results, publish);
    d->act = Lap(&t);
    record_->Run(obs, batch, acted);
    d->record = Lap(&t);  // the row's own commit is not in it
    record_->Commit(TimeRow(*d, acted));
    d->record += Lap(&t);
    d->Into(&sum_.times);
    Account(obs, acted);
    last_egos_ = batch.scenes.size();
  }

  StepTimeRow TimeRow(const StepDurations& d, const ActOutcome& acted) {
    StepTimeRow row;
    row.time_s = t_;
    d.Into(&row);
    row.estimates = static_cast<int>(acted.steps.size());
    for (const EgoStep& s : acted.steps) row.shortcut_estimates += s.shortcut ? 1 : 0;
    const Clock::time_point now = Clock::now();
    if (Seconds(now - last_rss_) >= 2.0 || sum_.steps == 0) {
      rss_mb_ = RssMb();
      last_rss_ = now;
    }
    row.rss_mb = rss_mb_;
    return row;
  }

  // The step's counts into the summary.
  void Account(const Observation& obs, const ActOutcome& acted) {
    sum_.steps += 1;
    sum_.sim_time_s = t_;
    sum_.egos = record_->EgosEstimated();
    sum_.invalid_objects = scenes_->invalid_objects();
    sum_.conditioned_states = scenes_->conditioned_states();
    sum_.parked_objects = scenes_->parked_objects();
    sum_.other_class_objects = scenes_->other_class_objects();
    sum_.parked_egos = scenes_->parked_egos();
    sum_.ego_events += static_cast<long long>(obs.ego_events.size());
    for (const CollisionEvent& c : obs.collisions) {
      ++sum_.collisions;
      if (!c.involves_ego) continue;
      ++sum_.ego_collisions;
      const std::string& partner = o_.run.expect_partner;
      if (o_.run.expect == "collision" &&
          (partner.empty() || c.sumo.collider == partner || c.sumo.victim == partner)) {
        sum_.expectation_met = true;
      }
    }
    for (const EgoStep& s : acted.steps) {
      ++sum_.estimates;
      // Exposure: each estimate stands for one step of its ego on the road.
      sum_.vehicle_hours += dt_ / 3600.0;
      sum_.vehicle_km += s.speed_mps * dt_ / 1000.0;
      sum_.shortcut_estimates += s.shortcut ? 1 : 0;
      sum_.objects_out_of_reach += s.objects - s.objects_in_reach;
      sum_.estimator_ms_sum += s.estimator_ms;
      sum_.estimator_ms_max = std::max(sum_.estimator_ms_max, s.estimator_ms);
    }
    for (const WarningEvent& w : acted.warnings) sum_.warnings += w.change == WarningChange::kOpen;
    sum_.actions += static_cast<long long>(acted.actions.size());
  }

  // The progress line, at most every 0.5 s (at once after SUMO wrote something: the line was
  // cleared for it).
  void Progress(Clock::time_point now, size_t egos, bool force = false) {
    if (!progress_) return;
    const bool wrote = progress_->Release();
    if (!force && !wrote && now - last_print_ < std::chrono::milliseconds(500)) return;
    ProgressState p;
    p.time_s = t_;
    p.begin_s = begin_s_;
    p.end_s = end_;
    p.wall_s = Seconds(now - wall0_);
    p.steps = sum_.steps;
    p.egos = static_cast<long long>(egos);
    p.warnings = sum_.warnings;
    p.collisions = sum_.collisions;
    progress_->Show(ProgressText(p));
    last_print_ = now;
  }

  // The run ended without an error (SUMO, --end, the egos, or a signal).
  void End() {
    if (progress_) {
      Progress(Clock::now(), last_egos_, true);  // the final state, then a line of its own
      progress_->End();
    }
    if (o_.run.expect == "collision" && !sum_.expectation_met) sum_.expectation_met = false;
    if (o_.run.expect == "no-collision") sum_.expectation_met = sum_.ego_collisions == 0;
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
    if (progress_) {
      progress_->Release();
      progress_->End();
    }
    sum_.status = status;
    sum_.error = error;
    sum_.sim_time_s = t_;
    sum_.wall_s = Seconds(Clock::now() - wall0_);
    sum_.max_rss_mb = MaxRssMb();
    sum_.cpu_s = CpuSeconds();
    if (!stepped_ && status != "completed" && made_scene_folder_) {
      std::error_code ec;  // a run that failed before its first step leaves no empty folder
      if (fs::is_empty(o_.record.scene_folder, ec)) fs::remove(o_.record.scene_folder, ec);
    }
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
  const OpenWorld& open_;
  const Clock::time_point wall0_;
  bool made_scene_folder_{false};
  std::unique_ptr<ResultsDb> db_;
  std::unique_ptr<SumoWorld> world_;
  // The stages of a step, in the order data flows.
  std::unique_ptr<ObserveStage> observe_;
  std::unique_ptr<SceneStage> scenes_;
  std::unique_ptr<EstimateStage> estimate_;
  std::unique_ptr<ActStage> act_;
  std::unique_ptr<RecordStage> record_;
  std::unique_ptr<EventScript> script_;
  // Pipelined: the step being estimated (alive until its act and record), and the thread that
  // estimates it (declared after it: destroyed first, waiting for the estimate).
  struct InFlightStep {
    Observation obs;
    SceneBatch batch;
    StepDurations d;
  } flight_;
  std::unique_ptr<EstimateAhead> ahead_;
  double dt_{0.1}, t_{0.0}, end_{-1.0}, begin_s_{0.0};
  bool end_option_{false};
  std::unique_ptr<ProgressLine> progress_;  ///< on a terminal only
  size_t last_egos_{0};
  bool stepped_{false};  ///< a step was made: from then on the database is kept
  bool euler_{true};     ///< SUMO moves vehicles by its Euler update (else ballistic)
  Clock::time_point last_print_{}, last_rss_{};
  double rss_mb_{0.0};
};

}  // namespace

int RunDriver(const DriverOptions& o, RunSummary* summary, const OpenWorld& open) {
  // Without SUMO_HOME, SUMO may try slow web lookups for XML schemas (DESIGN.md).
  if (!std::getenv("SUMO_HOME") && fs::exists("/usr/share/sumo"))
    setenv("SUMO_HOME", "/usr/share/sumo", 0);
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  CoSimulation run(o, summary, open);
  return run.Run();
}

}  // namespace criticality::plugin
