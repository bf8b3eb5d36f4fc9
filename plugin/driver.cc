#include "plugin/driver.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>

#include "criticality/estimator.h"
#include "criticality/scene_io.h"
#include "plugin/results_db.h"
#include "plugin/sumo_world.h"

namespace fs = std::filesystem;

namespace criticality::plugin {
namespace {

std::atomic<bool> g_stop{false};
extern "C" void OnSignal(int) { g_stop = true; }

struct EgoState {
  bool warning{false};
  long long episode{0};
  double peak{0.0};
  bool braking{false};
};

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
  Estimator estimator(o.params, o.estimator);
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

  const ExtractionConfig cfg{o.range_m, o.params.horizon_s, o.params.vehicle_accel_max_mps2};
  const bool tty = o.progress && isatty(2);
  std::map<std::string, EgoState> egos;
  std::set<std::string> seen, arrived, active_pairs;
  std::vector<bool> applied(o.events.size(), false);
  long long steps = 0, estimates = 0, warnings = 0, actions = 0, collisions = 0;
  double ms_sum = 0.0, ms_max = 0.0, t = 0.0;
  const auto wall0 = std::chrono::steady_clock::now();
  auto last_print = wall0;

  auto close_all_episodes = [&](double end) {
    for (auto& [id, s] : egos) {
      if (s.warning) db.CloseWarning(s.episode, end);
      s.warning = false;
    }
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
      t = world->Time();
      for (const std::string& id : world->TeleportingIds()) {
        if (egos.count(id) || (!o.all_vehicles && std::count(o.egos.begin(), o.egos.end(), id))) {
          throw EgoError("ego '" + id + "' was teleported by SUMO at t = " + std::to_string(t) +
                         " s (jam or collision with teleport action); its estimates would jump. "
                         "Use --collision.action warn, or another ego");
        }
      }
      for (const std::string& id : world->ArrivedIds()) {
        if (egos.count(id)) {
          if (egos[id].warning) db.CloseWarning(egos[id].episode, t);
          egos.erase(id);
        }
        arrived.insert(id);
        // A named ego whose route ends while the simulation goes on would silently stop being
        // estimated: that is a scenario error (an ego arriving with the run's end is fine).
        const bool named = !o.all_vehicles && std::count(o.egos.begin(), o.egos.end(), id);
        const bool run_goes_on = world->ExpectedObjects() > 0 && (end < 0.0 || t < end - 1e-9);
        if (named && run_goes_on) {
          throw EgoError("ego '" + id + "' arrived (its route ended) at t = " + std::to_string(t) +
                         " s while the simulation goes on; give it a route that lasts the run, "
                         "stop the run then with --end, or use --all-vehicles");
        }
      }
      // SUMO reports an overlapping pair at every step (collision.action warn): count events.
      std::set<std::string> now_pairs;
      for (const SumoCollision& c : world->Collisions()) {
        const std::string key = c.collider + "\n" + c.victim;
        now_pairs.insert(key);
        if (active_pairs.count(key)) continue;
        db.AddCollision(CollisionRow{t, c.collider, c.victim, c.collider_type, c.victim_type,
                                     c.type, c.lane, c.collider_speed, c.victim_speed, c.pos});
        ++collisions;
      }
      active_pairs.swap(now_pairs);

      const std::vector<std::string> present = world->VehicleIds();
      std::vector<std::string> current;
      if (o.all_vehicles) {
        current = present;
      } else {
        for (const std::string& e : o.egos) {
          if (std::find(present.begin(), present.end(), e) != present.end()) current.push_back(e);
        }
      }
      for (const std::string& ego : current) {
        seen.insert(ego);
        EgoState& s = egos[ego];
        const Scene scene = world->ExtractScene(ego, cfg);
        const Result r = estimator.Estimate(scene);
        const double p = r.p_collision;
        ++estimates;
        ms_sum += r.times.total_ms;
        ms_max = std::max(ms_max, r.times.total_ms);
        if (!o.record_scenes.empty()) {
          char name[64];
          std::snprintf(name, sizeof name, "t%010.3f_", t);
          const fs::path file = fs::path(o.record_scenes) / (name + ego + ".scene");
          std::ofstream out(file);
          WriteScene(out, scene);
          if (!out) throw ResultsError("cannot write scene file '" + file.string() + "'");
        }
        if (o.act != Act::kNone) {
          if (p >= o.warn_threshold && !s.warning) {
            s.warning = true;
            s.peak = p;
            s.episode = db.OpenWarning(ego, t, p);
            ++warnings;
          } else if (s.warning && p > s.peak) {
            s.peak = p;
            db.UpdateWarningPeak(s.episode, p);
          } else if (s.warning && p < o.warn_release) {
            db.CloseWarning(s.episode, t);
            s.warning = false;
          }
          world->Publish(ego, p, s.warning);
        }
        const double speed = world->Speed(ego);
        if (o.act == Act::kBrake) {
          if (p >= o.brake_threshold) {
            // Follow the best escape route's acceleration when one exists and it slows down;
            // otherwise brake as hard as the vehicle can.
            double accel = -world->EmergencyDecel(ego);
            if (!r.escape_routes.empty())
              accel = std::min(r.escape_routes.front().profile_accel_mps2, 0.0);
            if (accel >= 0.0) accel = -world->EmergencyDecel(ego);
            const double target = std::max(0.0, speed + accel * dt);
            world->CommandSpeed(ego, target);
            if (!s.braking) {
              db.AddAction(t, ego, "brake", accel, speed, p);
              ++actions;
            }
            s.braking = true;
          } else if (s.braking) {
            world->ReleaseSpeed(ego);
            db.AddAction(t, ego, "release", 0.0, speed, p);
            ++actions;
            s.braking = false;
          }
        }
        db.AddStep(t, ego, p, r.times.total_ms, static_cast<int>(r.objects.size()), speed,
                   s.braking);
      }
      db.Commit();
      if (tty) {
        const auto wall = std::chrono::steady_clock::now();
        if (wall - last_print > std::chrono::milliseconds(500)) {
          const double secs = std::chrono::duration<double>(wall - wall0).count();
          std::fprintf(stderr,
                       "\r  t = %.1f s  %.0f steps/s  egos %zu  warnings %lld  collisions %lld   ",
                       t, steps / std::max(secs, 1e-9), current.size(), warnings, collisions);
          last_print = wall;
        }
      }
    }
    if (tty) std::fprintf(stderr, "\n");
    if (g_stop) status = "interrupted";
    if (!o.all_vehicles) {
      for (const std::string& e : o.egos) {
        if (!seen.count(e)) {
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
          << ",\"steps\":" << steps << ",\"egos\":" << seen.size() << ",\"estimates\":" << estimates
          << ",\"warnings\":" << warnings << ",\"actions\":" << actions
          << ",\"collisions\":" << collisions
          << ",\"estimator_ms_mean\":" << (estimates ? ms_sum / estimates : 0.0)
          << ",\"estimator_ms_max\":" << ms_max << ",\"expectation_met\":" << expectation
          << ",\"output\":" << JsonString(db.path()) << "}\n";
}

}  // namespace criticality::plugin
