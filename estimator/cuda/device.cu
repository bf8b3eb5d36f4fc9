#include <cuda_runtime.h>

#include <string>

#include "cuda/device.cuh"

namespace criticality::cuda {

void Check(int status, const char* step) {
  if (status != cudaSuccess) {
    throw CudaError(std::string(step) + ": " +
                    cudaGetErrorString(static_cast<cudaError_t>(status)));
  }
}

bool DeviceAvailable(std::string* why) {
  int count = 0;
  const cudaError_t status = cudaGetDeviceCount(&count);
  if (status != cudaSuccess) {
    if (why) *why = std::string("no usable CUDA device: ") + cudaGetErrorString(status);
    return false;
  }
  if (count == 0) {
    if (why) *why = "no CUDA device found";
    return false;
  }
  return true;
}

std::string DeviceDescription() {
  cudaDeviceProp prop{};
  Check(cudaGetDeviceProperties(&prop, 0), "cudaGetDeviceProperties");
  return std::string(prop.name) + ", sm_" + std::to_string(prop.major) + std::to_string(prop.minor);
}

}  // namespace criticality::cuda
