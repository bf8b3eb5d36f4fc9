#pragma once
// The paper's benchmark scenes (Sec. V-B): the ego and 3 (S1) or 10 (S2) other vehicles on a
// straight road with 3.5 m lanes, 20-30 m/s. As in the paper's counts (7 paths per CO), every
// object sees three lanes: its own and one on each side; the ego's are given as lane points,
// each CO carries its own (so a CO in the ego's left lane may move one lane further left,
// which the ego does not see). The paper does not publish the positions; ours put traffic
// close enough that many, but not all, hypothesis combinations collide.
// Used by criticality-bench, the demo and the tests.
#include <string>

#include "criticality/scene.h"

namespace criticality::bench {

constexpr double kLaneWidth = 3.5;

/** The ego's three lanes on a straight road, ego in the middle lane, in its local frame. */
LaneSet StraightThreeLanes(double lane_width = kLaneWidth);

/** S1: ego + 3 COs (one per lane). */
Scene PaperSceneS1();
/** S2: ego + 10 COs. */
Scene PaperSceneS2();
/** The scaling family: the ego and `n` COs on the same road, spread over the three lanes at
 *  20-30 m/s, ahead and behind (n = 3 and 10 are not S1/S2: these are placed by a rule so
 *  that any n works). Cost should grow linearly with n. */
Scene ScalingScene(int n);

/** "S1" or "S2" (case-insensitive); throws InputError naming the accepted values. */
Scene PaperScene(const std::string& name);

}  // namespace criticality::bench
