#pragma once
// Scene building, independent of SUMO: an ego's snapshot and those of the objects around it
// become the estimator's Scene. Objects whose values the estimator cannot use (NaN or infinite
// position, heading or speed, as SUMO 1.15 reports some persons on walking areas; sizes that are
// not positive) are left out, never sent on: the caller counts them and reports them once.
#include <string>
#include <vector>

#include "criticality/scene.h"
#include "plugin/scenes/object_snapshot.h"

namespace criticality::plugin {

/** What makes `o` unusable ("state.x_m = nan"), or "" when the estimator can use it. */
std::string InvalidValues(const ObjectSnapshot& o);

struct LeftOutObject {
  std::string id;
  bool person{false};
  std::string why;  ///< InvalidValues()
};

/** The scene of `ego` (which must be valid): every valid object of `nearby` with the centre of
 *  a box of its body within `range_m` of the ego's, vehicles and pedestrians each in ID order (so
 *  that a scene does not depend on how SUMO listed them); vehicles that are no road user or
 *  parked off the road are nobody's obstacle and left out. Invalid objects within reach of the
 *  test are appended to `left_out`. */
Scene BuildScene(const ObjectSnapshot& ego, const std::vector<const ObjectSnapshot*>& nearby,
                 double range_m, std::vector<LeftOutObject>* left_out);

}  // namespace criticality::plugin
