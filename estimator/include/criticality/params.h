#pragma once
/** @file
 * Every tunable of the algorithm, with its default and where the value comes from.
 * "paper" = Sánchez Morales et al., IV 2019 (shared/reference). Where the paper gives no value,
 * the comment names the source we used, or says "project choice" and which test shows its effect.
 */
#include <cstdint>
#include <vector>

namespace criticality {

struct Params {
  // --- Horizon (paper Sec. IV-C and V-B: 2 s predicted with 20 ms resolution = 100 steps) ---
  double horizon_s{2.0};
  double step_s{0.02};

  // --- Longitudinal hypotheses (paper Sec. IV-B-2a) ---
  /** Acceleration / slip profiles per object, h_acc. Paper Sec. V-B: 6 (or 5). At least 3
   *  (maximum, minimum and zero are always sampled). */
  int profiles{6};
  /** One-track (other vehicles) acceleration range, paper: -9.7..9.7 m/s^2 (about 1 g). */
  double vehicle_accel_min_mps2{-9.7};
  double vehicle_accel_max_mps2{9.7};
  /** Two-track (ego) longitudinal slip range, paper: -0.1..0.1. */
  double ego_slip_min{-0.1};
  double ego_slip_max{0.1};
  /** Actuator + driver latency before a profile starts to act. DESIGN.md: brake latency about
   *  0.15-0.3 s; we take the middle. */
  double latency_s{0.2};
  /** Build-up of acceleration after the latency (jerk limit). DESIGN.md: 20-50 m/s^3 in an
   *  emergency. The ego's slip ramps at the equivalent rate:
   *  ego_slip_max * jerk_mps3 / vehicle_accel_max_mps2 per second. */
  double jerk_mps3{30.0};

  // --- Lateral hypotheses: paths (paper Sec. IV-B-2b) ---
  /** Instants at which the lanes are sampled; each opens a new path section. Paper: 1.0, 1.5,
   *  2.0 s. 1 to 4 strictly increasing positive values. */
  std::vector<double> path_sample_times_s{1.0, 1.5, 2.0};
  /** Samples across the own lane and across each neighbouring lane (paper: 3 and 2), equally
   *  distributed over the lane width. With all three lanes: 7 samples, so 7^3 = 343 ego paths
   *  (every combination of sections) and 7 paths per other vehicle (no combination). */
  int own_lane_samples{3};
  int neighbour_lane_samples{2};

  // --- Pedestrians (paper Sec. IV-B-3) ---
  /** Headings sampled over 0..360 deg, relative to the current heading. Paper: as many as the
   *  complete paths of a CO with three lanes (7). */
  int pedestrian_headings{7};
  /** Acceleration samples (as many as `profiles`) equally distributed over -12..12 m/s^2. */
  double pedestrian_accel_min_mps2{-12.0};
  double pedestrian_accel_max_mps2{12.0};
  /** Speed limit, paper: 2.7 m/s (slow to running, not sprinting; Zebala et al. 2012). */
  double pedestrian_max_speed_mps{2.7};

  // --- Lateral controller (paper Sec. IV-B-2b) ---
  /** Steering-angle limit at the front wheels. DESIGN.md: at most about 0.5 rad. */
  double max_steer_rad{0.5};
  /** Steering-rate limit at the wheels. Forkenbrock & Elsasser (NHTSA 2005): a fast human
   *  driver turns the wheel several hundred deg/s; with a ratio of 15-16 that is 0.7-1.1 rad/s
   *  at the wheels. We take 0.9 rad/s. */
  double max_steer_rate_radps{0.9};
  /** The paper's controller acts on a predicted position whose prediction time adapts to speed
   *  (values not given). Project choice: t_p = preview_s_per_mps * v clamped to
   *  [preview_min_s, preview_max_s], tuned by simulation so that a 3.5 m lane change reaches
   *  90 % in about 1.2 s at 20-40 m/s with at most a few percent overshoot, and stays damped
   *  at 5 m/s (tests/estimator/core/lateral_controller_test.cc). */
  double preview_s_per_mps{0.008};
  double preview_min_s{0.05};
  double preview_max_s{0.4};

  // --- Vehicle models ---
  /** Below this speed the one- and two-track models (singular in 1/v) are replaced by the
   *  kinematic single-track model. The seam is raised per vehicle, when needed, to the speed at
   *  which explicit Euler with step_s stays stable: v >= stability_factor * step_s *
   *  max((c_f + c_r)/m, (c_f l_f^2 + c_r l_r^2)/I_z). Project choice, tested at the seam. */
  double kinematic_below_mps{2.0};
  double euler_stability_factor{1.5};
  /** Tyre-road friction coefficient, dry asphalt about 1.0 (DESIGN.md; the paper's +-9.7 m/s^2
   *  range is about 1 g). */
  double friction{1.0};

  // --- Street data (paper Sec. IV-A) ---
  /** Width of the virtual own lane when the sensors deliver none. RAA (FGSV 2008): 3.5-3.75 m. */
  double virtual_lane_width_m{3.5};

  // --- Scoring (paper Sec. IV-D-1): n_h = (w_acc n_acc + w_str d_str) / (c_com c_cou) ---
  /** Weights. The paper gives none ("domain knowledge"); equal weights are the neutral choice. */
  double w_acc{1.0};
  double w_str{1.0};
  /** n_acc = 1 / (1 + |target - current| / (accel_score_scale * range)), range = the profile
   *  range's maximum. Project choice: a profile at the range limit scores about 1/4 of the
   *  current-acceleration one; test: scoring_test.cc. */
  double accel_score_scale{0.3};
  /** d_str = 1 / (1 + mean lateral offset of the path's samples from the own-lane centre /
   *  path_score_scale_m). Project choice: a full lane change (3.5 m) scores about 1/3. For
   *  pedestrians the heading change replaces the offset, scaled by heading_score_scale_rad. */
  double path_score_scale_m{1.5};
  double heading_score_scale_rad{1.0};
  /** c_com = 1 + complexity_penalty * (number of section changes along the path). Penalises
   *  weaving ego paths (own -> left -> own). Project choice. */
  double complexity_penalty{0.5};
  /** c_cou applied to a path with any section on a counter-traffic lane. Project choice: entering
   *  oncoming traffic is rarer than a lane change; test: scoring_test.cc. */
  double counter_traffic_penalty{4.0};

  // --- Outputs and limits ---
  /** How many escape routes (collision-free ego hypotheses, most probable first) to return. */
  int max_escape_routes{10};
  /** Upper bound on the memory one estimate may use (trajectories and the pair matrix). */
  std::uint64_t max_memory_bytes{std::uint64_t{4} << 30};

  /** Number of predicted time steps: round(horizon_s / step_s). */
  int TimeSteps() const;
  /** Number of lateral samples with all three lanes present (7 with the defaults). */
  int LateralSamplesThreeLanes() const { return own_lane_samples + 2 * neighbour_lane_samples; }
};

/** Throws InputError naming the first invalid field and its value. */
void ValidateParams(const Params& params);

}  // namespace criticality
