// The CUDA backend: trajectory generation, collision recognition and risk assessment on the
// device, for one scene or a whole batch of scenes in one set of launches (batch_layout.h), from
// the same core/ functions as the CPU (one thread per hypothesis and per ego x CO pair, one warp
// per ego hypothesis's risk with its scratch in shared memory; the bodies are in kernel_bodies.h,
// tested on the CPU), with no host round trip between modules. Street data processing and
// hypothesis scoring (tiny) stay on the host (BuildProblem). Buffers are plain cudaMalloc, grown
// when needed and reused across calls. Poses are stored step-major ([n * count + t]) so that the
// threads of a warp read neighbouring CO poses. Sums over ego hypotheses run in ego order on the
// device, like the CPU's, and every CUDA failure becomes a CudaError naming the step. A problem
// with carriages (long bodies) has every set simulated and checked on the device, and its pair
// matrix folded and its risk assessed on the host (internal::AssessBodies), beside the batch's
// other problems.
#include <cuda_runtime.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "core/chronological_risk.h"
#include "core/oriented_box.h"
#include "core/trajectory_generation.h"
#include "cuda/batch_layout.h"
#include "cuda/cuda_backend.h"
#include "cuda/device.cuh"
#include "cuda/kernel_bodies.h"
#include "src/parallel_for.h"
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
    Download(host, 0, n, what);
  }
  /** Elements [first, first + n). */
  void Download(std::vector<T>* host, size_t first, size_t n, const char* what) const {
    host->resize(n);
    if (n) {
      Check(cudaMemcpy(host->data(), ptr_ + first, n * sizeof(T), cudaMemcpyDeviceToHost), what);
    }
  }
  T* get() const { return ptr_; }
  size_t bytes() const { return capacity_ * sizeof(T); }

 private:
  T* ptr_{nullptr};
  size_t capacity_{0};
};

__global__ void TrajectoryKernel(const core::HypothesisSet* sets, BatchLayout b,
                                 core::SimulationConfig cfg, double* ex, double* ey, double* eyaw,
                                 double* cx, double* cy, double* cyaw) {
  const int g = blockIdx.x * blockDim.x + threadIdx.x;
  TrajectoryBody(g, sets, b, cfg, ex, ey, eyaw, cx, cy, cyaw);
}

__global__ void TrigKernel(const double* yaw, size_t n, double* c, double* s) {
  const size_t k = blockIdx.x * static_cast<size_t>(blockDim.x) + threadIdx.x;
  if (k < n) TrigBody(k, yaw, c, s);
}

__global__ void BoundsKernel(int total, int steps, const double* x, const double* y,
                             double* bounds) {
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t < total) BoundsBody(t, total, steps, x, y, bounds);
}

__global__ void CollisionKernel(BatchLayout b, long long pairs, Poses ego, Poses co,
                                const double* ego_bounds, const double* co_bounds,
                                std::int16_t* first, char* ego_hits) {
  const long long k = blockIdx.x * static_cast<long long>(blockDim.x) + threadIdx.x;
  if (k < pairs) CollisionBody(k, b, ego, co, ego_bounds, co_bounds, first, ego_hits);
}

__global__ void RiskKernel(BatchLayout b, const std::int16_t* first, const double* p_co,
                           const char* ego_hits, RiskScratch w, double* ego_col, double* by_step,
                           double* by_object) {
  const int g = blockIdx.x * blockDim.x + threadIdx.x;
  if (g < b.total_ego) RiskBody(g, b, first, p_co, ego_hits, w, ego_col, by_step, by_object);
}

// A warp on the device: each lane runs its own part of a phase; Sync orders the warp's
// shared and global memory between phases.
struct DeviceWarp {
  int lane;
  template <typename F>
  __device__ void Lanes(F f) const {
    f(lane);
  }
  template <typename F>
  __device__ void Lane0(F f) const {
    if (lane == 0) f();
  }
  __device__ void Sync() const { __syncwarp(); }
  __device__ void Increment(int* a) const { atomicAdd(a, 1); }
};

// One warp per ego hypothesis (RiskRowBody), each with its RiskRowBytes of shared memory.
__global__ void RiskRowKernel(BatchLayout b, const std::int16_t* first, const double* p_co,
                              const char* ego_hits, int* events, int max_obj, double* ego_col,
                              double* by_step, double* by_obj) {
  extern __shared__ double shared[];
  const int warp = threadIdx.x / kWarp;
  const int g = blockIdx.x * (blockDim.x / kWarp) + warp;
  char* mine = reinterpret_cast<char*>(shared) + warp * RiskRowBytes(b.steps, max_obj);
  RiskRowBody(DeviceWarp{static_cast<int>(threadIdx.x % kWarp)}, g, b, first, p_co, ego_hits,
              events, RiskRowScratchAt(mine, b.steps, max_obj), ego_col, by_step, by_obj);
}

// One warp per risk output (ReduceWarpBody).
__global__ void ReduceWarpKernel(BatchLayout b, int outputs, const double* p_ego,
                                 const double* ego_col, const double* by_step,
                                 const double* by_object, double* out) {
  constexpr int kWarps = kThreads / kWarp;
  __shared__ double term[kWarps][kWarp];
  __shared__ int counts[kWarps][kWarp];
  const int warp = threadIdx.x / kWarp;
  const int q = blockIdx.x * kWarps + warp;
  if (q >= outputs) return;
  ReduceWarpBody(DeviceWarp{static_cast<int>(threadIdx.x % kWarp)}, q, b, p_ego, ego_col, by_step,
                 by_object, ReduceScratch{term[warp], counts[warp]}, out);
}

__global__ void ReduceKernel(BatchLayout b, int outputs, const double* p_ego, const double* ego_col,
                             const double* by_step, const double* by_object, double* out) {
  const int q = blockIdx.x * blockDim.x + threadIdx.x;
  if (q < outputs) ReduceBody(q, b, p_ego, ego_col, by_step, by_object, out);
}

double MsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

class CudaBackend final : public EstimatorBackend {
 public:
  explicit CudaBackend(int host_threads) : host_threads_(std::max(1, host_threads)) {
    Check(cudaSetDevice(0), "cudaSetDevice");
    const char* timing = std::getenv("CRITICALITY_CUDA_TIMING");
    print_timing_ = timing && *timing && std::string(timing) != "0";
    // CRITICALITY_CUDA_RISK, to compare the risk kernels on one binary: unset, a warp per ego
    // hypothesis (RiskRowKernel) and a thread per output (ReduceKernel); "thread", a thread for
    // each (the first kernels); "warp", a warp for each (ReduceWarpKernel: checked on the CPU
    // by emulation, not yet run on a GPU, so not the default).
    if (const char* risk = std::getenv("CRITICALITY_CUDA_RISK"); risk && *risk) {
      const std::string v(risk);
      if (v != "thread" && v != "warp")
        throw CudaError("CRITICALITY_CUDA_RISK=" + v +
                        " is neither 'thread' nor 'warp'; unset it for the default");
      rows_per_thread_ = v == "thread";
      reduce_per_thread_ = v == "thread";
    }
  }

  void GenerateTrajectories(const internal::Problem& pb) override {
    Upload({&pb});
    LaunchTrajectories();
    Check(cudaDeviceSynchronize(), "after trajectory kernels");
  }

  void RecognizeCollisions(const internal::Problem& pb, std::vector<std::int16_t>* first) override {
    LaunchCollisions();
    d_first_.Download(first, static_cast<size_t>(pb.EgoTrajectories()) * pb.CoTrajectories(),
                      "after collision kernel (copy pair matrix)");
  }

  void Run(const internal::Problem& pb, const Params& params, bool keep_pair_matrix,
           Result* result) override {
    std::vector<Result> results(1);
    RunBatch({&pb}, params, keep_pair_matrix, &results);
    *result = std::move(results.front());
  }

  // A batch larger than the device's memory runs as consecutive chunks, each in one set of
  // launches (DeviceBytes, BatchChunks; batch_layout.h).
  void RunBatch(const std::vector<const internal::Problem*>& problems, const Params& params,
                bool keep_pair_matrix, std::vector<Result>* results) override {
    if (problems.empty()) return;
    std::vector<std::uint64_t> bytes;
    bytes.reserve(problems.size());
    for (const internal::Problem* pb : problems) bytes.push_back(DeviceBytes(*pb));
    const std::vector<std::pair<size_t, size_t>> chunks = BatchChunks(bytes, Budget());
    if (chunks.size() == 1) {
      RunChunk(problems, params, keep_pair_matrix, results);
      return;
    }
    for (const auto& [first, last] : chunks) {
      const std::vector<const internal::Problem*> part(problems.begin() + first,
                                                       problems.begin() + last);
      std::vector<Result> out(part.size());
      RunChunk(part, params, keep_pair_matrix, &out);
      std::move(out.begin(), out.end(), results->begin() + first);
    }
  }

 private:
  // What a batch may take: 90 % of the device memory that is free now or held by this
  // backend's buffers (they are freed and allocated again when they grow).
  // CRITICALITY_CUDA_BATCH_BYTES (bytes) sets it instead, for tests of the chunking.
  std::uint64_t Budget() const {
    if (const char* forced = std::getenv("CRITICALITY_CUDA_BATCH_BYTES"); forced && *forced)
      return std::strtoull(forced, nullptr, 10);
    size_t free_bytes = 0, total_bytes = 0;
    Check(cudaMemGetInfo(&free_bytes, &total_bytes), "cudaMemGetInfo");
    return static_cast<std::uint64_t>(0.9 * static_cast<double>(free_bytes + Reserved()));
  }

  size_t Reserved() const {
    size_t n = d_sets_.bytes() + d_first_.bytes() + d_ego_hits_.bytes();
    for (const auto* a : {&d_set_base_, &d_ego_base_, &d_co_base_, &d_obj_base_, &d_out_base_,
                          &d_object_of_, &d_co_offset_, &d_hist_, &d_events_})
      n += a->bytes();
    for (const auto* a : {&d_pair_base_, &d_ego_obj_base_}) n += a->bytes();
    for (const auto* a :
         {&d_co_hl_,   &d_co_hw_,   &d_ego_hl_, &d_ego_hw_, &d_p_co_,       &d_p_ego_,
          &d_ex_,      &d_ey_,      &d_eyaw_,   &d_ec_,     &d_es_,         &d_cx_,
          &d_cy_,      &d_cyaw_,    &d_cc_,     &d_cs_,     &d_contrib_,    &d_mass_,
          &d_ego_col_, &d_by_step_, &d_by_obj_, &d_out_,    &d_ego_bounds_, &d_co_bounds_})
      n += a->bytes();
    return n;
  }

  // How the risk kernel runs this chunk: a warp per ego hypothesis with its scratch in shared
  // memory (RiskRowKernel; up to 4 warps a block, fewer where a row's scratch is large), or,
  // where one warp's scratch does not fit or CRITICALITY_CUDA_RISK=thread asks for it (to
  // compare), a thread per ego hypothesis with its scratch in global memory (RiskKernel).
  struct RowLaunch {
    int warps_per_block{0};  ///< 0: RiskKernel
    int max_obj{0};
    int bytes_per_warp{0};
  };
  RowLaunch RiskRowLaunch() {
    RowLaunch r;
    if (rows_per_thread_) return r;
    const BatchHost& h = host_;
    for (int p = 0; p < h.problems; ++p)
      r.max_obj = std::max(r.max_obj, h.obj_base[p + 1] - h.obj_base[p]);
    const size_t per_warp = RiskRowBytes(h.steps, r.max_obj);
    if (shared_optin_ == 0) {
      int device = 0;
      Check(cudaGetDevice(&device), "cudaGetDevice");
      Check(cudaDeviceGetAttribute(&shared_optin_, cudaDevAttrMaxSharedMemoryPerBlockOptin, device),
            "shared memory per block");
    }
    const size_t warps = std::min<size_t>(4, static_cast<size_t>(shared_optin_) / per_warp);
    if (warps == 0) return r;
    r.warps_per_block = static_cast<int>(warps);
    r.bytes_per_warp = static_cast<int>(per_warp);
    const int bytes = r.warps_per_block * r.bytes_per_warp;
    if (bytes > shared_attr_) {
      Check(cudaFuncSetAttribute(RiskRowKernel, cudaFuncAttributeMaxDynamicSharedMemorySize, bytes),
            "risk row kernel's shared memory");
      shared_attr_ = bytes;
    }
    return r;
  }

  void RunChunk(const std::vector<const internal::Problem*>& problems, const Params& params,
                bool keep_pair_matrix, std::vector<Result>* results) {
    auto t = std::chrono::steady_clock::now();
    const auto t_chunk = t;
    Upload(problems);
    const double upload_ms = MsSince(t);
    LaunchTrajectories();
    Check(cudaDeviceSynchronize(), "after trajectory kernels");
    const double trajectory_ms = MsSince(t);
    t = std::chrono::steady_clock::now();
    LaunchCollisions();
    Check(cudaDeviceSynchronize(), "after collision kernel");
    const double collision_ms = MsSince(t);
    t = std::chrono::steady_clock::now();
    const BatchHost& h = host_;
    const size_t total_ego = h.TotalEgo(), pairs = h.TotalPairs();
    const size_t ego_obj = std::max<long long>(h.TotalEgoObj(), 1);
    double* ego_col = d_ego_col_.Reserve(total_ego, "cudaMalloc ego collision probability");
    double* by_step = d_by_step_.Reserve(total_ego * h.steps, "cudaMalloc by step");
    double* by_obj = d_by_obj_.Reserve(ego_obj, "cudaMalloc by object");
    double* out = d_out_.Reserve(h.TotalOut(), "cudaMalloc risk output");
    int* events = d_events_.Reserve(pairs, "cudaMalloc events");
    const RowLaunch rows = RiskRowLaunch();
    if (rows.warps_per_block > 0) {
      const int per_block = rows.warps_per_block;
      RiskRowKernel<<<static_cast<int>((total_ego + per_block - 1) / per_block), per_block * kWarp,
                      rows.bytes_per_warp * per_block>>>(layout_, d_first_.get(), d_p_co_.get(),
                                                         d_ego_hits_.get(), events, rows.max_obj,
                                                         ego_col, by_step, by_obj);
      Check(cudaGetLastError(), "after risk row kernel launch");
    } else {
      RiskScratch w{d_hist_.Reserve(total_ego * (h.steps + 1), "cudaMalloc histogram"), events,
                    d_contrib_.Reserve(pairs, "cudaMalloc contributions"),
                    d_mass_.Reserve(ego_obj, "cudaMalloc hit mass")};
      RiskKernel<<<Blocks(total_ego), kThreads>>>(layout_, d_first_.get(), d_p_co_.get(),
                                                  d_ego_hits_.get(), w, ego_col, by_step, by_obj);
      Check(cudaGetLastError(), "after risk kernel launch");
    }
    double row_kernel_ms = 0.0;
    if (print_timing_) {
      Check(cudaDeviceSynchronize(), "after risk row kernel");
      row_kernel_ms = MsSince(t);
    }
    if (reduce_per_thread_) {
      ReduceKernel<<<Blocks(h.TotalOut()), kThreads>>>(layout_, h.TotalOut(), d_p_ego_.get(),
                                                       ego_col, by_step, by_obj, out);
    } else {
      ReduceWarpKernel<<<static_cast<int>(
                             (static_cast<size_t>(h.TotalOut()) * kWarp + kThreads - 1) / kThreads),
                         kThreads>>>(layout_, h.TotalOut(), d_p_ego_.get(), ego_col, by_step,
                                     by_obj, out);
    }
    Check(cudaGetLastError(), "after reduction kernel launch");
    double risk_kernels_ms = 0.0;
    if (print_timing_) {
      Check(cudaDeviceSynchronize(), "after risk kernels");
      risk_kernels_ms = MsSince(t);
    }
    const auto t_download = std::chrono::steady_clock::now();
    std::vector<double>& sums = sums_;  // members: their memory is reused call after call
    std::vector<double>& col = col_;
    std::vector<char>& hit = hit_;
    std::vector<std::int16_t>& first = first_;
    if (!keep_pair_matrix) first.clear();
    d_out_.Download(&sums, h.TotalOut(), "after risk kernels (copy sums)");
    d_ego_col_.Download(&col, total_ego, "copy ego collision probabilities");
    d_ego_hits_.Download(&hit, total_ego, "copy ego hits");
    if (keep_pair_matrix) d_first_.Download(&first, pairs, "copy pair matrices");
    // Problems with carriages need their own slice of the device's pair matrix: copied here,
    // in order, before the host's threads take the problems.
    std::vector<std::vector<std::int16_t>> carriage_pairs(problems.size());
    for (size_t p = 0; p < problems.size(); ++p) {
      if (!problems[p]->HasCarriages()) continue;
      if (keep_pair_matrix) {
        carriage_pairs[p].assign(first.begin() + h.pair_base[p],
                                 first.begin() + h.pair_base[p + 1]);
      } else {
        d_first_.Download(&carriage_pairs[p], static_cast<size_t>(h.pair_base[p]),
                          static_cast<size_t>(h.pair_base[p + 1] - h.pair_base[p]),
                          "copy pair matrix of a problem with carriages");
      }
    }
    const double download_ms = MsSince(t_download);
    const auto t_host = std::chrono::steady_clock::now();
    // Each problem's outputs on the host's threads, each into its own result: the same
    // answers whatever the number of threads.
    std::vector<std::exception_ptr> errors(problems.size());
    internal::ParallelForDynamic(static_cast<int>(problems.size()), host_threads_, [&](int p) {
      try {
        FinishProblem(*problems[p], p, params, keep_pair_matrix, sums, col, hit, first,
                      &carriage_pairs[p], &(*results)[p]);
      } catch (...) {
        errors[p] = std::current_exception();
      }
    });
    internal::CallersPool().Rest();
    for (const std::exception_ptr& e : errors)
      if (e) std::rethrow_exception(e);
    const double risk_ms = MsSince(t);
    if (print_timing_) {
      std::fprintf(stderr,
                   "cuda chunk of %zu problems: upload %.3f (batch on the host %.3f), "
                   "trajectories %.3f, collisions %.3f, risk kernels %.3f (rows %.3f), downloads "
                   "%.3f, host outputs %.3f, total %.3f ms\n",
                   problems.size(), upload_ms, batch_ms_, trajectory_ms - upload_ms, collision_ms,
                   risk_kernels_ms, row_kernel_ms, download_ms, MsSince(t_host), MsSince(t_chunk));
    }
    const double n = static_cast<double>(problems.size());
    for (Result& r : *results) {  // a batch shares its time: each result gets the mean
      r.times.trajectory_ms = trajectory_ms / n;
      r.times.collision_ms = collision_ms / n;
      r.times.risk_ms = risk_ms / n;
    }
  }

  // Problem p's result from the downloaded sums, ego collision probabilities and hits (the
  // device's risk), or, for a problem with carriages, from its pair matrix on the host.
  void FinishProblem(const internal::Problem& pb, size_t p, const Params& params,
                     bool keep_pair_matrix, const std::vector<double>& sums,
                     const std::vector<double>& col, const std::vector<char>& hit,
                     const std::vector<std::int16_t>& first, std::vector<std::int16_t>* mine,
                     Result* out) const {
    const BatchHost& h = host_;
    Result& r = *out;
    if (pb.HasCarriages()) {
      // Long bodies: the device's risk knows every carriage as an object of its own, so
      // this problem's pair matrix is folded into its vehicles' columns and assessed on the
      // host, as every other backend does (estimator/ALGORITHM.md, "Long and articulated
      // bodies").
      internal::AssessBodies(pb, params, mine, 1, &r);
      if (keep_pair_matrix) r.first_collision_step = std::move(*mine);
      return;
    }
    const int steps = h.steps, n_obj = static_cast<int>(pb.cos.size());
    const double* s = sums.data() + h.out_base[p];
    r.first_collision_pmf.assign(s, s + steps);
    r.objects = pb.objects;
    for (int o = 0; o < n_obj; ++o) r.objects[o].contribution = s[steps + o];
    r.p_collision = s[steps + n_obj];
    r.ego_probability = pb.ego_probability;
    r.ego_collision_probability.assign(col.begin() + h.ego_base[p],
                                       col.begin() + h.ego_base[p + 1]);
    internal::FinishDecisionOutputs(
        pb, params, std::vector<char>(hit.begin() + h.ego_base[p], hit.begin() + h.ego_base[p + 1]),
        &r);
    if (keep_pair_matrix) {
      r.first_collision_step.assign(first.begin() + h.pair_base[p],
                                    first.begin() + h.pair_base[p + 1]);
    }
  }

 public:
  /** The host's threads (the device's work is in its launches). */
  int Threads() const override { return host_threads_; }
  const internal::TrajectoryStore& EgoTrajectories() const override {
    SyncHost();
    return ego_;
  }
  const internal::TrajectoryStore& CoTrajectories() const override {
    SyncHost();
    return co_;
  }

 private:
  void Upload(const std::vector<const internal::Problem*>& problems) {
    const auto t0 = std::chrono::steady_clock::now();
    MakeBatch(problems, &host_);
    batch_ms_ = MsSince(t0);
    const BatchHost& h = host_;
    d_sets_.Upload(h.sets, "copy hypothesis sets");
    layout_ = BatchLayout{h.problems,
                          h.steps,
                          h.TotalEgo(),
                          h.TotalCo(),
                          d_set_base_.Upload(h.set_base, "copy batch set offsets"),
                          d_ego_base_.Upload(h.ego_base, "copy batch ego offsets"),
                          d_co_base_.Upload(h.co_base, "copy batch CO offsets"),
                          d_pair_base_.Upload(h.pair_base, "copy batch pair offsets"),
                          d_obj_base_.Upload(h.obj_base, "copy batch object offsets"),
                          d_ego_obj_base_.Upload(h.ego_obj_base, "copy batch ego x object offsets"),
                          d_out_base_.Upload(h.out_base, "copy batch output offsets"),
                          d_object_of_.Upload(h.co_object_of, "copy CO object index"),
                          d_co_offset_.Upload(h.co_offset, "copy CO offsets"),
                          d_co_hl_.Upload(h.co_half_length, "copy CO half lengths"),
                          d_co_hw_.Upload(h.co_half_width, "copy CO half widths"),
                          d_ego_hl_.Upload(h.ego_half_length, "copy ego half lengths"),
                          d_ego_hw_.Upload(h.ego_half_width, "copy ego half widths")};
    d_p_co_.Upload(h.p_co, "copy CO probabilities");
    d_p_ego_.Upload(h.p_ego, "copy ego probabilities");
    sim_ = problems.front()->sim;
    host_stale_ = true;
  }

  void LaunchTrajectories() {
    const size_t ne = static_cast<size_t>(host_.TotalEgo()) * host_.steps;
    const size_t nc = static_cast<size_t>(host_.TotalCo()) * host_.steps;
    double* ex = d_ex_.Reserve(ne, "cudaMalloc ego x");
    double* ey = d_ey_.Reserve(ne, "cudaMalloc ego y");
    double* eyaw = d_eyaw_.Reserve(ne, "cudaMalloc ego yaw");
    double* cx = d_cx_.Reserve(nc, "cudaMalloc CO x");
    double* cy = d_cy_.Reserve(nc, "cudaMalloc CO y");
    double* cyaw = d_cyaw_.Reserve(nc, "cudaMalloc CO yaw");
    TrajectoryKernel<<<Blocks(host_.TotalEgo() + host_.TotalCo()), kThreads>>>(
        d_sets_.get(), layout_, sim_, ex, ey, eyaw, cx, cy, cyaw);
    Check(cudaGetLastError(), "after trajectory kernel launch");
    if (ne) {
      TrigKernel<<<Blocks(ne), kThreads>>>(eyaw, ne, d_ec_.Reserve(ne, "cudaMalloc ego cos"),
                                           d_es_.Reserve(ne, "cudaMalloc ego sin"));
      Check(cudaGetLastError(), "after ego trig kernel launch");
    }
    if (nc) {
      TrigKernel<<<Blocks(nc), kThreads>>>(cyaw, nc, d_cc_.Reserve(nc, "cudaMalloc CO cos"),
                                           d_cs_.Reserve(nc, "cudaMalloc CO sin"));
      Check(cudaGetLastError(), "after CO trig kernel launch");
    }
  }

  void LaunchCollisions() {
    const long long pairs = host_.TotalPairs();
    std::int16_t* first = d_first_.Reserve(pairs, "cudaMalloc pair matrix");
    const int total_ego = host_.TotalEgo(), total_co = host_.TotalCo(), steps = host_.steps;
    char* ego_hits = d_ego_hits_.Reserve(total_ego, "cudaMalloc ego hit marks");
    if (total_ego) Check(cudaMemset(ego_hits, 0, total_ego), "clear ego hit marks");
    if (pairs == 0) return;
    const size_t blocks = static_cast<size_t>(BoundsBlocks(steps)) * 4;
    double* ego_bounds = d_ego_bounds_.Reserve(blocks * total_ego, "cudaMalloc ego bounds");
    double* co_bounds = d_co_bounds_.Reserve(blocks * total_co, "cudaMalloc CO bounds");
    BoundsKernel<<<Blocks(total_ego), kThreads>>>(total_ego, steps, d_ex_.get(), d_ey_.get(),
                                                  ego_bounds);
    BoundsKernel<<<Blocks(total_co), kThreads>>>(total_co, steps, d_cx_.get(), d_cy_.get(),
                                                 co_bounds);
    Check(cudaGetLastError(), "after bounds kernel launch");
    CollisionKernel<<<Blocks(pairs), kThreads>>>(
        layout_, pairs, Poses{d_ex_.get(), d_ey_.get(), d_ec_.get(), d_es_.get()},
        Poses{d_cx_.get(), d_cy_.get(), d_cc_.get(), d_cs_.get()}, ego_bounds, co_bounds, first,
        ego_hits);
    Check(cudaGetLastError(), "after collision kernel launch");
  }

  // Device poses (step-major) -> host stores (trajectory-major) of the batch's first problem.
  void SyncHost() const {
    if (!host_stale_ || host_.problems == 0) return;
    const int steps = host_.steps;
    auto fetch = [&](const DeviceArray<double>& dx, const DeviceArray<double>& dy,
                     const DeviceArray<double>& dyaw, int total, int count,
                     internal::TrajectoryStore* out) {
      out->Resize(count, steps);
      std::vector<double> x, y, yaw;
      dx.Download(&x, static_cast<size_t>(total) * steps, "copy trajectories x");
      dy.Download(&y, static_cast<size_t>(total) * steps, "copy trajectories y");
      dyaw.Download(&yaw, static_cast<size_t>(total) * steps, "copy trajectories yaw");
      for (int t = 0; t < count; ++t) {
        for (int n = 0; n < steps; ++n) {
          out->x[out->Offset(t) + n] = x[static_cast<size_t>(n) * total + t];
          out->y[out->Offset(t) + n] = y[static_cast<size_t>(n) * total + t];
          out->yaw[out->Offset(t) + n] = yaw[static_cast<size_t>(n) * total + t];
        }
      }
    };
    fetch(d_ex_, d_ey_, d_eyaw_, host_.TotalEgo(), host_.ego_base[1], &ego_);
    fetch(d_cx_, d_cy_, d_cyaw_, host_.TotalCo(), host_.co_base[1], &co_);
    host_stale_ = false;
  }

  int host_threads_{1};
  int shared_optin_{0};             ///< the device's shared memory per block, opted in
  int shared_attr_{48 * 1024};      ///< RiskRowKernel's dynamic shared memory allowed so far
  bool rows_per_thread_{false};     ///< CRITICALITY_CUDA_RISK: RiskKernel instead of RiskRowKernel
  bool reduce_per_thread_{false};   ///< ReduceKernel instead of ReduceWarpKernel
  bool print_timing_{false};        ///< CRITICALITY_CUDA_TIMING: each chunk's stages on stderr
  double batch_ms_{0.0};            ///< the last MakeBatch's time
  std::vector<double> sums_, col_;  ///< downloads of the last chunk
  std::vector<char> hit_;
  std::vector<std::int16_t> first_;
  BatchHost host_;
  BatchLayout layout_{};
  core::SimulationConfig sim_;
  mutable bool host_stale_{false};
  mutable internal::TrajectoryStore ego_, co_;
  DeviceArray<core::HypothesisSet> d_sets_;
  DeviceArray<int> d_set_base_, d_ego_base_, d_co_base_, d_obj_base_, d_out_base_;
  DeviceArray<long long> d_pair_base_, d_ego_obj_base_;
  DeviceArray<int> d_object_of_, d_co_offset_, d_hist_, d_events_;
  DeviceArray<double> d_co_hl_, d_co_hw_, d_ego_hl_, d_ego_hw_, d_p_co_, d_p_ego_;
  DeviceArray<double> d_ex_, d_ey_, d_eyaw_, d_ec_, d_es_, d_cx_, d_cy_, d_cyaw_, d_cc_, d_cs_;
  DeviceArray<std::int16_t> d_first_;
  DeviceArray<double> d_contrib_, d_mass_, d_ego_col_, d_by_step_, d_by_obj_, d_out_;
  DeviceArray<double> d_ego_bounds_, d_co_bounds_;
  DeviceArray<char> d_ego_hits_;
};

}  // namespace

std::unique_ptr<EstimatorBackend> MakeCudaBackend(int host_threads) {
  return std::make_unique<CudaBackend>(host_threads);
}

}  // namespace criticality::cuda
