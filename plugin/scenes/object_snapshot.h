#pragma once
// One vehicle or person of one step as scene building sees it: in the estimator's conventions
// (centre of gravity, math yaw, lanes in the object's own frame), with what the scenes stage
// worked out about it (its lanes, a stop obligation, what its driver is expected to do, whether
// a walker keeps to the footway). Plain data, no SUMO types.
#include <optional>
#include <string>
#include <vector>

#include "criticality/scene.h"
#include "plugin/scenes/car_following.h"

namespace criticality::plugin {

struct ObjectSnapshot {
  std::string id;
  bool person{false};
  /** Centre of gravity and math yaw; SUMO's values as they came (they may be NaN: SUMO 1.15
   *  reports some persons on walking areas with NaN position and angle). */
  ObjectState state;
  double length_m{4.5};
  double width_m{1.8};
  std::optional<double> height_m;
  /** A vehicle's normal maximum deceleration (SUMO's decel, m/s^2); 0 for persons. */
  double normal_decel_mps2{0.0};
  /** A vehicle's own, left and right lanes seen from itself (counter-traffic flagged from its
   *  own direction of travel); empty for persons and where no usable lane exists. */
  LaneSet lanes;
  /** A vehicle's obligation to stop ahead, as SUMO knows it (plugin/scenes/stop_lines.h): its
   *  next signal is red or yellow, or its next link is a stop sign or yields to an approaching
   *  foe. */
  std::optional<StopLine> stop_line;
  /** A vehicle's leader (SUMO's getLeader) when one is close enough to matter (car_following.h):
   *  its expected acceleration follows it. */
  std::optional<Leader> leader;
  /** A person's walk goes on along the footway (plugin/scenes/footway.h,
   *  Pedestrian::stays_on_footway). */
  bool stays_on_footway{false};
  /** A vehicle's type for the estimator: its road user class and SUMO's limits. */
  VehicleType type;
  /** The boxes of a long body behind this one (plugin/scenes/carriages.h); length_m is the
   *  first box's. */
  std::vector<Carriage> carriages;
  /** A vehicle's way in a junction (plugin/scenes/junction_way.h), in its own frame. */
  std::optional<Way> way;
  /** SUMO's stop state: stopped (at a stop, a bus stop, in its lane) and parked (a parking
   *  stop); off_road: parked beside its lane (in a parking area), where it is nobody's
   *  obstacle. A parked vehicle is no ego; one off the road is no object either. */
  bool stopped{false};
  bool parked{false};
  bool off_road{false};
  /** Its vClass is no road user (a ship, an aircraft): left out of every scene. */
  bool not_a_road_user{false};
  std::string vehicle_class;  ///< SUMO's vClass ("pedestrian" for persons)
  std::string vehicle_type;   ///< SUMO's vType ID ("" for persons)
  std::string lane;  ///< SUMO lane ID ("" when not on a lane)
  std::string edge;  ///< SUMO edge ID of that lane
};

}  // namespace criticality::plugin
