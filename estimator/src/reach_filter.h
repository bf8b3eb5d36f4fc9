#pragma once
// The exact reach shortcut (EstimatorOptions::reach_shortcut): a collision object none of whose
// hypotheses ever comes within reach of any ego hypothesis cannot have a colliding pair, so
// leaving it out changes nothing in the result (p_cra, the other objects' contributions, the
// pair matrix of the kept objects, escape routes). An ego with no object left gets its result
// without generating a single trajectory.
//
// The ego's reach is bounded from the motion model, not simulated (the ego's 2,058 hypotheses
// are what the shortcut saves): per Euler step (core/euler_integration.h) the centre moves by
//   |dp| <= v_n tau + |(a_x, a_y)_n| tau^2 / 2,
// the speed grows by at most mu g tau (two-track: the four tyre forces stay within their
// friction circles, sum F_z = m g; kinematic model: F_x <= mu F_z), and the acceleration vector
// is at most mu g in the two-track model and sqrt((mu g)^2 + (v_s^2 tan(delta_max) / L)^2) in
// the kinematic model (used only below the seam speed v_s; steering is clamped to delta_max);
// the first step uses the scene's current acceleration and yaw rate. The collision objects'
// hypotheses are simulated (they are few, and the one-track model has no lateral grip limit to
// bound them by), unless the object starts within the ego's final reach, which keeps it at once.
// Two boxes can only overlap when their centres are at most the sum of their bounding radii
// apart (core/oriented_box.h). tests/estimator/reach_filter_test.cc checks the bound against
// simulated ego hypotheses and the shortcut against the full estimate.
#include <vector>

#include "src/problem.h"

namespace criticality::internal {

class ObjectPathsCache;

/** bound[n] >= |centre after n steps - centre now| for every hypothesis of `ego`
 *  (n = 0..sim.n_steps; bound[0] = 0). */
std::vector<double> EgoReachBound(const core::HypothesisSet& ego,
                                  const core::SimulationConfig& sim);

/** The same bound from a state the simulation of `ego` reached (speed v, acceleration vector of
 *  length `accel`) for `steps` more steps: bound[m] >= |stored pose m steps on - stored pose
 *  at that state|, m = 0..steps, whatever hypothesis continues from it (the stored poses: the
 *  shifts of HypothesisSet::position_lead and body_on_path included). */
std::vector<double> EgoReachBoundFrom(const core::HypothesisSet& ego,
                                      const core::SimulationConfig& sim, double v, double accel,
                                      int steps);

/** EgoReachBoundFrom(...)[steps] in closed form (the sums of its steps), for the CPU backend's
 *  per-node test; at least that value up to rounding (callers add a margin). */
double EgoReachAfter(const core::HypothesisSet& ego, const core::SimulationConfig& sim, double v,
                     double accel, int steps);

/** out[o] = 1 when collision object o of `problem` (o < problem.objects.size()) can meet no
 *  ego hypothesis: neither its own box nor any of its carriages' boxes. `simd`: the objects'
 *  paths of one profile simulated together in SIMD lanes where they apply (cpu/sibling_steps.h,
 *  EstimatorOptions::simd), else one by one with the scalar step. `cache` (with simd): a set's
 *  paths in SIMD lanes are taken from the batch's cache where a scene stored them, else
 *  simulated whole and stored there (the CPU backend then copies them). */
std::vector<char> OutOfReach(const Problem& problem, bool simd = false,
                             ObjectPathsCache* cache = nullptr);

/** `problem` without the objects marked in `drop` (their trajectories, their carriages',
 *  probabilities and results); kept objects and carriages keep their order. */
Problem WithoutObjects(const Problem& problem, const std::vector<char>& drop);

}  // namespace criticality::internal
