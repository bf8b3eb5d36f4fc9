#pragma once
// What each vehicle's driver is expected to do next, from the step's snapshots: the
// car-following acceleration behind its leader (car_following.h), handed to the estimator as
// ObjectState::expected_accel_mps2 (the reference hypothesis, Params::expected_accel_reference).
#include <vector>

#include "plugin/scenes/object_snapshot.h"

namespace criticality::plugin {

/** Sets the expected acceleration of every vehicle in `objects` that has a leader:
 *  CarFollowingAccel, with the leader's stop distance when the leader is among `objects` and
 *  has a stop line, so that a follower behind a leader that must stop (a red light, a yield
 *  line) is expected to stop behind it although the leader has not braked yet. Runs once all
 *  of a step's snapshots are read. */
void ExpectCarFollowing(std::vector<ObjectSnapshot>* objects, double normal_decel_mps2);

}  // namespace criticality::plugin
