#pragma once
// Host entry points that run core/ functions on the device, one thread per element. They exist
// so that tests run the same inputs through host and device code and compare.
#include <cstdint>
#include <vector>

#include "core/hypothesis_set.h"
#include "core/oriented_box.h"
#include "core/trajectory_generation.h"

namespace criticality::cuda {

/** out[k] = BoxesOverlap(a[k], b[k]) computed on the device. */
std::vector<std::uint8_t> BoxesOverlapOnDevice(const std::vector<core::OrientedBox<double>>& a,
                                               const std::vector<core::OrientedBox<double>>& b);

/** Every hypothesis of `h` simulated on the device; poses at [t * n_steps + n]. */
void SimulateOnDevice(const core::HypothesisSet& h, const core::SimulationConfig& cfg,
                      std::vector<double>* x, std::vector<double>* y, std::vector<double>* yaw);

}  // namespace criticality::cuda
