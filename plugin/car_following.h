#pragma once
// What a driver is expected to do about the vehicle ahead in its lane: the acceleration that
// the scene hands the estimator as ObjectState::expected_accel_mps2 (the reference hypothesis,
// Params::expected_accel_reference). Plain arithmetic, no SUMO types.
#include <optional>

namespace criticality::plugin {

/** The vehicle ahead as SUMO's getLeader reports it. */
struct Leader {
  double gap_m{0.0};  ///< from the follower's front bumper + its minGap to the leader's back
  double speed_mps{0.0};
  double accel_mps2{0.0};
};

/** The constant acceleration that keeps a follower at `speed_mps` behind its leader: the
 *  smaller of -(v - v_leader)^2 / (2 gap) (the leader keeps its speed: match it within the
 *  gap) and, when the leader brakes, -v^2 / (2 (gap + v_leader^2 / (2 |a_leader|))) (the
 *  leader brakes to a stop at its current deceleration: stop behind it). The gap SUMO reports
 *  already leaves the follower's minGap (its standstill distance) out. Drivers do not brake harder
 * than they normally do to follow (`normal_decel_mps2`): beyond it the situation is not ordinary,
 * and the reference keeps that normal braking (the hypotheses braking harder keep their lower
 *  scores). nullopt when the leader is neither slower nor braking (nothing to react to). */
std::optional<double> CarFollowingAccel(double speed_mps, const Leader& leader,
                                        double normal_decel_mps2);

/** How far ahead a leader matters: the distance in which a closing leader would ask for
 *  1 m/s^2 of braking, at least 20 m and at most 250 m. */
double LeaderLookAhead(double speed_mps);

/** AASHTO (A Policy on Geometric Design of Highways and Streets, 2011): most drivers stopping
 *  for an unexpected object decelerate at more than 4.5 m/s^2 (3.4 m/s^2 is comfortable);
 *  SUMO's passenger cars follow with decel = 4.5 m/s^2. The estimator's decel_score_sigma_mps2
 *  cites the same source. */
constexpr double kNormalFollowingDecelMps2 = 4.5;

}  // namespace criticality::plugin
