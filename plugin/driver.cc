#include "plugin/driver.h"

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
#include "plugin/observe_stage.h"
#include "plugin/record_stage.h"
#include "plugin/results_db.h"
#include "plugin/scene_stage.h"
#include "plugin/sumo_world.h"

namespace fs = std::filesystem;

namespace criticality::plugin {
namespace {

std::atomic<bool> g_stop{false};
extern "C" void OnSignal(int) { g_stop = true; }

std::string Join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ",") + x;
  return s;
}

std::string JsonString(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
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

}  // namespace

void RunDriver(const DriverOptions& o, std::ostream& summary) {
  // Without SUMO_HOME, SUMO may try slow web lookups for XML schemas (DESIGN.md).
  if (!std::getenv("SUMO_HOME") && fs::exists("/usr/share/sumo"))
    setenv("SUMO_HOME", "/usr/share/sumo", 0);
  if (!o.record_scenes.empty()) {
    std::error_code ec;
    fs::create_directories(o.record_scenes, ec);
    if (ec)
      throw std::invalid_argument("--record-scenes '" + o.record_scenes + "': " + ec.message());
  }
  ResultsDb db(o.output);
  std::unique_ptr<SumoWorld> world;
  std::string status = "completed";
  try {
    world = Open(o);
    db.BeginRun(o.command_line, world->Version(), o.all_vehicles ? "*" : Join(o.egos));
  } catch (const std::exception& e) {
    db.BeginRun(o.command_line, "", o.all_vehicles ? "*" : Join(o.egos));
    db.EndRun(std::string("failed: ") + e.what());
    throw;
  }
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);

  // The stages of a step, in the order data flows.
  ObserveStage observe(o, world.get());
  SceneStage scenes(o, world.get());
  EstimateStage estimate(o);
  ActStage act(o, world.get());
  RecordStage record(o, &db);

  const bool tty = o.progress && isatty(2);
  long long steps = 0, estimates = 0, warnings = 0, actions = 0, collisions = 0;
  double ms_sum = 0.0, ms_max = 0.0, t = 0.0;
  const auto wall0 = std::chrono::steady_clock::now();
  auto last_print = wall0;
  std::vector<bool> applied(o.events.size(), false);

  auto close_all_episodes = [&](double end) {
    for (const std::string& ego : act.OpenEpisodes()) record.CloseEpisode(ego, end);
  };

  try {
    const double dt = world->StepLength();
    // libsumo does not stop at the configuration's end time by itself.
    double end = world->EndTime();
    if (o.end_time_s >= 0.0 && (end < 0.0 || o.end_time_s < end)) end = o.end_time_s;
    while (!g_stop) {
      t = world->Time();
      if (end >= 0.0 && t >= end - 1e-9) break;
      if (world->ExpectedObjects() <= 0) break;
      for (size_t k = 0; k < o.events.size(); ++k) {
        if (!applied[k] && o.events[k].time_s <= t + 0.5 * dt)
          applied[k] = world->Apply(o.events[k]);
      }
      world->Step();
      ++steps;
      const Observation obs = observe.Run();
      t = obs.time_s;
      const SceneBatch batch = scenes.Run(obs);
      const std::vector<Result> results = estimate.Run(batch);
      const ActOutcome acted = act.Run(batch, results);
      record.Run(obs, batch, acted);

      collisions += static_cast<long long>(obs.collisions.size());
      estimates += static_cast<long long>(results.size());
      for (const Result& r : results) {
        ms_sum += r.times.total_ms;
        ms_max = std::max(ms_max, r.times.total_ms);
      }
      for (const WarningEvent& w : acted.warnings) warnings += w.change == WarningChange::kOpen;
      actions += static_cast<long long>(acted.actions.size());
      if (tty) {
        const auto wall = std::chrono::steady_clock::now();
        if (wall - last_print > std::chrono::milliseconds(500)) {
          const double secs = std::chrono::duration<double>(wall - wall0).count();
          std::fprintf(stderr,
                       "\r  t = %.1f s  %.0f steps/s  egos %zu  warnings %lld  collisions %lld   ",
                       t, steps / std::max(secs, 1e-9), batch.egos.size(), warnings, collisions);
          last_print = wall;
        }
      }
    }
    if (tty) std::fprintf(stderr, "\n");
    if (g_stop) status = "interrupted";
    if (!o.all_vehicles) {
      for (const std::string& e : o.egos) {
        if (!observe.seen().count(e)) {
          throw EgoError("ego '" + e + "' never departed by t = " + std::to_string(t) +
                         " s: check its ID and depart time in the routes");
        }
      }
    }
    close_all_episodes(t);
    db.EndRun(status);
  } catch (const std::exception& e) {
    if (tty) std::fprintf(stderr, "\n");
    try {
      close_all_episodes(t);
      db.EndRun(std::string("failed: ") + e.what());
    } catch (const std::exception&) {
      // the database itself failed (e.g. disk full): what was committed stays readable
    }
    world->Close();
    throw;
  }
  world->Close();
  std::string expectation = "null";
  if (o.expect == "collision") expectation = collisions > 0 ? "true" : "false";
  if (o.expect == "no-collision") expectation = collisions == 0 ? "true" : "false";
  summary << "{\"status\":" << JsonString(status) << ",\"sim_time_s\":" << t
          << ",\"steps\":" << steps << ",\"egos\":" << observe.seen().size()
          << ",\"estimates\":" << estimates << ",\"warnings\":" << warnings
          << ",\"actions\":" << actions << ",\"collisions\":" << collisions
          << ",\"estimator_ms_mean\":" << (estimates ? ms_sum / estimates : 0.0)
          << ",\"estimator_ms_max\":" << ms_max << ",\"expectation_met\":" << expectation
          << ",\"output\":" << JsonString(db.path()) << "}\n";
}

}  // namespace criticality::plugin
