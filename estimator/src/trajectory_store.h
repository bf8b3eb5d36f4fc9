#pragma once
// Trajectories as structs of arrays (DESIGN.md): x[], y[], yaw[] of trajectory t at step n
// (n = 0 is the first PREDICTED pose, time step_s) at [t * steps + n].
#include <cstddef>
#include <vector>

namespace criticality::internal {

struct TrajectoryStore {
  int steps{0};
  int trajectories{0};
  std::vector<double> x, y, yaw;

  void Resize(int n_trajectories, int n_steps) {
    trajectories = n_trajectories;
    steps = n_steps;
    const size_t n = static_cast<size_t>(n_trajectories) * n_steps;
    x.resize(n);
    y.resize(n);
    yaw.resize(n);
  }
  size_t Offset(int t) const { return static_cast<size_t>(t) * steps; }
};

}  // namespace criticality::internal
