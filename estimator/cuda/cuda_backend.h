#pragma once
// The CUDA backend's factory, as plain C++ (no CUDA types): the Estimator creates it when the
// build has CUDA and a device is usable.
#include <memory>

#include "src/backend.h"

namespace criticality::cuda {

/** host_threads: the threads of the host's share of a batch (each problem's outputs after the
 *  device's risk, and the risk of problems with carriages); >= 1. */
std::unique_ptr<EstimatorBackend> MakeCudaBackend(int host_threads = 1);

}  // namespace criticality::cuda
