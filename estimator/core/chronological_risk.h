#pragma once
// Risk assessment with the paper's chronological approximation of conditional probabilities
// (Sec. IV-D-2), for ONE ego hypothesis.
//
// Given the CO trajectories that collide with this ego trajectory, in chronological order of
// their first colliding step (ties: by CO trajectory index, i.e. by object, then hypothesis),
// each collision event (object o, trajectory j) contributes
//     p_CO,j * prod_{o' != o} (1 - M_o')
// where M_o' is the probability mass of object o''s trajectories that hit this ego trajectory
// EARLIER. So the first collision keeps its probability, later ones are scaled by the
// no-collision probability of every other object before them:
//     P(B and not A) ~ P(not A) P(B),  P(C and not B and not A) ~ P(not A) P(not B) P(C).
// Trajectories of the same object exclude each other (an object follows one), so they are not
// scaled by each other. The contributions add up to 1 - prod_o (1 - q_o), q_o = an object's
// colliding mass: <= 1, and exactly 1 when every hypothesis collides.
#include "core/hd.h"

namespace criticality::core {

/** @param n_events number of colliding CO trajectories, in chronological order
 *  @param event_traj their CO trajectory indices
 *  @param p_co occurrence probability of every CO trajectory
 *  @param object_of object index (0..n_objects-1) of every CO trajectory
 *  @param hit_mass scratch of n_objects values, zero on entry
 *  @param contribution out: the scaled probability of each event (may be null)
 *  @returns the probability that this ego hypothesis collides. */
CRIT_HD double ChronologicalCollisionProbability(int n_events, const int* event_traj,
                                                 const double* p_co, const int* object_of,
                                                 int n_objects, double* hit_mass,
                                                 double* contribution) {
  double total = 0.0;
  for (int e = 0; e < n_events; ++e) {
    const int j = event_traj[e];
    const int o = object_of[j];
    double survive_others = 1.0;
    for (int k = 0; k < n_objects; ++k) {
      if (k != o) survive_others *= 1.0 - hit_mass[k];
    }
    const double c = p_co[j] * survive_others;
    hit_mass[o] += p_co[j];
    if (contribution) contribution[e] = c;
    total += c;
  }
  return total;
}

}  // namespace criticality::core
