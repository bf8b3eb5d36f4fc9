#pragma once
// CUDA device discovery and error checking. Every CUDA call's status becomes an exception naming
// the step that failed.
#include <stdexcept>
#include <string>

namespace criticality::cuda {

/** Thrown for any CUDA failure; the message names the step ("after overlap kernel"). */
class CudaError : public std::runtime_error {
 public:
  explicit CudaError(const std::string& what) : std::runtime_error(what) {}
};

/** True when a CUDA device can be used; otherwise `why` says what is missing. */
bool DeviceAvailable(std::string* why);

/** Name and compute capability of device 0 ("NVIDIA H100 80GB HBM3, sm_90"). */
std::string DeviceDescription();

/** Throws CudaError("<step>: <cuda error string>") when `status` is not cudaSuccess. */
void Check(int status, const char* step);

}  // namespace criticality::cuda
