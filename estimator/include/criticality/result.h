#pragma once
/** @file The output of one estimate (paper Sec. IV-D). */
#include <cstdint>
#include <string>
#include <vector>

namespace criticality {

/** What kind of object a trajectory belongs to. */
enum class ObjectKind { kEgo, kVehicle, kPedestrian };

/** Per collision object (other vehicle or pedestrian). */
struct ObjectResult {
  std::string id;
  ObjectKind kind{ObjectKind::kVehicle};
  int first_trajectory{0};  ///< index of its first trajectory among all CO trajectories
  int trajectories{0};      ///< its number of hypotheses
  /** Ego lane its centre of gravity lies in (vehicles driving along the ego's lanes):
   *  -1 right, 0 the ego's, +1 left; 2 = none (outside, crossing, or a pedestrian). */
  int lane{2};
  /** Its share of p_collision: sum over ego hypotheses of p_ego * (chronologically scaled
   *  probability that this object is the first one hit). The shares add up to p_collision. */
  double contribution{0.0};
  /** Left out by the exact reach shortcut (EstimatorOptions::reach_shortcut): none of its
   *  hypotheses can come near any ego hypothesis, so it has no colliding pair. It stays listed,
   *  with contribution 0 and no trajectories (trajectories = 0). */
  bool out_of_reach{false};
};

/** A collision-free ego hypothesis (paper Sec. V-A, "escape routes"). */
struct EscapeRoute {
  int ego_trajectory{0};           ///< index = profile * paths + path
  int profile{0};                  ///< index into the ego's profiles
  double profile_slip{0.0};        ///< the profile's target longitudinal slip
  double profile_accel_mps2{0.0};  ///< the steady deceleration/acceleration that slip gives
  std::vector<int> sections;       ///< lateral sample index per sample instant (right to left)
  double probability{0.0};         ///< occurrence probability p_EGO,i
};

/** Work sizes, so that figures compare with the paper's (DESIGN.md "Counting"). */
struct WorkCounts {
  int time_steps{0};
  int ego_trajectories{0};             ///< h_acc * h_EGO,str
  int co_trajectories{0};              ///< sum over COs of their hypotheses
  std::uint64_t pose_combinations{0};  ///< co_trajectories * ego_trajectories * time_steps
};

/** Wall time of each module, milliseconds. */
struct ModuleTimes {
  double street_ms{0.0};  ///< street data processing + hypothesis set-up + scoring
  double trajectory_ms{0.0};
  double collision_ms{0.0};
  double risk_ms{0.0};
  double total_ms{0.0};
};

struct Result {
  /** p_cra: probability that the scene leads to a collision of the ego (paper Sec. IV-D), with
   *  the chronological approximation of conditional probabilities (Sec. IV-D-2). */
  double p_collision{0.0};
  std::vector<ObjectResult> objects;
  /** first_collision_pmf[n]: probability that the ego's first collision happens at predicted
   *  step n+1, i.e. at time (n+1)*step_s. Sums to p_collision. */
  std::vector<double> first_collision_pmf;
  /** Collision-free ego hypotheses, most probable first (at most Params::max_escape_routes). */
  std::vector<EscapeRoute> escape_routes;
  int collision_free_ego_trajectories{0};
  /** Occurrence probability of every ego hypothesis and, for each, the probability that it
   *  collides (chronologically scaled), indexed by ego trajectory. */
  std::vector<double> ego_probability;
  std::vector<double> ego_collision_probability;
  /** The pair matrix, kept when EstimatorOptions::keep_pair_matrix: first colliding step
   *  (1..time_steps) of ego trajectory i against CO trajectory j at [i * co_trajectories + j],
   *  0 when the pair never collides. */
  std::vector<std::int16_t> first_collision_step;
  WorkCounts counts;
  ModuleTimes times;
};

}  // namespace criticality
