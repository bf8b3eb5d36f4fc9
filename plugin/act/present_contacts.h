#pragma once
// Contacts that exist already: the objects of a scene whose body overlaps the ego's where the
// scene starts (the estimator's boxes: a vehicle's length x width about its state, each of its
// carriages, a person's footprint; touching counts, as in the estimator's collision test).
//
// Such a contact makes every ego hypothesis collide at the first step, so p is 1 whatever the
// ego does, and it hides every other threat of the scene. For an ego that stands
// (ClosedLoop::kStandstill), the closed loop decides on the scene without them (ActStage):
// holding a standing vehicle changes nothing about a contact that has happened, and a hold
// kept for it never ends while the bodies stay in contact (a car stopped on a crossing with a
// waiting pedestrian's footprint over its corner was held for 73 s, until the pedestrian
// walked into it: bench/RESULTS.md, twenty-second stop).
// A moving ego keeps them: its braking still lowers the speed at which SUMO sees the contact
// (the estimator's footprints may touch a step before SUMO reports a collision).
#include <string>
#include <vector>

#include "criticality/scene.h"

namespace criticality::plugin {

/** The IDs of the vehicles and pedestrians of `scene` whose body (or one of its carriages)
 *  overlaps the ego's at the scene's start, in scene order (vehicles first). */
std::vector<std::string> ObjectsInContact(const Scene& scene);

/** `scene` without the vehicles and pedestrians named in `ids`. */
Scene WithoutObjects(const Scene& scene, const std::vector<std::string>& ids);

}  // namespace criticality::plugin
