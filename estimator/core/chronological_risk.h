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
#include <cstdint>

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

/** Everything risk assessment needs of ONE ego hypothesis, from its row of the pair matrix
 *  (first colliding step of each CO trajectory, 1-based, 0 = none): its colliding CO
 *  trajectories in chronological order (a counting sort by step, stable in the trajectory
 *  index, so ties go by object, then hypothesis), the chronological approximation above, and
 *  how its collision probability splits over steps and objects (not weighted by p_EGO).
 *  Shared by the CPU and CUDA backends.
 *  @param histogram scratch of steps + 1 ints; events, contribution scratch of n_co entries;
 *         hit_mass scratch of n_obj values (all overwritten)
 *  @param by_step out: steps values; by_object out: n_obj values (overwritten)
 *  @param n_events out: the number of colliding CO trajectories
 *  @returns the probability that this ego hypothesis collides. */
CRIT_HD double SplitEgoRisk(const std::int16_t* row, int n_co, int steps, int n_obj,
                            const double* p_co, const int* object_of, int* histogram, int* events,
                            double* contribution, double* hit_mass, double* by_step,
                            double* by_object, int* n_events) {
  for (int n = 0; n <= steps; ++n) histogram[n] = 0;
  for (int j = 0; j < n_co; ++j) {
    if (row[j] > 0) ++histogram[row[j]];
  }
  int total = 0;
  for (int n = 1; n <= steps; ++n) {  // counts -> start offsets
    const int c = histogram[n];
    histogram[n] = total;
    total += c;
  }
  for (int j = 0; j < n_co; ++j) {
    if (row[j] > 0) events[histogram[row[j]]++] = j;
  }
  for (int o = 0; o < n_obj; ++o) {
    hit_mass[o] = 0.0;
    by_object[o] = 0.0;
  }
  for (int n = 0; n < steps; ++n) by_step[n] = 0.0;
  *n_events = total;
  if (total == 0) return 0.0;
  const double p = ChronologicalCollisionProbability(total, events, p_co, object_of, n_obj,
                                                     hit_mass, contribution);
  for (int e = 0; e < total; ++e) {
    by_step[row[events[e]] - 1] += contribution[e];
    by_object[object_of[events[e]]] += contribution[e];
  }
  return p;
}

}  // namespace criticality::core
