#pragma once
#include <cstddef>
#include <string>

#include "criticality/params.h"
#include "criticality/scene.h"

namespace criticality::internal {

/** How error messages name an object of a scene list: by index and, when it has one, id:
 *  "scene.vehicles[2] ('train7')" (fields follow: "scene.vehicles[2] ('train7').length_m"). */
std::string ObjectName(const std::string& list, size_t index, const std::string& id);

/** Throws InputError naming the first invalid field of the scene and the object it belongs to
 *  ("scene.vehicles[2] ('train7').length_m = 500: must be <= 400 m"). Lane geometry is checked
 *  when the lanes are fitted. */
void ValidateScene(const Scene& scene, const Params& params);

}  // namespace criticality::internal
