#include "criticality/estimator.h"

#include <chrono>

#include "cpu/cpu_backend.h"
#include "cpu/reference_backend.h"
#include "criticality/errors.h"
#include "src/backend.h"
#include "src/problem.h"
#include "src/risk_assessment.h"

namespace criticality {
namespace {

double MsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

Backend ParseBackend(const std::string& name) {
  if (name == "reference") return Backend::kReference;
  if (name == "cpu") return Backend::kCpu;
  throw InputError("backend = '" + name + "': unknown; use reference or cpu");
}

std::string BackendName(Backend backend) {
  switch (backend) {
    case Backend::kReference: return "reference";
    case Backend::kCpu: return "cpu";
  }
  return "unknown";
}

Estimator::Estimator(const Params& params, const EstimatorOptions& options)
    : params_(params), options_(options) {
  ValidateParams(params_);
  if (options_.threads < 0) {
    throw InputError("options.threads = " + std::to_string(options_.threads) +
                     ": must be >= 0 (0 = all hardware threads)");
  }
  switch (options_.backend) {
    case Backend::kReference: backend_ = std::make_unique<ReferenceBackend>(); break;
    case Backend::kCpu: backend_ = std::make_unique<CpuBackend>(options_.threads); break;
  }
}

Estimator::~Estimator() = default;

int Estimator::threads() const { return backend_->Threads(); }

Result Estimator::Estimate(const Scene& scene) {
  const auto t0 = std::chrono::steady_clock::now();
  Result result;
  const internal::Problem problem = internal::BuildProblem(scene, params_);
  result.times.street_ms = MsSince(t0);

  auto t = std::chrono::steady_clock::now();
  backend_->GenerateTrajectories(problem);
  result.times.trajectory_ms = MsSince(t);

  t = std::chrono::steady_clock::now();
  std::vector<std::int16_t> first_step;
  backend_->RecognizeCollisions(problem, &first_step);
  result.times.collision_ms = MsSince(t);

  t = std::chrono::steady_clock::now();
  internal::AssessRisk(problem, params_, first_step.data(), backend_->Threads(), &result);
  result.times.risk_ms = MsSince(t);

  result.counts = problem.counts;
  if (options_.keep_pair_matrix) result.first_collision_step = std::move(first_step);
  result.times.total_ms = MsSince(t0);
  return result;
}

}  // namespace criticality
