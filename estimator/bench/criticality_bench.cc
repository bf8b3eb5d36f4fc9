// criticality-bench: runs the estimator on the paper's scenes and reports the time per estimate
// (median and minimum over --repeat runs, after --warmup runs). No SUMO dependency: it must run
// on a bare GPU machine. With --json the last line of standard output is one JSON object.
#include <algorithm>
#include <boost/program_options.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "bench/discrimination_scenes.h"
#include "bench/paper_scenes.h"
#include "bench/whole_option_names.h"
#include "criticality/errors.h"
#include "criticality/estimator.h"
#include "criticality/scene_io.h"

namespace po = boost::program_options;
using namespace criticality;

namespace {

struct Options {
  std::string scene{"S1"};
  std::string scene_file;
  std::string fleet;
  std::string backend{"cpu"};
  int profiles{6};
  int threads{0};
  int repeat{5};
  int warmup{1};
  bool json{false};
  bool report{false};
  bool compare{false};
  bool no_simd{false};
  bool no_skip{false};
  int cos{-1};
  int batch{0};
  std::string preset{"default"};
  std::vector<std::string> experiments;
  bool discrimination{false};
  std::string save_scenes;
  std::string paths_json;
  int paths{12};
};

// Params with the experiments named by --experiment (the driver's options of the same names,
// so that a scene recorded under them replays as it was estimated).
void ApplyExperiments(const std::vector<std::string>& names, Params* p) {
  for (const std::string& name : names) {
    if (name == "way-lateral-paths") {
      p->way_lateral_paths = true;
    } else if (name == "ego-on-way") {
      p->ego_on_way = true;
    } else if (name == "euler-stops") {
      p->euler_stops = true;
    } else {
      throw InputError("--experiment " + name +
                       ": unknown (known: way-lateral-paths, ego-on-way, euler-stops)");
    }
  }
}

// The estimator's options from the command line's, for the named backend.
EstimatorOptions BackendOptions(const Options& opt, const std::string& backend) {
  EstimatorOptions eopt;
  eopt.backend = ParseBackend(backend);
  eopt.threads = opt.threads;
  eopt.simd = !opt.no_simd;
  eopt.skip_out_of_reach = !opt.no_skip;
  return eopt;
}

struct Timing {
  Result last;
  std::vector<double> total, traj, coll, risk;
};

Timing TimeBackend(const Scene& scene, const Params& params, EstimatorOptions eopt, int warmup,
                   int repeat) {
  Estimator estimator(params, eopt);
  Timing t;
  for (int k = 0; k < warmup; ++k) estimator.Estimate(scene);
  for (int k = 0; k < repeat; ++k) {
    t.last = estimator.Estimate(scene);
    t.total.push_back(t.last.times.total_ms);
    t.traj.push_back(t.last.times.trajectory_ms);
    t.coll.push_back(t.last.times.collision_ms);
    t.risk.push_back(t.last.times.risk_ms);
  }
  return t;
}

std::string JsonEscape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out;
}

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string KindName(ObjectKind k) {
  switch (k) {
    case ObjectKind::kEgo:
      return "ego";
    case ObjectKind::kVehicle:
      return "vehicle";
    case ObjectKind::kPedestrian:
      return "pedestrian";
  }
  return "?";
}

std::string LaneName(int lane) {
  switch (lane) {
    case -1:
      return "right lane";
    case 0:
      return "ego lane";
    case 1:
      return "left lane";
  }
  return "no ego lane";
}

void PrintReport(const Scene& scene, const Params& params, const Result& r) {
  std::printf("\nScene: ego '%s' at %.1f m/s with %zu vehicles and %zu pedestrians\n",
              scene.ego.id.c_str(), scene.ego.state.speed_mps, scene.vehicles.size(),
              scene.pedestrians.size());
  std::printf("Collision probability p_cra = %.4f (%.1f %%)\n", r.p_collision,
              100.0 * r.p_collision);
  std::printf("\nContribution per object (shares of p_cra):\n");
  for (const ObjectResult& o : r.objects) {
    std::printf("  %-14s %-10s %-16s %4d hypotheses  %.4f\n", o.id.c_str(),
                KindName(o.kind).c_str(), LaneName(o.lane).c_str(), o.trajectories, o.contribution);
  }
  // First-collision time: where the mass lies.
  double cum = 0.0, t_first = -1.0, t_median = -1.0;
  for (size_t n = 0; n < r.first_collision_pmf.size(); ++n) {
    const double t = (n + 1) * params.step_s;
    if (t_first < 0.0 && r.first_collision_pmf[n] > 0.0) t_first = t;
    cum += r.first_collision_pmf[n];
    if (t_median < 0.0 && r.p_collision > 0.0 && cum >= 0.5 * r.p_collision) t_median = t;
  }
  if (t_first >= 0.0) {
    std::printf("\nFirst collision: earliest possible at %.2f s, half of p_cra by %.2f s\n",
                t_first, t_median);
    std::printf("  p(first collision by t):");
    cum = 0.0;
    size_t next = 0;
    const double marks[] = {0.5, 1.0, 1.5, 2.0};
    for (size_t n = 0; n < r.first_collision_pmf.size(); ++n) {
      cum += r.first_collision_pmf[n];
      const double t = (n + 1) * params.step_s;
      while (next < 4 && t >= marks[next] - 1e-9) {
        std::printf("  %.1fs: %.4f", marks[next], cum);
        ++next;
      }
    }
    std::printf("\n");
  } else {
    std::printf("\nNo hypothesis combination collides within %.1f s.\n", params.horizon_s);
  }
  std::printf(
      "\nIf the ego keeps its reference (hypothesis %d): p = %.4f; unavoidability (the "
      "least colliding ego hypothesis) = %.4f\n",
      r.reference_ego_trajectory, r.p_reference, r.unavoidability);
  std::printf(
      "\nEscape routes: %d of %d ego hypotheses are collision-free. Least colliding, then "
      "most probable:\n",
      r.collision_free_ego_trajectories, r.counts.ego_trajectories);
  const size_t show = std::min<size_t>(5, r.escape_routes.size());
  for (size_t k = 0; k < show; ++k) {
    const EscapeRoute& e = r.escape_routes[k];
    std::ostringstream lanes;
    for (size_t s = 0; s < e.target_lanes.size(); ++s) {
      lanes << (s ? "," : "")
            << (e.target_lanes[s] < 0   ? "right"
                : e.target_lanes[s] > 0 ? "left"
                                        : "own");
    }
    double max_steer = 0.0, max_lat = 0.0;
    for (size_t n = 0; n < e.steer_rad.size(); ++n) {
      max_steer = std::max(max_steer, std::fabs(e.steer_rad[n]));
      max_lat = std::max(max_lat, std::fabs(e.lateral_accel_mps2[n]));
    }
    std::printf(
        "  #%zu  hypothesis %4d  p_collision %.4f  p = %.5f  accel %+.1f m/s^2 (slip %+.3f)  lanes "
        "[%s]\n      after %.1f s: speed %.1f m/s, offset %+.2f m from the own-lane centre; max "
        "steer %.3f rad, max lateral accel %.1f m/s^2\n",
        k + 1, e.ego_trajectory, e.collision_probability, e.probability, e.profile_accel_mps2,
        e.profile_slip, lanes.str().c_str(), e.time_s.empty() ? 0.0 : e.time_s.back(),
        e.speed_mps.empty() ? 0.0 : e.speed_mps.back(),
        e.lateral_offset_m.empty() ? 0.0 : e.lateral_offset_m.back(), max_steer, max_lat);
  }
}

// The discrimination benchmark: every designed scene, its label and the outputs.
int Discrimination(const Params& params, const Options& opt) {
  const std::vector<bench::DiscriminationScene> scenes = bench::DiscriminationScenes();
  if (!opt.save_scenes.empty()) {
    std::filesystem::create_directories(opt.save_scenes);
    for (const bench::DiscriminationScene& d : scenes) {
      const std::string file = opt.save_scenes + "/" + d.name + ".scene";
      std::ofstream out(file);
      WriteScene(out, d.scene);
      if (!out) throw InputError("--save-scenes: cannot write '" + file + "'");
    }
  }
  EstimatorOptions eopt = BackendOptions(opt, opt.backend);
  Estimator estimator(params, eopt);
  std::printf("discrimination benchmark, preset %s, backend %s\n", opt.preset.c_str(),
              BackendName(estimator.options().backend).c_str());
  std::printf("%-38s %-10s %6s %9s %11s %14s %12s  %s\n", "scene", "label", "TTC s", "p_cra",
              "p_reference", "unavoidability", "best escape", "best route (accel, lanes)");
  std::string json = "{\"preset\":\"" + JsonEscape(opt.preset) + "\",\"scenes\":[";
  double safe_max = 0.0, critical_min = 1.0;
  for (size_t k = 0; k < scenes.size(); ++k) {
    const bench::DiscriminationScene& d = scenes[k];
    const Result r = estimator.Estimate(d.scene);
    const EscapeRoute* best = r.escape_routes.empty() ? nullptr : &r.escape_routes.front();
    std::ostringstream route;
    if (best) {
      route << std::showpos << std::fixed << std::setprecision(1) << best->profile_accel_mps2
            << std::noshowpos << " m/s^2, ";
      for (size_t s = 0; s < best->target_lanes.size(); ++s) {
        route << (s ? "," : "")
              << (best->target_lanes[s] < 0   ? "R"
                  : best->target_lanes[s] > 0 ? "L"
                                              : "O");
      }
    }
    char ttc[16] = "-";
    if (d.ttc_s > 0.0) std::snprintf(ttc, sizeof ttc, "%.2f", d.ttc_s);
    std::printf("%-38s %-10s %6s %9.4f %11.4f %14.4f %12.4f  %s\n", d.name.c_str(),
                d.critical ? "critical" : "safe-close", ttc, r.p_collision, r.p_reference,
                r.unavoidability, best ? best->collision_probability : 1.0, route.str().c_str());
    if (d.critical && d.ttc_s <= 1.5) critical_min = std::min(critical_min, r.p_collision);
    if (!d.critical) safe_max = std::max(safe_max, r.p_collision);
    char item[512];
    std::snprintf(item, sizeof item,
                  "%s{\"name\":\"%s\",\"critical\":%s,\"ttc_s\":%.3f,\"p_collision\":%.17g,"
                  "\"p_reference\":%.17g,\"unavoidability\":%.17g,\"best_escape\":%.17g}",
                  k ? "," : "", JsonEscape(d.name).c_str(), d.critical ? "true" : "false", d.ttc_s,
                  r.p_collision, r.p_reference, r.unavoidability,
                  best ? best->collision_probability : 1.0);
    json += item;
  }
  std::printf(
      "highest safe-close p_cra %.4f, lowest critical (TTC <= 1.5 s) p_cra %.4f, margin "
      "%.4f\n",
      safe_max, critical_min, critical_min - safe_max);
  json += "]}";
  if (opt.json) std::printf("%s\n", json.c_str());
  return 0;
}

// A fleet of egos in one call: copies of the scene with the ego's speed spread over +-20 %.
int Batch(const Scene& scene, const Params& params, const Options& opt) {
  std::vector<Scene> scenes(opt.batch, scene);
  for (int k = 0; k < opt.batch; ++k) {
    scenes[k].ego.state.speed_mps *= 0.8 + 0.4 * (k % 101) / 100.0;
  }
  EstimatorOptions eopt = BackendOptions(opt, opt.backend);
  Estimator estimator(params, eopt);
  for (int k = 0; k < opt.warmup; ++k) estimator.EstimateBatch(scenes);
  std::vector<double> ms;
  double p_sum = 0.0;
  for (int k = 0; k < opt.repeat; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<Result> results = estimator.EstimateBatch(scenes);
    ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    p_sum = 0.0;
    for (const Result& r : results) p_sum += r.p_collision;
  }
  const double median = Median(ms);
  std::printf(
      "batch of %d %s-size egos, backend %s (%d threads): median %.3f ms per batch, "
      "%.1f egos/s, mean p_collision %.6f\n",
      opt.batch, opt.scene.c_str(), BackendName(estimator.options().backend).c_str(),
      estimator.threads(), median, opt.batch / (median * 1e-3), p_sum / opt.batch);
  if (opt.json) {
    std::printf(
        "{\"scene\":\"%s\",\"backend\":\"%s\",\"batch\":%d,\"median_ms\":%.6f,"
        "\"egos_per_s\":%.3f,\"mean_p_collision\":%.17g}\n",
        JsonEscape(opt.scene).c_str(), BackendName(estimator.options().backend).c_str(), opt.batch,
        median, opt.batch / (median * 1e-3), p_sum / opt.batch);
  }
  return 0;
}

// --fleet DIR: every scene file in DIR (one recorded SUMO step of a whole fleet, each ego's
// scene) estimated in one EstimateBatch call, on the cpu fast path and, when usable, on cuda in
// the same process: the time per batch, egos per second and how far each backend's p_cra is
// from the cpu's, scene by scene.
std::vector<Scene> ReadFleet(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw InputError("--fleet '" + dir + "': not a folder (give a folder of .scene files, e.g. "
                     "one step written by sumo-criticality --record-scenes)");
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() == ".scene") files.push_back(entry.path().string());
  }
  if (files.empty()) throw InputError("--fleet '" + dir + "': holds no .scene file");
  std::sort(files.begin(), files.end());
  std::vector<Scene> scenes;
  scenes.reserve(files.size());
  for (const std::string& f : files) scenes.push_back(ReadSceneFile(f));
  return scenes;
}

int Fleet(const Params& params, const Options& opt) {
  const std::vector<Scene> scenes = ReadFleet(opt.fleet);
  // cpu-unshared: each scene simulates its own other road users (no ObjectPathsCache), the
  // cost the batch's sharing saves; it must agree with cpu exactly.
  std::vector<std::string> names{"cpu", "cpu-unshared"};
  if (CudaUsable(nullptr)) names.push_back("cuda");
  std::printf("fleet %s: %zu egos in one batch, %d profiles\n", opt.fleet.c_str(), scenes.size(),
              opt.profiles);
  std::printf("%-12s %7s %12s %12s %12s %14s  %s\n", "backend", "threads", "median ms", "min ms",
              "egos/s", "x cpu", "agreement with cpu");
  std::vector<Result> cpu_results;
  double cpu_median = 0.0;
  std::string json = "{\"fleet\":\"" + JsonEscape(opt.fleet) + "\",\"egos\":" +
                     std::to_string(scenes.size()) + ",\"backends\":[";
  for (size_t k = 0; k < names.size(); ++k) {
    const bool unshared = names[k] == "cpu-unshared";
    EstimatorOptions eopt = BackendOptions(opt, unshared ? "cpu" : names[k]);
    if (unshared) eopt.shared_object_paths_mib = 0;
    Estimator estimator(params, eopt);
    for (int w = 0; w < opt.warmup; ++w) estimator.EstimateBatch(scenes);
    std::vector<double> ms;
    std::vector<Result> results;
    for (int r = 0; r < opt.repeat; ++r) {
      const auto t0 = std::chrono::steady_clock::now();
      results = estimator.EstimateBatch(scenes);
      ms.push_back(
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    }
    const double median = Median(ms);
    const double min = *std::min_element(ms.begin(), ms.end());
    if (k == 0) {
      cpu_results = results;
      cpu_median = median;
    }
    double max_dp = 0.0, p_sum = 0.0;
    size_t beyond = 0;  // scenes whose p_cra differs from the cpu's by more than 1e-6
    for (size_t q = 0; q < results.size(); ++q) {
      const double dp = std::fabs(results[q].p_collision - cpu_results[q].p_collision);
      max_dp = std::max(max_dp, dp);
      beyond += dp > 1e-6;
      p_sum += results[q].p_collision;
    }
    const double egos_per_s = scenes.size() / (median * 1e-3);
    char agree[160];
    std::snprintf(agree, sizeof agree, "max |dp_cra| = %.1e, %zu of %zu scenes beyond 1e-6",
                  max_dp, beyond, results.size());
    std::printf("%-12s %7d %12.3f %12.3f %12.1f %14.2f  %s\n", names[k].c_str(),
                estimator.threads(), median, min, egos_per_s, cpu_median / median, agree);
    double street = 0.0, traj = 0.0, coll = 0.0, risk = 0.0;  // the last batch's, over its egos
    for (const Result& r : results) {
      street += r.times.street_ms;
      traj += r.times.trajectory_ms;
      coll += r.times.collision_ms;
      risk += r.times.risk_ms;
    }
    std::printf("       stages of the last batch, summed over egos: street data %.3f, trajectories "
                "%.3f, collisions %.3f, risk %.3f ms\n",
                street, traj, coll, risk);
    char item[400];
    std::snprintf(item, sizeof item,
                  "%s{\"backend\":\"%s\",\"threads\":%d,\"median_ms\":%.6f,\"min_ms\":%.6f,"
                  "\"egos_per_s\":%.3f,\"speedup_vs_cpu\":%.3f,\"max_dp_vs_cpu\":%.3g,"
                  "\"scenes_beyond_1e-6\":%zu,\"mean_p_collision\":%.17g}",
                  k ? "," : "", names[k].c_str(), estimator.threads(), median, min, egos_per_s,
                  cpu_median / median, max_dp, beyond, p_sum / results.size());
    json += item;
  }
  json += "]}";
  if (opt.json) std::printf("%s\n", json.c_str());
  return 0;
}

// Every backend on the same scene, one after the other in this process.
int Compare(const Scene& scene, const Params& params, const Options& opt) {
  // The cpu fast path twice: scalar (bit for bit the reference's pair matrix) and with SIMD.
  std::vector<Backend> backends{Backend::kReference, Backend::kCpu, Backend::kCpu, Backend::kCpu};
  std::vector<std::string> names{"reference", "cpu-scalar", "cpu-noskip", "cpu"};
  if (CudaUsable(nullptr)) {
    backends.push_back(Backend::kCuda);
    names.push_back("cuda");
  }
  std::vector<Timing> runs;
  std::vector<int> threads;
  for (size_t k = 0; k < backends.size(); ++k) {
    const Backend b = backends[k];
    EstimatorOptions eopt;
    eopt.backend = b;
    eopt.threads = opt.threads;
    eopt.simd = names[k] != "cpu-scalar";
    eopt.skip_out_of_reach = names[k] != "cpu-noskip";
    eopt.keep_pair_matrix = true;
    // The reference is slow: fewer repetitions keep --compare usable on S2.
    const int repeat = b == Backend::kReference ? std::max(1, std::min(opt.repeat, 3)) : opt.repeat;
    runs.push_back(
        TimeBackend(scene, params, eopt, b == Backend::kReference ? 0 : opt.warmup, repeat));
    threads.push_back(b == Backend::kReference ? 1 : Estimator(params, eopt).threads());
  }
  const Result& ref = runs[0].last;
  const WorkCounts& c = ref.counts;
  std::printf(
      "scene %s, %d profiles: %d ego x %d CO trajectories x %d steps = %llu pose combinations\n",
      opt.scene.c_str(), opt.profiles, c.ego_trajectories, c.co_trajectories, c.time_steps,
      static_cast<unsigned long long>(c.pose_combinations));
  std::printf("%-10s %7s %10s %10s %14s %9s  %s\n", "backend", "threads", "median ms", "min ms",
              "poses/s", "x ref", "agreement with the reference");
  const double ref_median = Median(runs[0].total);
  std::string json =
      "{\"scene\":\"" + JsonEscape(opt.scene) + "\",\"profiles\":" + std::to_string(opt.profiles) +
      ",\"pose_combinations\":" + std::to_string(c.pose_combinations) + ",\"backends\":[";
  for (size_t k = 0; k < backends.size(); ++k) {
    const Result& r = runs[k].last;
    const double median = Median(runs[k].total);
    const double min = *std::min_element(runs[k].total.begin(), runs[k].total.end());
    size_t differing = 0;
    for (size_t q = 0; q < r.first_collision_step.size(); ++q) {
      differing += r.first_collision_step[q] != ref.first_collision_step[q];
    }
    const double dp = std::fabs(r.p_collision - ref.p_collision);
    char agree[160];
    std::snprintf(agree, sizeof agree, "%zu of %zu pairs differ, |dp_cra| = %.1e", differing,
                  r.first_collision_step.size(), dp);
    std::printf("%-10s %7d %10.3f %10.3f %14.3e %9.1f  %s\n", names[k].c_str(),
                threads[k], median, min, c.pose_combinations / (median * 1e-3), ref_median / median,
                agree);
    char item[400];
    std::snprintf(item, sizeof item,
                  "%s{\"backend\":\"%s\",\"threads\":%d,\"median_ms\":%.6f,\"min_ms\":%.6f,"
                  "\"speedup_vs_reference\":%.3f,\"differing_pairs\":%zu,\"p_collision\":%.17g}",
                  k ? "," : "", names[k].c_str(), threads[k], median, min,
                  ref_median / median, differing, r.p_collision);
    json += item;
  }
  json += "]}";
  if (opt.json) std::printf("%s\n", json.c_str());
  return 0;
}

// One ego hypothesis as JSON: its probabilities and its poses (scene frame, cm).
std::string HypothesisJson(const EscapeRoute& e, bool reference) {
  std::ostringstream o;
  o << std::setprecision(6) << "{\"trajectory\":" << e.ego_trajectory
    << ",\"probability\":" << e.probability
    << ",\"collision_probability\":" << e.collision_probability
    << ",\"reference\":" << (reference ? "true" : "false") << ",\"x\":[";
  o << std::fixed << std::setprecision(2);
  for (size_t n = 0; n < e.x_m.size(); ++n) o << (n ? "," : "") << e.x_m[n];
  o << "],\"y\":[";
  for (size_t n = 0; n < e.y_m.size(); ++n) o << (n ? "," : "") << e.y_m[n];
  o << "],\"yaw\":[" << std::setprecision(3);
  for (size_t n = 0; n < e.yaw_rad.size(); ++n) o << (n ? "," : "") << e.yaw_rad[n];
  o << "]}";
  return o.str();
}

// --paths-json: one estimate, then the ego's most probable hypotheses and its most probable
// colliding ones with their poses, the objects' shares and the first-collision times, for a
// picture of the scene (the campaign report's warning scenes).
int Paths(const Scene& scene, Params params, const Options& opt) {
  params.max_escape_routes = 1 << 30;  // every ego hypothesis, re-simulated with its poses
  EstimatorOptions eopt = BackendOptions(opt, opt.backend);
  Estimator estimator(params, eopt);
  const Result r = estimator.Estimate(scene);
  std::vector<const EscapeRoute*> probable, colliding;
  for (const EscapeRoute& e : r.escape_routes) {
    probable.push_back(&e);
    if (e.collision_probability > 0.0) colliding.push_back(&e);
  }
  const size_t n = static_cast<size_t>(std::max(0, opt.paths));
  auto keep = [n](std::vector<const EscapeRoute*>& v, auto weight) {
    std::stable_sort(v.begin(), v.end(), [&](const EscapeRoute* a, const EscapeRoute* b) {
      return weight(*a) > weight(*b);
    });
    if (v.size() > n) v.resize(n);
  };
  keep(probable, [](const EscapeRoute& e) { return e.probability; });
  keep(colliding, [](const EscapeRoute& e) { return e.probability * e.collision_probability; });
  std::ostringstream o;
  o << std::setprecision(8) << "{\"ego\":\"" << JsonEscape(scene.ego.id)
    << "\",\"p_collision\":" << r.p_collision << ",\"p_reference\":" << r.p_reference
    << ",\"unavoidability\":" << r.unavoidability << ",\"step_s\":" << params.step_s
    << ",\"horizon_s\":" << params.horizon_s << ",\"hypotheses\":" << r.counts.ego_trajectories
    << ",\"objects\":[";
  for (size_t k = 0; k < r.objects.size(); ++k) {
    const ObjectResult& ob = r.objects[k];
    o << (k ? "," : "") << "{\"id\":\"" << JsonEscape(ob.id) << "\",\"kind\":\""
      << KindName(ob.kind) << "\",\"contribution\":" << ob.contribution
      << ",\"out_of_reach\":" << (ob.out_of_reach ? "true" : "false") << "}";
  }
  o << "],\"first_collision_pmf\":[";
  for (size_t k = 0; k < r.first_collision_pmf.size(); ++k)
    o << (k ? "," : "") << r.first_collision_pmf[k];
  for (const auto& [name, list] :
       {std::pair<const char*, std::vector<const EscapeRoute*>*>{"most_probable", &probable},
        {"colliding", &colliding}}) {
    o << "],\"" << name << "\":[";
    for (size_t k = 0; k < list->size(); ++k) {
      const EscapeRoute& e = *(*list)[k];
      o << (k ? "," : "") << HypothesisJson(e, e.ego_trajectory == r.reference_ego_trajectory);
    }
  }
  o << "]}\n";
  std::ofstream out(opt.paths_json);
  out << o.str();
  if (!out) throw InputError("--paths-json '" + opt.paths_json + "': cannot be written");
  std::printf(
      "paths of %s: p_collision %.4f, %zu most probable and %zu colliding hypotheses -> %s\n",
      scene.ego.id.c_str(), r.p_collision, probable.size(), colliding.size(),
      opt.paths_json.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  po::options_description desc(
      "criticality-bench: time the multi-hypothesis criticality estimator on the paper's scenes\n"
      "(S1 = ego + 3 other vehicles, S2 = ego + 10, straight 3-lane road, 2 s horizon, 20 ms\n"
      "steps, 343 ego paths, 7 paths per other vehicle).\n\nOptions");
  desc.add_options()("help,h", "show this help and exit")(
      "scene", po::value(&opt.scene)->default_value(opt.scene), "S1 or S2")(
      "scene-file", po::value(&opt.scene_file),
      "replay a scene file instead (written by sumo-criticality --record-scenes)")(
      "fleet", po::value(&opt.fleet),
      "estimate every .scene file in this folder as one batch (a recorded fleet step, e.g. "
      "bench/fleet_step), on cpu, cpu-unshared (each scene simulates its own other road users) "
      "and, when usable, cuda in this process: ms per batch, egos/s, |dp_cra| against cpu")(
      "profiles", po::value(&opt.profiles)->default_value(opt.profiles),
      "acceleration/slip profiles per object (paper: 6 or 5)")(
      "backend", po::value(&opt.backend)->default_value(opt.backend),
      "reference (plain literal algorithm, one thread), cpu (fast path), cuda (GPU) or auto (cuda "
      "when usable, else cpu)")("threads", po::value(&opt.threads)->default_value(opt.threads),
                                "worker threads for the cpu backend (0 = all hardware threads)")(
      "repeat", po::value(&opt.repeat)->default_value(opt.repeat), "timed estimates")(
      "warmup", po::value(&opt.warmup)->default_value(opt.warmup), "untimed estimates first")(
      "json", po::bool_switch(&opt.json), "print one JSON object as the last line of stdout")(
      "no-simd", po::bool_switch(&opt.no_simd),
      "cpu backend: the scalar fast path (bit for bit the reference's pair matrix) instead of "
      "sibling ego paths in SIMD lanes (within 3 ulp per sin/cos/atan; grazing contacts may "
      "differ)")(
      "no-skip", po::bool_switch(&opt.no_skip),
      "cpu backend: simulate every ego path, also the subtrees whose reach meets no object "
      "(the same result; for comparing the cost)")(
      "compare", po::bool_switch(&opt.compare),
      "run every available backend (reference, cpu-scalar, cpu-noskip, cpu, cuda) on the same "
      "scene in this process and "
      "print a table: times, pose combinations per second, ratio to the reference, agreement")(
      "cos", po::value(&opt.cos),
      "instead of --scene: the scaling scene with this many other vehicles (e.g. 1 3 10 30 100)")(
      "batch", po::value(&opt.batch),
      "estimate a batch of this many scenes in one call (Estimator::EstimateBatch): copies of the "
      "scene with the ego's speed varied, as a fleet of egos; reports egos per second")(
      "report", po::bool_switch(&opt.report),
      "print a readable summary of the result (per-object shares, collision times, p_reference, "
      "unavoidability, escape routes)")(
      "preset", po::value(&opt.preset)->default_value(opt.preset),
      "parameter set: default (drivable hypotheses, naturalistic scoring) or paper-literal (the "
      "first implementation, for comparison)")(
      "experiment", po::value(&opt.experiments)->composing(),
      "turn on an experiment that is off by default, as the driver's option of the same name "
      "(repeatable): way-lateral-paths, ego-on-way, euler-stops (replay a scene recorded with it)")(
      "discrimination", po::bool_switch(&opt.discrimination),
      "run the discrimination benchmark: designed scenes labelled safe-close or critical, with "
      "p_cra, p_reference, unavoidability and the best escape route of each")(
      "save-scenes", po::value(&opt.save_scenes),
      "with --discrimination: also write every scene as a scene file into this folder")(
      "paths-json", po::value(&opt.paths_json),
      "estimate once and write to FILE (JSON) the ego's most probable hypotheses and its most "
      "probable colliding ones with their poses (scene frame), the objects' shares and the "
      "first-collision time distribution (for pictures of a scene; no timing)")(
      "paths", po::value(&opt.paths)->default_value(opt.paths),
      "with --paths-json: hypotheses of each kind");
  try {
    po::variables_map vm;
    criticality::bench::StoreWholeNames(argc, argv, desc, &vm);
    if (vm.count("help")) {
      std::cout << desc
                << "\nExample: criticality-bench --scene S2 --backend reference --repeat 3\n";
      return 0;
    }
    po::notify(vm);
    if (opt.repeat < 1)
      throw InputError("--repeat = " + std::to_string(opt.repeat) + ": must be >= 1");
    if (opt.warmup < 0)
      throw InputError("--warmup = " + std::to_string(opt.warmup) + ": must be >= 0");

    Params params = ParamsPreset(opt.preset);
    params.profiles = opt.profiles;
    ApplyExperiments(opt.experiments, &params);
    if (opt.discrimination) return Discrimination(params, opt);
    if (!opt.fleet.empty()) return Fleet(params, opt);
    EstimatorOptions eopt = BackendOptions(opt, opt.backend);
    if (opt.cos > 100000)
      throw InputError("--cos = " + std::to_string(opt.cos) + ": at most 100000");
    Scene scene;
    if (!opt.scene_file.empty()) {
      scene = ReadSceneFile(opt.scene_file);
      opt.scene = opt.scene_file;
    } else if (opt.cos >= 0) {
      scene = bench::ScalingScene(opt.cos);
      opt.scene = "cos" + std::to_string(opt.cos);
    } else {
      scene = bench::PaperScene(opt.scene);
    }
    if (!opt.paths_json.empty()) return Paths(scene, params, opt);
    if (opt.compare) return Compare(scene, params, opt);
    if (opt.batch < 0 || opt.batch > 1000000)
      throw InputError("--batch = " + std::to_string(opt.batch) + ": use 1 to 1000000");
    if (opt.batch > 0) return Batch(scene, params, opt);
    Estimator estimator(params, eopt);

    for (int k = 0; k < opt.warmup; ++k) estimator.Estimate(scene);
    std::vector<double> total, traj, coll, risk;
    Result last;
    for (int k = 0; k < opt.repeat; ++k) {
      last = estimator.Estimate(scene);
      total.push_back(last.times.total_ms);
      traj.push_back(last.times.trajectory_ms);
      coll.push_back(last.times.collision_ms);
      risk.push_back(last.times.risk_ms);
    }
    const double median = Median(total);
    const double min = *std::min_element(total.begin(), total.end());
    const WorkCounts& c = last.counts;
    std::printf("scene %s, backend %s (%d threads), %d profiles\n", opt.scene.c_str(),
                opt.backend.c_str(), estimator.threads(), opt.profiles);
    std::printf("  trajectories: %d ego, %d CO; %d steps; %llu pose combinations\n",
                c.ego_trajectories, c.co_trajectories, c.time_steps,
                static_cast<unsigned long long>(c.pose_combinations));
    std::printf("  p_collision %.6f\n", last.p_collision);
    std::printf(
        "  time per estimate over %d runs: median %.3f ms, min %.3f ms "
        "(median trajectories %.3f, collisions %.3f, risk %.3f ms)\n",
        opt.repeat, median, min, Median(traj), Median(coll), Median(risk));
    if (opt.report) PrintReport(scene, params, last);
    if (opt.json) {
      std::printf(
          "{\"scene\":\"%s\",\"backend\":\"%s\",\"threads\":%d,\"profiles\":%d,"
          "\"pose_combinations\":%llu,\"ego_trajectories\":%d,\"co_trajectories\":%d,"
          "\"time_steps\":%d,\"p_collision\":%.17g,\"median_ms\":%.6f,\"min_ms\":%.6f,"
          "\"median_trajectory_ms\":%.6f,\"median_collision_ms\":%.6f,\"median_risk_ms\":%.6f,"
          "\"repeat\":%d}\n",
          JsonEscape(opt.scene).c_str(), opt.backend.c_str(), estimator.threads(), opt.profiles,
          static_cast<unsigned long long>(c.pose_combinations), c.ego_trajectories,
          c.co_trajectories, c.time_steps, last.p_collision, median, min, Median(traj),
          Median(coll), Median(risk), opt.repeat);
    }
    return 0;
  } catch (const po::error& e) {
    std::cerr << "criticality-bench: error: " << e.what() << " (see --help)\n";
    return 2;
  } catch (const InputError& e) {
    std::cerr << "criticality-bench: error: " << e.what() << "\n";
    return 2;
  } catch (const WorkloadError& e) {
    std::cerr << "criticality-bench: error: " << e.what() << "\n";
    return 3;
  } catch (const std::exception& e) {
    std::cerr << "criticality-bench: internal error: " << e.what() << "\n";
    return 1;
  }
}
