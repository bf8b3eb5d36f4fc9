// The CUDA backend: trajectory generation, collision recognition and risk assessment on the
// device, from the same core/ functions as the CPU (one thread per hypothesis, per ego x CO
// pair, per ego hypothesis; the per-thread bodies are in kernel_bodies.h, tested on the CPU),
// with no host round trip between modules. Street data processing
// and hypothesis scoring (tiny) stay on the host (BuildProblem). Buffers are plain cudaMalloc,
// grown when needed and reused across calls. Poses are stored step-major ([n * count + t]) so
// that the threads of a warp read neighbouring CO poses. Sums over ego hypotheses run in ego
// order on the device, like the CPU's, and every CUDA failure becomes a CudaError naming the
// step.
#include <cuda_runtime.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <vector>

#include "core/chronological_risk.h"
#include "core/oriented_box.h"
#include "core/trajectory_generation.h"
#include "cuda/cuda_backend.h"
#include "cuda/device.cuh"
#include "cuda/kernel_bodies.h"
#include "src/risk_assessment.h"

namespace criticality::cuda {
namespace {

constexpr int kThreads = 128;

int Blocks(size_t n) { return static_cast<int>((n + kThreads - 1) / kThreads); }

// A grow-only device array.
template <typename T>
class DeviceArray {
 public:
  DeviceArray() = default;
  DeviceArray(const DeviceArray&) = delete;
  DeviceArray& operator=(const DeviceArray&) = delete;
  ~DeviceArray() {
    if (ptr_) cudaFree(ptr_);
  }
  T* Reserve(size_t n, const char* what) {
    if (n > capacity_) {
      if (ptr_) cudaFree(ptr_);
      ptr_ = nullptr;
      capacity_ = 0;
      Check(cudaMalloc(&ptr_, std::max<size_t>(n, 1) * sizeof(T)), what);
      capacity_ = n;
    }
    return ptr_;
  }
  T* Upload(const std::vector<T>& host, const char* what) {
    Reserve(host.size(), what);
    if (!host.empty()) {
      Check(cudaMemcpy(ptr_, host.data(), host.size() * sizeof(T), cudaMemcpyHostToDevice), what);
    }
    return ptr_;
  }
  void Download(std::vector<T>* host, size_t n, const char* what) const {
    host->resize(n);
    if (n) Check(cudaMemcpy(host->data(), ptr_, n * sizeof(T), cudaMemcpyDeviceToHost), what);
  }
  T* get() const { return ptr_; }

 private:
  T* ptr_{nullptr};
  size_t capacity_{0};
};

__global__ void TrajectoryKernel(const core::HypothesisSet* sets, const int* co_object_of,
                                 const int* co_offset, int n_ego, int n_co,
                                 core::SimulationConfig cfg, double* ex, double* ey, double* eyaw,
                                 double* cx, double* cy, double* cyaw) {
  const int g = blockIdx.x * blockDim.x + threadIdx.x;
  TrajectoryBody(g, sets, co_object_of, co_offset, n_ego, n_co, cfg, ex, ey, eyaw, cx, cy, cyaw);
}

__global__ void TrigKernel(const double* yaw, size_t n, double* c, double* s) {
  const size_t k = blockIdx.x * static_cast<size_t>(blockDim.x) + threadIdx.x;
  if (k < n) TrigBody(k, yaw, c, s);
}

__global__ void CollisionKernel(int n_ego, int n_co, int steps, Poses ego, Poses co, double ego_hl,
                                double ego_hw, const double* co_hl, const double* co_hw,
                                std::int16_t* first) {
  const size_t k = blockIdx.x * static_cast<size_t>(blockDim.x) + threadIdx.x;
  if (k < static_cast<size_t>(n_ego) * n_co) {
    CollisionBody(k, n_ego, n_co, steps, ego, co, ego_hl, ego_hw, co_hl, co_hw, first);
  }
}

__global__ void RiskKernel(int n_ego, int n_co, int steps, int n_obj, const std::int16_t* first,
                           const double* p_co, const int* object_of, RiskScratch w, double* ego_col,
                           char* ego_hit, double* by_step, double* by_object) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n_ego)
    RiskBody(i, n_co, steps, n_obj, first, p_co, object_of, w, ego_col, ego_hit, by_step,
             by_object);
}

__global__ void ReduceKernel(int n_ego, int steps, int n_obj, const double* p_ego,
                             const double* ego_col, const double* by_step, const double* by_object,
                             double* out) {
  const int q = blockIdx.x * blockDim.x + threadIdx.x;
  if (q <= steps + n_obj)
    ReduceBody(q, n_ego, steps, n_obj, p_ego, ego_col, by_step, by_object, out);
}

double MsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

class CudaBackend final : public EstimatorBackend {
 public:
  CudaBackend() { Check(cudaSetDevice(0), "cudaSetDevice"); }

  void GenerateTrajectories(const internal::Problem& pb) override {
    Upload(pb);
    LaunchTrajectories(pb);
    Check(cudaDeviceSynchronize(), "after trajectory kernels");
    host_stale_ = true;
  }

  void RecognizeCollisions(const internal::Problem& pb, std::vector<std::int16_t>* first) override {
    LaunchCollisions(pb);
    d_first_.Download(first, static_cast<size_t>(pb.EgoTrajectories()) * pb.CoTrajectories(),
                      "after collision kernel (copy pair matrix)");
  }

  void Run(const internal::Problem& pb, const Params& params, bool keep_pair_matrix,
           Result* result) override {
    auto t = std::chrono::steady_clock::now();
    GenerateTrajectories(pb);
    result->times.trajectory_ms = MsSince(t);
    t = std::chrono::steady_clock::now();
    LaunchCollisions(pb);
    Check(cudaDeviceSynchronize(), "after collision kernel");
    result->times.collision_ms = MsSince(t);
    t = std::chrono::steady_clock::now();
    const int n_ego = pb.EgoTrajectories(), n_co = pb.CoTrajectories(), steps = pb.Steps();
    const int n_obj = static_cast<int>(pb.cos.size());
    RiskScratch w{
        d_hist_.Reserve(static_cast<size_t>(n_ego) * (steps + 1), "cudaMalloc histogram"),
        d_events_.Reserve(static_cast<size_t>(n_ego) * n_co, "cudaMalloc events"),
        d_contrib_.Reserve(static_cast<size_t>(n_ego) * n_co, "cudaMalloc contributions"),
        d_mass_.Reserve(static_cast<size_t>(n_ego) * std::max(n_obj, 1), "cudaMalloc hit mass")};
    double* ego_col = d_ego_col_.Reserve(n_ego, "cudaMalloc ego collision probability");
    char* ego_hit = d_ego_hit_.Reserve(n_ego, "cudaMalloc ego hit");
    double* by_step = d_by_step_.Reserve(static_cast<size_t>(n_ego) * steps, "cudaMalloc by step");
    double* by_obj =
        d_by_obj_.Reserve(static_cast<size_t>(n_ego) * std::max(n_obj, 1), "cudaMalloc by object");
    double* out = d_out_.Reserve(steps + n_obj + 1, "cudaMalloc risk output");
    RiskKernel<<<Blocks(n_ego), kThreads>>>(n_ego, n_co, steps, n_obj, d_first_.get(),
                                            d_p_co_.get(), d_object_of_.get(), w, ego_col, ego_hit,
                                            by_step, by_obj);
    Check(cudaGetLastError(), "after risk kernel launch");
    ReduceKernel<<<Blocks(steps + n_obj + 1), kThreads>>>(n_ego, steps, n_obj, d_p_ego_.get(),
                                                          ego_col, by_step, by_obj, out);
    Check(cudaGetLastError(), "after reduction kernel launch");
    std::vector<double> sums;
    d_out_.Download(&sums, steps + n_obj + 1, "after risk kernels (copy sums)");
    std::vector<double> col;
    d_ego_col_.Download(&col, n_ego, "copy ego collision probabilities");
    std::vector<char> hit;
    d_ego_hit_.Download(&hit, n_ego, "copy ego hits");
    result->first_collision_pmf.assign(sums.begin(), sums.begin() + steps);
    result->objects = pb.objects;
    for (int o = 0; o < n_obj; ++o) result->objects[o].contribution = sums[steps + o];
    result->p_collision = sums[steps + n_obj];
    result->ego_probability = pb.ego_probability;
    result->ego_collision_probability = std::move(col);
    internal::FillEscapeRoutes(pb, params, hit, result);
    if (keep_pair_matrix) {
      d_first_.Download(&result->first_collision_step, static_cast<size_t>(n_ego) * n_co,
                        "copy pair matrix");
    }
    result->times.risk_ms = MsSince(t);
  }

  int Threads() const override { return 1; }
  const internal::TrajectoryStore& EgoTrajectories() const override {
    SyncHost();
    return ego_;
  }
  const internal::TrajectoryStore& CoTrajectories() const override {
    SyncHost();
    return co_;
  }

 private:
  void Upload(const internal::Problem& pb) {
    std::vector<core::HypothesisSet> sets{pb.ego};
    sets.insert(sets.end(), pb.cos.begin(), pb.cos.end());
    d_sets_.Upload(sets, "copy hypothesis sets");
    d_object_of_.Upload(pb.co_object_of, "copy CO object index");
    d_offset_.Upload(pb.co_offset, "copy CO offsets");
    d_p_co_.Upload(pb.co_probability, "copy CO probabilities");
    d_p_ego_.Upload(pb.ego_probability, "copy ego probabilities");
    std::vector<double> hl(pb.CoTrajectories()), hw(pb.CoTrajectories());
    for (int j = 0; j < pb.CoTrajectories(); ++j) {
      hl[j] = pb.cos[pb.co_object_of[j]].half_length;
      hw[j] = pb.cos[pb.co_object_of[j]].half_width;
    }
    d_co_hl_.Upload(hl, "copy CO half lengths");
    d_co_hw_.Upload(hw, "copy CO half widths");
    pb_ = &pb;
  }

  void LaunchTrajectories(const internal::Problem& pb) {
    const int n_ego = pb.EgoTrajectories(), n_co = pb.CoTrajectories(), steps = pb.Steps();
    const size_t ne = static_cast<size_t>(n_ego) * steps, nc = static_cast<size_t>(n_co) * steps;
    double* ex = d_ex_.Reserve(ne, "cudaMalloc ego x");
    double* ey = d_ey_.Reserve(ne, "cudaMalloc ego y");
    double* eyaw = d_eyaw_.Reserve(ne, "cudaMalloc ego yaw");
    double* cx = d_cx_.Reserve(nc, "cudaMalloc CO x");
    double* cy = d_cy_.Reserve(nc, "cudaMalloc CO y");
    double* cyaw = d_cyaw_.Reserve(nc, "cudaMalloc CO yaw");
    TrajectoryKernel<<<Blocks(n_ego + n_co), kThreads>>>(d_sets_.get(), d_object_of_.get(),
                                                         d_offset_.get(), n_ego, n_co, pb.sim, ex,
                                                         ey, eyaw, cx, cy, cyaw);
    Check(cudaGetLastError(), "after trajectory kernel launch");
    TrigKernel<<<Blocks(ne), kThreads>>>(eyaw, ne, d_ec_.Reserve(ne, "cudaMalloc ego cos"),
                                         d_es_.Reserve(ne, "cudaMalloc ego sin"));
    Check(cudaGetLastError(), "after ego trig kernel launch");
    TrigKernel<<<Blocks(nc), kThreads>>>(cyaw, nc, d_cc_.Reserve(nc, "cudaMalloc CO cos"),
                                         d_cs_.Reserve(nc, "cudaMalloc CO sin"));
    Check(cudaGetLastError(), "after CO trig kernel launch");
  }

  void LaunchCollisions(const internal::Problem& pb) {
    const int n_ego = pb.EgoTrajectories(), n_co = pb.CoTrajectories();
    const size_t pairs = static_cast<size_t>(n_ego) * n_co;
    std::int16_t* first = d_first_.Reserve(pairs, "cudaMalloc pair matrix");
    if (pairs == 0) return;
    CollisionKernel<<<Blocks(pairs), kThreads>>>(
        n_ego, n_co, pb.Steps(), Poses{d_ex_.get(), d_ey_.get(), d_ec_.get(), d_es_.get()},
        Poses{d_cx_.get(), d_cy_.get(), d_cc_.get(), d_cs_.get()}, pb.ego.half_length,
        pb.ego.half_width, d_co_hl_.get(), d_co_hw_.get(), first);
    Check(cudaGetLastError(), "after collision kernel launch");
  }

  // Device poses (step-major) -> host stores (trajectory-major), when a caller asks.
  void SyncHost() const {
    if (!host_stale_ || !pb_) return;
    const int steps = pb_->Steps();
    auto fetch = [&](const DeviceArray<double>& dx, const DeviceArray<double>& dy,
                     const DeviceArray<double>& dyaw, int count, internal::TrajectoryStore* out) {
      out->Resize(count, steps);
      std::vector<double> x, y, yaw;
      dx.Download(&x, static_cast<size_t>(count) * steps, "copy trajectories x");
      dy.Download(&y, static_cast<size_t>(count) * steps, "copy trajectories y");
      dyaw.Download(&yaw, static_cast<size_t>(count) * steps, "copy trajectories yaw");
      for (int t = 0; t < count; ++t) {
        for (int n = 0; n < steps; ++n) {
          out->x[out->Offset(t) + n] = x[static_cast<size_t>(n) * count + t];
          out->y[out->Offset(t) + n] = y[static_cast<size_t>(n) * count + t];
          out->yaw[out->Offset(t) + n] = yaw[static_cast<size_t>(n) * count + t];
        }
      }
    };
    fetch(d_ex_, d_ey_, d_eyaw_, pb_->EgoTrajectories(), &ego_);
    fetch(d_cx_, d_cy_, d_cyaw_, pb_->CoTrajectories(), &co_);
    host_stale_ = false;
  }

  const internal::Problem* pb_{nullptr};
  mutable bool host_stale_{false};
  mutable internal::TrajectoryStore ego_, co_;
  DeviceArray<core::HypothesisSet> d_sets_;
  DeviceArray<int> d_object_of_, d_offset_, d_hist_, d_events_;
  DeviceArray<double> d_p_co_, d_p_ego_, d_co_hl_, d_co_hw_;
  DeviceArray<double> d_ex_, d_ey_, d_eyaw_, d_ec_, d_es_, d_cx_, d_cy_, d_cyaw_, d_cc_, d_cs_;
  DeviceArray<std::int16_t> d_first_;
  DeviceArray<double> d_contrib_, d_mass_, d_ego_col_, d_by_step_, d_by_obj_, d_out_;
  DeviceArray<char> d_ego_hit_;
};

}  // namespace

std::unique_ptr<EstimatorBackend> MakeCudaBackend() { return std::make_unique<CudaBackend>(); }

}  // namespace criticality::cuda
