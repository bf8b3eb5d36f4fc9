#pragma once
#include "criticality/params.h"
#include "criticality/scene.h"

namespace criticality::internal {

/** Throws InputError naming the first invalid field of the scene ("scene.vehicles[2].length_m =
 *  -1: must be > 0"). Lane geometry is checked when the lanes are fitted. */
void ValidateScene(const Scene& scene, const Params& params);

}  // namespace criticality::internal
