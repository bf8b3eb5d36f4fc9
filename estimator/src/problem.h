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
  /** The hypothesis sets the backends simulate and check against the ego: first the collision
   *  objects (vehicles in scene order, then pedestrians: cos[o] for o < objects.size()), then
   *  the carriages of long vehicles (cos[objects.size() + c], a box of object
   *  carriage_object[c]'s body), which FoldCarriages folds into their vehicle's columns. */
  std::vector<core::HypothesisSet> cos;
  /** co_offset[s] = first global CO trajectory of set s; co_offset.back() = total. */
  std::vector<int> co_offset;
  /** Set index of every global CO trajectory (an object's index for the objects' columns). */
  std::vector<int> co_object_of;
  /** p_EGO,i and p_CO,j (L1-normalised per set; a carriage's are never used). */
  std::vector<double> ego_probability;
  std::vector<double> co_probability;
  /** Per CO: id, kind, lane association (contribution filled by the risk assessment). */
  std::vector<ObjectResult> objects;
  /** The object (a vehicle) whose body each carriage set belongs to, in set order. */
  std::vector<int> carriage_object;
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
  /** Every column of the backends' pair matrix (objects' and carriages'). */
  int CoTrajectories() const { return counts.co_trajectories; }
  int Steps() const { return sim.n_steps; }
  bool HasCarriages() const { return !carriage_object.empty(); }
  /** The objects' columns: the pair matrix after FoldCarriages. */
  int ObjectTrajectories() const { return co_offset[objects.size()]; }
  /** The trajectory of carriage set `s` (an index into cos) that belongs to hypothesis t of
   *  its vehicle: the same profile and path, or the same profile on its only path. */
  int CarriageTrajectory(int s, int t) const {
    const core::HypothesisSet& vehicle = cos[carriage_object[s - objects.size()]];
    const core::HypothesisSet& c = cos[s];
    const int profile = t / vehicle.n_paths, path = t % vehicle.n_paths;
    return profile * c.n_paths + (c.n_paths == 1 ? 0 : path);
  }
};

/** Validates the scene and builds the problem.
 *  @throws InputError for an invalid scene, WorkloadError when the estimate would need more
 *  than params.max_memory_bytes. */
Problem BuildProblem(const Scene& scene, const Params& params);

/** The pair matrix of the objects alone (ego-major, problem.ObjectTrajectories() columns)
 *  from the backends' one over every set (problem.CoTrajectories() columns): each object
 *  column's first colliding step is the earliest of the vehicle's own box and its carriages'
 *  for the same hypothesis (0 when none collides). */
std::vector<std::int16_t> FoldCarriages(const Problem& problem,
                                        const std::vector<std::int16_t>& first_step);

/** `problem` without its carriage sets: the objects alone, as the risk assessment sees them
 *  (with FoldCarriages' pair matrix). */
Problem ObjectProblem(const Problem& problem);

/** The work counts a result reports: co_trajectories the objects' hypotheses (the columns of
 *  Result::first_collision_step), carriage_trajectories the carriages', pose_combinations
 *  every pose pair checked. */
WorkCounts ResultCounts(const Problem& problem);

/** Bytes an estimate of this size needs (trajectories with cached cos/sin, pair matrix, risk
 *  scratch). */
std::uint64_t WorkloadBytes(std::uint64_t ego_trajectories, std::uint64_t co_trajectories,
                            std::uint64_t steps, std::uint64_t objects);

}  // namespace criticality::internal
