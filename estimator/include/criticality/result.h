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

/** An ego hypothesis offered as an escape route (paper Sec. V-A): what the driver would do and
 *  how likely it is to collide. Result::escape_routes ranks them by collision probability
 *  (lowest first), then by their own probability (highest first). */
struct EscapeRoute {
  int ego_trajectory{0};           ///< index = profile * paths + path
  int profile{0};                  ///< index into the ego's profiles
  double profile_slip{0.0};        ///< the profile's longitudinal slip (steady state)
  double profile_accel_mps2{0.0};  ///< the profile's target acceleration (after latency, ramp)
  /** Lateral sample index per sample instant (right to left: with all three lanes 0-1 the
   *  right lane, 2-4 the own lane, 5-6 the left lane). */
  std::vector<int> sections;
  /** The lane each sample instant's section lies in: -1 right, 0 own, +1 left. */
  std::vector<int> target_lanes;
  double probability{0.0};            ///< occurrence probability p_EGO,i
  double collision_probability{0.0};  ///< probability that it collides (chronological approx.)
  /** The manoeuvre over time, re-simulated: entry n is predicted step n + 1, time (n + 1)
   *  step_s. Speed, longitudinal and lateral acceleration in the vehicle frame, front-wheel
   *  steering angle (positive = left), lateral offset from the centre of the ego's own lane
   *  (positive = left, in the ego's frame at t = 0), and the pose in the scene frame. */
  std::vector<double> time_s;
  std::vector<double> speed_mps;
  std::vector<double> accel_mps2;
  std::vector<double> lateral_accel_mps2;
  std::vector<double> steer_rad;
  std::vector<double> lateral_offset_m;
  std::vector<double> x_m;
  std::vector<double> y_m;
  std::vector<double> yaw_rad;
};

/** Work sizes, so that figures compare with the paper's (DESIGN.md "Counting"). */
struct WorkCounts {
  int time_steps{0};
  int ego_trajectories{0};  ///< h_acc * h_EGO,str
  int co_trajectories{0};   ///< sum over COs of their hypotheses (the pair matrix's columns)
  /** Trajectories simulated for the carriages of long vehicles (Vehicle::carriages), checked
   *  like the COs' and folded into their vehicle's columns. */
  int carriage_trajectories{0};
  /** (co_trajectories + carriage_trajectories) * ego_trajectories * time_steps */
  std::uint64_t pose_combinations{0};
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
   *  the chronological approximation of conditional probabilities (Sec. IV-D-2). Averages
   *  over the ego's own hypotheses too, so it includes the ego's unlikely manoeuvres. */
  double p_collision{0.0};
  /** The collision probability if the ego keeps its reference hypothesis: the most probable
   *  one (keep the current acceleration, follow the own lane's centre), index
   *  reference_ego_trajectory. What happens if the driver does nothing different. */
  double p_reference{0.0};
  int reference_ego_trajectory{0};
  /** The smallest collision probability over all ego hypotheses: 1 = every ego hypothesis
   *  collides (the paper's "unavoidable collision"); 0 = at least one is collision-free. */
  double unavoidability{0.0};
  std::vector<ObjectResult> objects;
  /** first_collision_pmf[n]: probability that the ego's first collision happens at predicted
   *  step n+1, i.e. at time (n+1)*step_s. Sums to p_collision. */
  std::vector<double> first_collision_pmf;
  /** The ego hypotheses with the lowest collision probability, ties by their own probability
   *  (highest first), at most Params::max_escape_routes; never empty when that is > 0 (when
   *  every hypothesis collides, the least colliding ones). */
  std::vector<EscapeRoute> escape_routes;
  /** Ego hypotheses that collide with no CO hypothesis at all. */
  int collision_free_ego_trajectories{0};
  /** Occurrence probability of every ego hypothesis and, for each, the probability that it
   *  collides (chronologically scaled), indexed by ego trajectory. */
  std::vector<double> ego_probability;
  std::vector<double> ego_collision_probability;
  /** The pair matrix, kept when EstimatorOptions::keep_pair_matrix: first colliding step
   *  (1..time_steps) of ego trajectory i against CO trajectory j at [i * co_trajectories + j],
   *  0 when the pair never collides. */
  std::vector<std::int16_t> first_collision_step;
  /** True when the exact reach shortcut (EstimatorOptions::reach_shortcut) answered this
   *  estimate without generating hypothesis trajectories or recognising collisions: no
   *  collision object was left in reach (every one is out_of_reach, or there is none), so
   *  p_collision is 0 (only the escape routes' manoeuvres were simulated). Always false with
   *  the shortcut off. */
  bool answered_by_reach_shortcut{false};
  WorkCounts counts;
  ModuleTimes times;
};

/** The object with the largest share of p_collision (ObjectResult::contribution), the first of
 *  equal ones; nullptr when none has any. */
inline const ObjectResult* MainObject(const Result& r) {
  const ObjectResult* main = nullptr;
  for (const ObjectResult& o : r.objects) {
    if (o.contribution > 0.0 && (!main || o.contribution > main->contribution)) main = &o;
  }
  return main;
}

}  // namespace criticality
