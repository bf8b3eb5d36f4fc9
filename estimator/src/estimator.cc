#include "criticality/estimator.h"

#include <chrono>

#include "cpu/cpu_backend.h"
#include "cpu/reference_backend.h"
#include "criticality/errors.h"
#include "src/backend.h"
#include "src/problem.h"
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

std::string LaneProblem(const Lane& lane) {
  try {
    internal::FitLanes(LaneSet{lane, std::nullopt, std::nullopt}, "lane");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
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
  internal::AssessRisk(problem, params, first_step.data(), Threads(), result);
  result->times.risk_ms = MsSince(t);
  if (keep_pair_matrix) result->first_collision_step = std::move(first_step);
}

Estimator::Estimator(const Params& params, const EstimatorOptions& options)
    : params_(params), options_(options) {
  ValidateParams(params_);
  if (options_.threads < 0) {
    throw InputError("options.threads = " + std::to_string(options_.threads) +
                     ": must be >= 0 (0 = all hardware threads)");
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
      backend_ = std::make_unique<CpuBackend>(options_.threads);
      break;
    case Backend::kCuda:
      if (!CudaUsable(&why)) {
        throw InputError("backend cuda: " + why + "; use --backend cpu or auto");
      }
#ifdef CRIT_WITH_CUDA
      backend_ = cuda::MakeCudaBackend();
#endif
      break;
  }
}

Estimator::~Estimator() = default;

int Estimator::threads() const { return backend_->Threads(); }

Result Estimator::Estimate(const Scene& scene) {
  const auto t0 = std::chrono::steady_clock::now();
  Result result;
  const internal::Problem problem = internal::BuildProblem(scene, params_);
  result.times.street_ms = MsSince(t0);

  backend_->Run(problem, params_, options_.keep_pair_matrix, &result);
  result.counts = problem.counts;
  result.times.total_ms = MsSince(t0);
  return result;
}

std::vector<Result> Estimator::EstimateBatch(const std::vector<Scene>& scenes) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<internal::Problem> problems;
  problems.reserve(scenes.size());
  for (const Scene& scene : scenes) problems.push_back(internal::BuildProblem(scene, params_));
  const double street_ms = MsSince(t0);
  std::vector<const internal::Problem*> views;
  for (const internal::Problem& pb : problems) views.push_back(&pb);
  std::vector<Result> results(scenes.size());
  backend_->RunBatch(views, params_, options_.keep_pair_matrix, &results);
  const double total_ms = MsSince(t0);
  for (size_t k = 0; k < results.size(); ++k) {
    results[k].counts = problems[k].counts;
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
