#include <cuda_runtime.h>

#include "cuda/core_kernels.cuh"
#include "cuda/device.cuh"

namespace criticality::cuda {
namespace {

__global__ void OverlapKernel(const core::OrientedBox<double>* a,
                              const core::OrientedBox<double>* b, int n, std::uint8_t* out) {
  const int k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k < n) out[k] = core::BoxesOverlap(a[k], b[k]) ? 1 : 0;
}

__global__ void SimulateKernel(core::HypothesisSet h, core::SimulationConfig cfg, double* x,
                               double* y, double* yaw) {
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t >= h.Trajectories()) return;
  const size_t at = static_cast<size_t>(t) * cfg.n_steps;
  core::SimulateHypothesis(h, cfg, t / h.n_paths, t % h.n_paths, x + at, y + at, yaw + at);
}

// A device buffer freed on scope exit (plain cudaMalloc).
template <typename T>
struct DeviceBuffer {
  T* ptr{nullptr};
  explicit DeviceBuffer(size_t n) { Check(cudaMalloc(&ptr, n * sizeof(T) + 1), "cudaMalloc"); }
  ~DeviceBuffer() { cudaFree(ptr); }
  DeviceBuffer(const DeviceBuffer&) = delete;
  DeviceBuffer& operator=(const DeviceBuffer&) = delete;
};

}  // namespace

std::vector<std::uint8_t> BoxesOverlapOnDevice(const std::vector<core::OrientedBox<double>>& a,
                                               const std::vector<core::OrientedBox<double>>& b) {
  const int n = static_cast<int>(a.size());
  DeviceBuffer<core::OrientedBox<double>> d_a(n), d_b(n);
  DeviceBuffer<std::uint8_t> d_out(n);
  Check(cudaMemcpy(d_a.ptr, a.data(), n * sizeof(a[0]), cudaMemcpyHostToDevice), "copy boxes a");
  Check(cudaMemcpy(d_b.ptr, b.data(), n * sizeof(b[0]), cudaMemcpyHostToDevice), "copy boxes b");
  OverlapKernel<<<(n + 255) / 256, 256>>>(d_a.ptr, d_b.ptr, n, d_out.ptr);
  Check(cudaGetLastError(), "after overlap kernel launch");
  std::vector<std::uint8_t> out(n);
  Check(cudaMemcpy(out.data(), d_out.ptr, n, cudaMemcpyDeviceToHost), "after overlap kernel");
  return out;
}

void SimulateOnDevice(const core::HypothesisSet& h, const core::SimulationConfig& cfg,
                      std::vector<double>* x, std::vector<double>* y, std::vector<double>* yaw) {
  const int n_traj = h.Trajectories();
  const size_t n = static_cast<size_t>(n_traj) * cfg.n_steps;
  DeviceBuffer<double> d_x(n), d_y(n), d_yaw(n);
  SimulateKernel<<<(n_traj + 127) / 128, 128>>>(h, cfg, d_x.ptr, d_y.ptr, d_yaw.ptr);
  Check(cudaGetLastError(), "after simulate kernel launch");
  x->resize(n);
  y->resize(n);
  yaw->resize(n);
  Check(cudaMemcpy(x->data(), d_x.ptr, n * sizeof(double), cudaMemcpyDeviceToHost),
        "after simulate kernel (x)");
  Check(cudaMemcpy(y->data(), d_y.ptr, n * sizeof(double), cudaMemcpyDeviceToHost), "copy y");
  Check(cudaMemcpy(yaw->data(), d_yaw.ptr, n * sizeof(double), cudaMemcpyDeviceToHost), "copy yaw");
}

}  // namespace criticality::cuda
