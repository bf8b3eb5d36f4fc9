#pragma once
// What a driver is expected to do about the vehicle ahead in its lane: the acceleration that
// the scene hands the estimator as ObjectState::expected_accel_mps2 (the reference hypothesis,
// Params::expected_accel_reference). Plain arithmetic, no SUMO types.
#include <optional>
#include <string>

namespace criticality::plugin {

/** The vehicle ahead as SUMO's getLeader reports it. */
struct Leader {
  double gap_m{0.0};  ///< from the follower's front bumper + its minGap to the leader's back
  double speed_mps{0.0};
  double accel_mps2{0.0};
  std::string id;
  /** The leader must stop this far ahead of its front bumper (its StopLine::distance_m: a red
   *  or yellow light, a stop sign, a yield to an approaching foe), when it has to. */
  std::optional<double> stop_distance_m;
};

/** The constant acceleration that keeps a follower at `speed_mps` behind its leader: the
 *  smaller of -(v - v_leader)^2 / (2 gap) (the leader keeps its speed: match it within the
 *  gap) and -v^2 / (2 (gap + s_leader)), stopping behind the point where the leader stops:
 *  s_leader = v_leader^2 / (2 |a_leader|) when it brakes (at its current deceleration), or
 *  its stop distance when it must stop and can at a normal deceleration (v_leader^2 / (2
 *  stop distance) <= `normal_decel_mps2`), whichever is shorter. The gap SUMO reports
 *  already leaves the follower's minGap (its standstill distance) out. Drivers do not brake harder
 * than they normally do to follow (`normal_decel_mps2`): beyond it the situation is not ordinary,
 * and the reference keeps that normal braking (the hypotheses braking harder keep their lower
 *  scores). nullopt when the leader is neither slower nor braking nor stopping (nothing to
 *  react to). */
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
