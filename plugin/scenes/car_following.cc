#include "plugin/scenes/car_following.h"

#include <algorithm>
#include <cmath>

namespace criticality::plugin {

std::optional<double> CarFollowingAccel(double speed_mps, const Leader& leader,
                                        double normal_decel_mps2) {
  constexpr double kMinGap = 0.1;  // m: at or inside minGap the follower brakes as hard as it may
  const double gap = std::max(leader.gap_m, kMinGap);
  const double closing = speed_mps - leader.speed_mps;
  const double v2 = leader.speed_mps * leader.speed_mps;
  // Where the leader stops, when it does: braking at its current deceleration, or at the line
  // it must stop at when a normal deceleration gets it there.
  std::optional<double> leader_stop;
  if (leader.accel_mps2 < 0.0 && leader.speed_mps > 0.0)
    leader_stop = v2 / (2.0 * -leader.accel_mps2);
  if (leader.stop_distance_m && leader.speed_mps > 0.0) {
    const double d = std::max(*leader.stop_distance_m, 0.0);
    if (v2 <= 2.0 * normal_decel_mps2 * d) leader_stop = std::min(leader_stop.value_or(d), d);
  }
  if (closing <= 0.0 && !leader_stop) return std::nullopt;
  double needed = 0.0;
  // The leader keeps its speed: match it within the gap.
  if (closing > 0.0) needed = -closing * closing / (2.0 * gap);
  // The leader stops: stop behind it.
  if (leader_stop) needed = std::min(needed, -speed_mps * speed_mps / (2.0 * (gap + *leader_stop)));
  return std::max(needed, -normal_decel_mps2);
}

double LeaderLookAhead(double speed_mps) {
  return std::clamp(speed_mps * speed_mps / 2.0, 20.0, 250.0);
}

}  // namespace criticality::plugin
