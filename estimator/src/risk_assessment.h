#pragma once
// Risk assessment (paper Sec. IV-D), host side: from the pair matrix (first colliding step of
// every ego x CO trajectory pair) and the hypothesis probabilities to p_cra, per-object
// contributions, the first-collision-time distribution and escape routes.
#include <cstdint>
#include <vector>

#include "criticality/params.h"
#include "criticality/result.h"
#include "src/problem.h"

namespace criticality::internal {

/** @param first_step ego-major pair matrix: first_step[i * co_trajectories + j] = first
 *  colliding step (1..steps) of ego trajectory i with CO trajectory j, 0 when none.
 *  Per-ego work runs on `threads` threads; sums are taken in ego order (deterministic). */
void AssessRisk(const Problem& problem, const Params& params, const std::int16_t* first_step,
                int threads, Result* result);

/** AssessRisk of a problem whose vehicles may have carriages: with carriages, `first_step`
 *  (the backends' pair matrix over every set) is folded into the objects' columns first
 *  (FoldCarriages) and replaced by the folded matrix, and the objects alone are assessed
 *  (ObjectProblem); without, it is AssessRisk on `first_step` as it is. */
void AssessBodies(const Problem& problem, const Params& params,
                  std::vector<std::int16_t>* first_step, int threads, Result* result);

/** The outputs for decisions, from result->ego_collision_probability (every backend fills it)
 *  and which ego hypotheses collide with any CO hypothesis: p_reference, unavoidability, the
 *  count of collision-free ego hypotheses and the escape routes, each re-simulated on the host
 *  to record its manoeuvre over time. Rounds p_collision and each ego hypothesis' collision
 *  probability that a sum put a few ulps above 1 to 1. */
void FinishDecisionOutputs(const Problem& problem, const Params& params,
                           const std::vector<char>& ego_hit, Result* result);

}  // namespace criticality::internal
