#include "criticality/estimator.h"

#include <chrono>
#include <cmath>
#include <exception>

#include "cpu/cpu_backend.h"
#include "cpu/object_paths_cache.h"
#include "cpu/reference_backend.h"
#include "cpu/scene_pool.h"
#include "criticality/errors.h"
#include "src/backend.h"
#include "src/parallel_for.h"
#include "src/problem.h"
#include "src/reach_filter.h"
#include "src/risk_assessment.h"
#include "src/street_data.h"

#ifdef CRIT_WITH_CUDA
#include "cuda/cuda_backend.h"
#include "cuda/device.cuh"
#endif

#include <cstdio>

namespace criticality {
namespace {

double MsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// The reach shortcut's hook: applied to a built problem, it returns the problem to run (the
// same when nothing is out of reach) and, after the run, puts the dropped objects back into
// the result's list.
struct ReachShortcut {
  std::vector<char> drop;
  bool any{false};
  bool none_left{false};

  internal::Problem Apply(const internal::Problem& pb, bool simd,
                          internal::ObjectPathsCache* cache) {
    drop = internal::OutOfReach(pb, simd, cache);
    for (char d : drop) any = any || d;
    internal::Problem kept = any ? internal::WithoutObjects(pb, drop) : pb;
    none_left = kept.cos.empty();
    return kept;
  }
  // Answers a problem with no object left as the risk assessment of an empty pair matrix
  // does, after the backend generated every ego trajectory: nothing collides, every ego
  // hypothesis is an escape route candidate (tests/estimator/reach_filter_test.cc compares
  // every field with the full estimate).
  static void Answer(const internal::Problem& kept, const Params& params, Result* result) {
    const int n_ego = kept.EgoTrajectories();  // no object left, so no carriage either
    result->p_collision = 0.0;
    result->first_collision_pmf.assign(kept.Steps(), 0.0);
    result->objects = kept.objects;
    result->ego_probability = kept.ego_probability;
    result->ego_collision_probability.assign(n_ego, 0.0);
    internal::FinishDecisionOutputs(kept, params, std::vector<char>(n_ego, 0), result);
  }
  void Restore(const internal::Problem& pb, Result* result) const {
    if (!any) return;
    std::vector<ObjectResult> all;
    size_t next = 0;
    int offset = 0;
    for (size_t o = 0; o < pb.objects.size(); ++o) {
      if (drop[o]) {
        ObjectResult r = pb.objects[o];
        r.contribution = 0.0;
        r.out_of_reach = true;
        r.first_trajectory = offset;
        r.trajectories = 0;
        all.push_back(r);
      } else {
        all.push_back(result->objects[next++]);
        offset = all.back().first_trajectory + all.back().trajectories;
      }
    }
    result->objects = std::move(all);
  }
};

// True when one estimate with `params` is too small to split over threads: below ~50,000 ego
// hypothesis steps (all three lanes) it takes well under a millisecond on one thread, and
// waking threads for it costs more than it saves.
bool TooSmallToSplit(const Params& p) {
  double ego_steps = p.profiles * static_cast<double>(p.TimeSteps());
  for (size_t k = 0; k < p.path_sample_times_s.size(); ++k)
    ego_steps *= p.LateralSamplesThreeLanes();
  return ego_steps < 5e4;
}

}  // namespace

Backend ParseBackend(const std::string& name) {
  if (name == "reference") return Backend::kReference;
  if (name == "cpu") return Backend::kCpu;
  if (name == "cuda") return Backend::kCuda;
  if (name == "auto") return Backend::kAuto;
  throw InputError("backend = '" + name + "': unknown; use reference, cpu, cuda or auto");
}

std::string BackendName(Backend backend) {
  switch (backend) {
    case Backend::kReference:
      return "reference";
    case Backend::kCpu:
      return "cpu";
    case Backend::kCuda:
      return "cuda";
    case Backend::kAuto:
      return "auto";
  }
  return "unknown";
}

double LaneFrameAngle(const LaneSet& lanes, const Params& params) {
  return internal::LaneFrameAngle(lanes, params);
}

std::string LaneProblem(const Lane& lane, double frame_rad) {
  try {
    internal::FitLanes(LaneSet{lane, std::nullopt, std::nullopt}, "lane", frame_rad, false, true);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

double LaneCentreDeviation(const Lane& lane, double frame_rad, const std::vector<Point2>& centre) {
  const internal::FittedLanes f =
      internal::FitLanes(LaneSet{lane, std::nullopt, std::nullopt}, "lane", frame_rad, false, true);
  const core::Parabola mid = f.own->Centre();
  double x_min = HUGE_VAL, x_max = -HUGE_VAL;
  for (const LaneDivider* d : {&lane.left, &lane.right}) {
    for (const Point2& p : d->points) {
      double xr = 0.0, yr = 0.0;
      mid.ToFrame(p.x, p.y, &xr, &yr);
      x_min = std::fmin(x_min, xr);
      x_max = std::fmax(x_max, xr);
    }
  }
  double worst = 0.0;
  for (const Point2& p : centre) {
    double xr = 0.0, yr = 0.0;
    mid.ToFrame(p.x, p.y, &xr, &yr);
    if (xr < x_min || xr > x_max) continue;
    const double slope = mid.Slope(xr);  // the gap along y, taken across the curve
    worst = std::fmax(worst, std::fabs(mid.Eval(xr) - yr) / std::sqrt(1.0 + slope * slope));
  }
  return worst;
}

bool CudaUsable(std::string* why) {
#ifdef CRIT_WITH_CUDA
  return cuda::DeviceAvailable(why);
#else
  if (why) *why = "this build has no CUDA (nvcc was not found when it was configured)";
  return false;
#endif
}

void EstimatorBackend::Run(const internal::Problem& problem, const Params& params,
                           bool keep_pair_matrix, Result* result) {
  auto t = std::chrono::steady_clock::now();
  GenerateTrajectories(problem);
  result->times.trajectory_ms = MsSince(t);
  t = std::chrono::steady_clock::now();
  std::vector<std::int16_t> first_step;
  RecognizeCollisions(problem, &first_step);
  result->times.collision_ms = MsSince(t);
  t = std::chrono::steady_clock::now();
  internal::AssessBodies(problem, params, &first_step, Threads(), result);
  result->times.risk_ms = MsSince(t);
  internal::CallersPool().Rest();  // no helper spins while the caller is elsewhere
  if (keep_pair_matrix) result->first_collision_step = std::move(first_step);
}

Estimator::Estimator(const Params& params, const EstimatorOptions& options)
    : params_(params), options_(options) {
  ValidateParams(params_);
  if (options_.threads < 0) {
    throw InputError("options.threads = " + std::to_string(options_.threads) +
                     ": must be >= 0 (0 = all hardware threads)");
  }
  if (options_.shared_object_paths_mib < 0) {
    throw InputError(
        "options.shared_object_paths_mib = " + std::to_string(options_.shared_object_paths_mib) +
        ": must be >= 0 (0 = every scene of a batch simulates its own objects)");
  }
  std::string why;
  if (options_.backend == Backend::kAuto) {
    if (CudaUsable(&why)) {
      options_.backend = Backend::kCuda;
    } else {
      std::fprintf(stderr, "criticality: backend auto: %s; using the cpu backend\n", why.c_str());
      options_.backend = Backend::kCpu;
    }
  }
  switch (options_.backend) {
    case Backend::kReference:
      backend_ = std::make_unique<ReferenceBackend>();
      break;
    case Backend::kCpu:
    case Backend::kAuto:
      backend_ =
          std::make_unique<CpuBackend>(options_.threads, options_.simd, options_.skip_out_of_reach);
      if (options_.shared_object_paths_mib > 0) {
        paths_cache_ = std::make_unique<internal::ObjectPathsCache>(
            static_cast<size_t>(options_.shared_object_paths_mib) << 20);
      }
      break;
    case Backend::kCuda:
      if (!CudaUsable(&why)) {
        throw InputError("backend cuda: " + why + "; use --backend cpu or auto");
      }
#ifdef CRIT_WITH_CUDA
      backend_ = cuda::MakeCudaBackend(internal::ResolveThreads(options_.threads));
#endif
      break;
  }
}

Estimator::~Estimator() = default;

int Estimator::threads() const { return backend_->Threads(); }

void Estimator::SharePaths(internal::ObjectPathsCache* cache) {
  batch_paths_ = cache;
  backend_->ShareObjectPaths(cache);
}

Result Estimator::Estimate(const Scene& scene) {
  const auto t0 = std::chrono::steady_clock::now();
  Result result;
  const internal::Problem built = internal::BuildProblem(scene, params_);
  ReachShortcut shortcut;
  const internal::Problem problem =
      options_.reach_shortcut ? shortcut.Apply(built, options_.simd, batch_paths_) : built;
  result.times.street_ms = MsSince(t0);

  if (shortcut.none_left) {
    ReachShortcut::Answer(problem, params_, &result);
  } else {
    internal::CallersPool().SetSpin(options_.spin_wait);
    backend_->Run(problem, params_, options_.keep_pair_matrix, &result);
  }
  shortcut.Restore(built, &result);
  result.answered_by_reach_shortcut = shortcut.none_left;
  result.counts = internal::ResultCounts(problem);
  result.times.total_ms = MsSince(t0);
  return result;
}

std::vector<Result> Estimator::EstimateBatch(const std::vector<Scene>& scenes) {
  // The cpu backend on several threads: whole estimates in parallel, each on one thread, for
  // a batch; a single scene keeps every thread (below) unless it is small.
  if (options_.backend == Backend::kCpu && threads() > 1 &&
      (scenes.size() > 1 || (scenes.size() == 1 && TooSmallToSplit(params_)))) {
    if (!pool_) pool_ = std::make_unique<ScenePool>(params_, options_, threads());
    return pool_->EstimateBatch(scenes);
  }
  const auto t0 = std::chrono::steady_clock::now();
  // The batch's scenes share their other road users' paths, in the reach shortcut and in the
  // backend; forgotten after the batch (also when a scene throws): memory holds one batch.
  struct Sharing {
    Estimator* estimator;
    internal::ObjectPathsCache* cache;
    ~Sharing() {
      if (!cache) return;
      estimator->SharePaths(nullptr);
      cache->Clear();
    }
  } sharing{this, scenes.size() > 1 ? paths_cache_.get() : nullptr};
  if (sharing.cache) SharePaths(sharing.cache);
  std::vector<internal::Problem> built, problems;
  std::vector<ReachShortcut> shortcuts(scenes.size());
  // Each problem into its own slot: for a device batch on the host's threads (the device waits
  // for them), otherwise on this one. A scene that cannot be built is reported as a sequential
  // loop would (the first in scene order).
  built.resize(scenes.size());
  problems.resize(scenes.size());
  std::vector<std::exception_ptr> errors(scenes.size());
  const int threads = options_.backend == Backend::kCuda ? internal::ResolveThreads(options_.threads)
                                                         : 1;
  internal::ParallelForDynamic(static_cast<int>(scenes.size()), threads, [&](int k) {
    try {
      built[k] = internal::BuildProblem(scenes[k], params_);
      problems[k] = options_.reach_shortcut
                        ? shortcuts[k].Apply(built[k], options_.simd, batch_paths_)
                        : built[k];
    } catch (...) {
      errors[k] = std::current_exception();
    }
  });
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
  const double street_ms = MsSince(t0);
  std::vector<Result> results(scenes.size());
  std::vector<const internal::Problem*> views;
  std::vector<size_t> run;  // the problems the backend runs
  for (size_t k = 0; k < problems.size(); ++k) {
    if (shortcuts[k].none_left) {
      ReachShortcut::Answer(problems[k], params_, &results[k]);
    } else {
      views.push_back(&problems[k]);
      run.push_back(k);
    }
  }
  if (!views.empty()) {
    std::vector<Result> ran(views.size());
    internal::CallersPool().SetSpin(options_.spin_wait);
    backend_->RunBatch(views, params_, options_.keep_pair_matrix, &ran);
    for (size_t i = 0; i < run.size(); ++i) results[run[i]] = std::move(ran[i]);
  }
  for (size_t k = 0; k < results.size(); ++k) {
    shortcuts[k].Restore(built[k], &results[k]);
    results[k].answered_by_reach_shortcut = shortcuts[k].none_left;
  }
  const double total_ms = MsSince(t0);
  for (size_t k = 0; k < results.size(); ++k) {
    results[k].counts = internal::ResultCounts(problems[k]);
    if (results.size() > 1) {  // a batch shares its time: each result gets the mean
      results[k].times.street_ms = street_ms / results.size();
      results[k].times.total_ms = total_ms / results.size();
    } else {
      results[k].times.street_ms = street_ms;
      results[k].times.total_ms = total_ms;
    }
  }
  return results;
}

}  // namespace criticality
