#pragma once
// clang-format off
/** @file Scene files: a Scene as plain text, written by sumo-criticality --record-scenes and
 *  replayed by criticality-bench --scene-file (no SUMO needed). Numbers are written with 17
 *  significant digits, so a replay sees exactly the recorded scene.
 *
 *  Format (one record per line, '#' starts a comment):
 *    criticality-scene 1
 *    euler-update-step DT
 *    bodies-on-path
 *    ego ID x y yaw speed accel yaw_rate sideslip length width height|-
 *    lane own|left|right COUNTER  lx0 ly0 lx1 ly1 lx2 ly2  rx0 ry0 rx1 ry1 rx2 ry2 [straight-to-middle] [corner T]
 *    vehicle ID x y yaw speed accel yaw_rate sideslip length width height|- LANES(0|1)
 *    stop red|yellow|yield DISTANCE
 *    pedestrian ID x y yaw speed accel yaw_rate sideslip length width
 *    footway
 *    expected-accel A
 *    route-end D
 *    braking-causes-known
 *    type car|motorcycle|bicycle|heavy|rail [mass M] [accel A] [decel D] [emergency-decel E] [max-speed V]
 *    carriage x y yaw yaw_rate length width LANES(0|1)
 *    way FRONT BACK N x0 y0 ... x(N-1) y(N-1)
 *  `lane` lines belong to the ego, vehicle or carriage line before them (for a vehicle or a
 *  carriage only when its LANES flag is 1); a `stop` line (Vehicle::stop_line,
 *  Ego::stop_line) to the vehicle or ego line before it; a `type` line (Ego::type,
 *  Vehicle::type: the road user class and the values given, absent: a car without values) to
 *  the ego or vehicle line before it; `carriage` lines
 *  (Vehicle::carriages, front to back) to the vehicle line before them; a `way` line
 *  (Vehicle::way: its front's and back's arc lengths, its N points) to the vehicle line before
 *  it; a
 *  `footway` line (Pedestrian::stays_on_footway) to the pedestrian line before it; an
 *  `expected-accel` line sets ObjectState::expected_accel_mps2 of the ego, vehicle or
 *  pedestrian line before it (absent: not set), a `route-end` line the ObjectState::route_end_m
 *  of the ego or vehicle line before it, a `braking-causes-known` line sets
 *  ObjectState::braking_causes_known of the ego or vehicle line before it. A lane line ending in `straight-to-middle` sets
 *  Lane::straight_to_middle, one with `corner T` Lane::corner_tangent_m = T. An `euler-update-step` line (anywhere after the header; absent: 0)
 *  sets Scene::euler_update_step_s, a `bodies-on-path` line (likewise; absent: false)
 *  Scene::bodies_on_path. Version 1 throughout: `type`, `carriage` and `way` lines were added to it,
 *  and a file without them is the same as before they existed (a reader from before them
 *  rejects a file with them, naming the record). */
// clang-format on
#include <istream>
#include <ostream>
#include <string>

#include "criticality/scene.h"

namespace criticality {

void WriteScene(std::ostream& out, const Scene& scene);

/** @throws InputError naming the line and what is wrong with it. */
Scene ReadScene(std::istream& in, const std::string& source = "scene");

/** Reads a scene file; @throws InputError when it cannot be read or parsed. */
Scene ReadSceneFile(const std::string& path);

}  // namespace criticality
