#pragma once
// The CUDA backend's factory, as plain C++ (no CUDA types): the Estimator creates it when the
// build has CUDA and a device is usable.
#include <memory>

#include "src/backend.h"

namespace criticality::cuda {

std::unique_ptr<EstimatorBackend> MakeCudaBackend();

}  // namespace criticality::cuda
