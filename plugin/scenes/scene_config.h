#pragma once
// What the scenes stage needs to know: the range of a scene, how far ahead each object's lanes
// and stop lines reach, and how its lanes are sampled.
#include <cmath>

#include "plugin/scenes/lane_corridor.h"
#include "plugin/scenes/road_users.h"

namespace criticality::plugin {

struct SceneConfig {
  /** --range: objects whose centre lies within this distance of the ego's are in its scene. */
  double range_m{80.0};
  /** The estimator's horizon and largest acceleration (Params::horizon_s,
   *  vehicle_accel_max_mps2): an object's lanes and stop line reach v T + a T^2 / 2 ahead. */
  double horizon_s{2.0};
  double max_accel_mps2{9.7};
  /** How far lanes are sampled into a turn (LaneSamplingFor the estimator's parameters). */
  LaneSampling lane_sampling{};
  /** What a vehicle's state may be (plugin/scenes/object_reading.h, plausible states): the
   *  estimator's tyre-road friction and steering limit (Params::friction, max_steer_rad). */
  double friction{1.0};
  double max_steer_rad{0.5};
  /** With --all-vehicles: which vClasses are egos (--ego-classes; see road_users.h). */
  EgoClasses ego_classes;
  bool all_vehicles{false};
  /** --observable-only: scenes hold only what the vehicles' sensors could know (positions,
   *  speeds, headings, sizes and classes, lane geometry, signal states, turn signals): no
   *  routes, route ends, next edges or vType values (plugin/README.md). */
  bool observable_only{false};
  /** --accel-window: a vehicle's acceleration is its speed change over this time, the mean of
   *  SUMO's accelerations (each the last step's speed change) over its consecutive reads within
   *  it; at steps as long as the window or longer, SUMO's of the last step. 0: SUMO's always.
   *  At short steps SUMO's driver imperfection (sigma) changes a speed by up to +-0.45 m/s per
   *  0.1 s step, so the last step's acceleration jumps between about +2.5 and -4.5 m/s^2 from
   *  step to step (bench/RESULTS.md, twenty-second stop). Off by default: 0.3 s lowered the
   *  flicker of p but not the held-out networks' false alarms (twenty-third stop). */
  double accel_window_s{0.0};
  /** A person on a walking area whose next crossing it may not enter now (red, or no priority
   *  while a vehicle approaches, at the link SUMO's persons obey in the way it walks:
   *  CrossingEntries, MustWaitAt) stays on the footway. Reads the person's next edge, which
   *  only the simulator knows (off with --observable-only, which does not read it,
   *  and with --no-crossing-obligations). */
  bool crossing_obligations{true};
  /** Such a waiting person is expected to stop where the crossing begins, as SUMO's persons do:
   *  its expected acceleration (its reference hypothesis) is the deceleration that stops it
   *  there (CrossingStopDecel). Needs crossing_obligations; --no-crossing-stops turns it off. */
  bool crossing_stops{true};
  /** A vehicle at a link without priority ('m', 'g', '=') while SUMO has a foe approaching it
   *  (the link's has_foe, which only the simulator knows) gets a yield line (stop_lines.h).
   *  --no-yield-stops leaves those lines out (stop signs, red and yellow lights stay): SUMO's
   *  vehicle goes on when its gap before the foe suffices, so "a foe approaches" is not "it
   *  stops" (bench/RESULTS.md, right-of-way violations). */
  bool yield_stops{true};
  /** Where such a link's internal lane continues into another internal lane (SUMO's internal
   *  junction: a left turn across oncoming traffic), the yield line is at the end of the first
   *  internal lane, where SUMO's vehicle waits inside the junction, not at the junction's
   *  entry. On by default since the eighteenth stop (bench/RESULTS.md: with other vehicles
   *  acting on their lines at once, Params::stop_obligation_at_once, it took a left turner's
   *  line to where SUMO stops it; tuning grid 22 -> 20 warnings, held-out 52 -> 51; alone, at
   *  the eighth stop, it gained nothing). --no-internal-junction-yield turns it off. */
  bool internal_junction_yield{true};
  /** Whether to tell the estimator which vehicles' reasons to brake the scene knows
   *  (ObjectState::braking_causes_known, MayYieldAhead in stop_lines.h): only what
   *  --release-braking (Params::release_unexplained_braking) reads, and a link read per
   *  vehicle near its lane's end, so off unless that experiment is on. */
  bool braking_causes{false};
  /** --bent-bodies (off by default: measured, not kept; bench/RESULTS.md): a vehicle whose way
   *  behind its front turns (SUMO's box of it, front to back, shorter than the vehicle: IsBent)
   *  is a chain of boxes along that way, each keeping to the lanes it stands on; the first box
   *  of a chain (a train's too) points along its own part of the way, not along SUMO's angle,
   *  which points from the whole body's back to its front (carriages.h); a single box is SUMO's
   *  (BodyLengthOf). The way behind is the route's edges already driven: where the body
   *  stands, which sensors see, so observable_only keeps it. Off: every vehicle up to 20 m is
   *  one box of its length along SUMO's angle. */
  bool bent_bodies{false};
  /** --bodies-on-path (experimental, off: measured, not kept; bench/RESULTS.md): the box
   *  of every vehicle of one box (no carriages) is SUMO's (front to back, BodyLengthOf,
   *  centred between them) and the
   *  estimator predicts it so (Scene::bodies_on_path: centred on the chord of the path its
   *  centre follows). Off: a box of the vehicle's length from its front along SUMO's angle,
   *  predicted centred on its path. */
  bool bodies_on_path{false};
  /** A vehicle of one box (no carriages) is SUMO's box of it: from its front to its back on the
   *  way behind it (BodyLengthOf, the chord: shorter than the vehicle where that way bends,
   *  in a tight turn), centred between them along SUMO's angle, and predicted as every box is.
   *  Off (--no-sumo-box): a box of the vehicle's length from its front along SUMO's angle,
   *  which in a tight turn reaches past the body's back (traced at a spider's centre, where
   *  SUMO turns a car through 110 degrees at 1.3 m radius: the long box overlapped a car that
   *  SUMO's box of it cleared; bench/RESULTS.md, twentieth stop). Where the body stands, which
   *  sensors see: observable_only keeps it. */
  bool sumo_box{true};
  /** A vehicle whose front or back is on a junction's internal lane brings the way its body
   *  moves along (plugin/scenes/junction_way.h, the estimator's Vehicle::way), which the
   *  estimator moves it on (Params::bodies_on_way). --no-junction-ways: not sent. */
  bool junction_ways{true};
  /** A vehicle's heading that SUMO turns faster than the vehicle can (beyond v r <= mu g since
   *  the previous step) is held for up to kMaxHeadingHoldS where SUMO's lane changes are
   *  instantaneous, and on or just off a junction's internal lane (ObjectReader::HeadingOf);
   *  --no-heading-hold turns it off. Reads only the heading's history, which sensors see. */
  bool heading_hold{true};
  /** After a lane change within one step made while the body's back still stands on the lanes
   *  behind the old lane (just past a junction), SUMO's angle points from that back to the
   *  front in the new lane, often against the turn it is finishing. Where SUMO's lane changes
   *  are instantaneous, a vehicle whose front is less than its length into a normal lane that
   *  no link of its previous route edge leads to is read with the heading of the way behind
   *  that lane (the lanes it came by moved sideways onto it, way_behind.h), as if it had come
   *  by that lane (ObjectReader::Vehicle); --no-way-heading takes SUMO's angle. Reads the lane
   *  geometry and the edges the vehicle came by, which sensors see. */
  bool way_heading{true};
  /** On by default since the twenty-sixth stop (held-out false alarms 40 -> 36, every warned
   *  collision and overlap kept, as early): a vehicle whose body is in a junction (front or
   *  back on an internal lane, BodyInJunction) is read with the heading of the chord of its lanes from its back
   *  (its length behind its front along them) to its front, as SUMO places its body, not with
   *  SUMO's angle, which follows the internal lane's piece at the front and jumps at its
   *  corners (6.7, 29.5, 58.6, 29.4 degrees in four 0.1 s steps of one turn), nor with the
   *  heading held over such a jump (heading_hold), which kept a car turning right pointing
   *  0.44 rad off its turn and its centre 2 m off its way (bench/RESULTS.md, twenty-sixth
   *  stop). --no-junction-chord-heading turns it off. Reads the lanes the vehicle is on, which
   *  a map gives. */
  bool junction_chord_heading{true};
  /** The lanes ahead of a vehicle run through a junction along its internal lanes (the turn
   *  as SUMO drives it). Off (--no-junction-shapes): the straight chord from the lane's end
   *  to the next lane's start (getLinks names only the lane after the junction). On by
   *  default since it helped both held-out families (bench/RESULTS.md, 2026-12-05). Lane
   *  geometry, which a map holds. */
  bool junction_shapes{true};
  /** At steps up to kLongStepS a vehicle whose heading is SUMO's heading along its lanes (the
   *  chord from its back to its front on them, within kFollowsLaneToleranceRad) turns as that
   *  chord turns around its front (ObjectLanes::lane_heading), not at its last step's heading
   *  change, which along a lane of straight pieces is 0 or a spike. On by default since it
   *  helped the held-out networks at 0.1 s steps (bench/RESULTS.md, 2026-12-05);
   *  --no-lane-heading-yaw-rate takes the last step's change. Lane geometry and the body's
   *  length, which a map and sensors give. */
  bool lane_heading_yaw_rate{true};
  /** Experimental, off by default (--lane-change-target): a vehicle seen changing lanes (its
   *  blinker, its front off its lane's centre and its heading turned that way:
   *  LaneChangeTarget in object_lanes.h) is taken as on the lane it moves into, which SUMO
   *  gives it only past the middle of the change; its most likely path then leads there. On
   *  held-out sublane grids it warned of more changes that SUMO then broke off than it helped
   *  (bench/RESULTS.md, sixteenth stop). Blinker, pose and lane geometry, which sensors and a
   *  map give. */
  bool lane_change_target{false};
  /** With continuous lane changes (not instant_lane_changes): a vehicle whose back is still on
   *  the lanes behind its normal lane, and whose heading does not follow its lanes
   *  (lane_heading_yaw_rate) but lies within kSidewaysMaxAngleRad of that lane's direction,
   *  is being moved sideways by SUMO, and takes its lane's yaw rate, not its heading's change
   *  since the last step. SUMO then measures its heading from the lane's start, not from its
   *  back (MSVehicle::getBackPosition), so the heading jumps when such a move begins or ends:
   *  a 9 degree jump in 0.1 s read as a turn at 1.6 rad/s into the counter lane
   *  (bench/RESULTS.md, sixteenth stop). Once its back is on the lane too, its heading's
   *  change is the sideways motion's. --no-lane-change-yaw-rate: the heading's change
   *  everywhere. Heading and lane geometry, which sensors and a map give. */
  bool lane_change_yaw_rate{true};
  /** SUMO moves a vehicle into the next lane within one step (no sublane model,
   *  lanechange.duration 0, SUMO's defaults); set by the driver from SUMO's options. */
  bool instant_lane_changes{true};
};

/** How long a held heading (SceneConfig::heading_hold) may last since SUMO's was last taken. */
inline constexpr double kMaxHeadingHoldS = 0.5;

/** How far a vehicle can get within the horizon, at least 10 m: v T + a_max T^2 / 2 (its lane
 *  corridor's length, and how far ahead a stop line counts). */
inline double ReachAhead(double speed_mps, const SceneConfig& config) {
  return std::fmax(10.0, speed_mps * config.horizon_s +
                             0.5 * config.max_accel_mps2 * config.horizon_s * config.horizon_s);
}

/** Steps longer than this (SUMO's default is 1 s) make the heading change since the previous
 *  step a stale yaw rate: a car that finished a junction turn within the step kept "turning" at
 *  its mean rate, into the oncoming lane. Such steps take the yaw rate of following the lane
 *  instead, as SUMO's vehicles do. */
inline constexpr double kLongStepS = 0.25;

/** How close a vehicle's heading must be to SUMO's heading along its lanes for it to count as
 *  following them (SceneConfig::lane_heading_yaw_rate): half a degree. Measured on a
 *  netgenerate rand net at 0.1 s steps, 40 s, every vehicle: 98 % of 10,344 reads within
 *  0.01 degrees, 19 between 0.5 and 5 or more (a sublane change, a held heading). */
inline constexpr double kFollowsLaneToleranceRad = 0.5 * 3.14159265358979323846 / 180.0;

/** SceneConfig::lane_change_yaw_rate: the most a heading moved sideways along its lane is taken
 *  to be turned from the lane's direction (SUMO turns it by the sideways speed over the speed:
 *  1 m/s sideways at 2.7 m/s is 20 degrees). */
inline constexpr double kSidewaysMaxAngleRad = 20.0 * 3.14159265358979323846 / 180.0;

}  // namespace criticality::plugin
