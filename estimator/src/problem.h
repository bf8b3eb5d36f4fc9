#pragma once
// The estimate as data: every object's hypothesis set with the occurrence probability of each
// hypothesis. Built on the host from a Scene (street data processing + hypothesis set-up +
// scoring); every backend consumes it.
#include <cstdint>
#include <vector>

#include "core/hypothesis_set.h"
#include "core/trajectory_generation.h"
#include "criticality/params.h"
#include "criticality/result.h"
#include "criticality/scene.h"

namespace criticality::internal {

struct Problem {
  core::SimulationConfig sim;
  core::HypothesisSet ego;
  /** Collision objects: vehicles in scene order, then pedestrians. */
  std::vector<core::HypothesisSet> cos;
  /** co_offset[o] = first global CO trajectory of object o; co_offset.back() = total. */
  std::vector<int> co_offset;
  /** Object index of every global CO trajectory. */
  std::vector<int> co_object_of;
  /** p_EGO,i and p_CO,j (L1-normalised per object). */
  std::vector<double> ego_probability;
  std::vector<double> co_probability;
  /** Per CO: id, kind, lane association (contribution filled by the risk assessment). */
  std::vector<ObjectResult> objects;
  /** The ego's profiles as a driver reads them: target acceleration (m/s^2) and longitudinal
   *  slip of each; the ego lane (-1 right, 0 own, +1 left) of each lateral sample; its own
   *  lane's centre in its local frame; its most probable hypothesis (the first maximum of
   *  ego_probability: the reference). */
  std::vector<double> ego_profile_accel;
  std::vector<double> ego_profile_slip;
  std::vector<int> ego_sample_lane;
  core::Parabola ego_lane_centre;
  int ego_reference_trajectory{0};
  WorkCounts counts;

  int EgoTrajectories() const { return counts.ego_trajectories; }
  int CoTrajectories() const { return counts.co_trajectories; }
  int Steps() const { return sim.n_steps; }
};

/** Validates the scene and builds the problem.
 *  @throws InputError for an invalid scene, WorkloadError when the estimate would need more
 *  than params.max_memory_bytes. */
Problem BuildProblem(const Scene& scene, const Params& params);

/** Bytes an estimate of this size needs (trajectories with cached cos/sin, pair matrix, risk
 *  scratch). */
std::uint64_t WorkloadBytes(std::uint64_t ego_trajectories, std::uint64_t co_trajectories,
                            std::uint64_t steps, std::uint64_t objects);

}  // namespace criticality::internal
