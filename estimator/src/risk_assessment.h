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

/** The outputs for decisions, from result->ego_collision_probability (every backend fills it)
 *  and which ego hypotheses collide with any CO hypothesis: p_reference, unavoidability, the
 *  count of collision-free ego hypotheses and the escape routes, each re-simulated on the host
 *  to record its manoeuvre over time. */
void FinishDecisionOutputs(const Problem& problem, const Params& params,
                           const std::vector<char>& ego_hit, Result* result);

}  // namespace criticality::internal
