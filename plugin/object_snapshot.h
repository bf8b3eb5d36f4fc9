#pragma once
// What SUMO reported about one vehicle or person in one step, already converted to the
// estimator's conventions (centre of gravity, math yaw, lanes in the object's own frame), and
// the egos' surroundings in that step. Plain data, no SUMO types: scene building works on it.
#include <optional>
#include <string>
#include <vector>

#include "criticality/scene.h"
#include "plugin/car_following.h"

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
  /** A vehicle's obligation to stop ahead, as SUMO knows it (sumo_world.h): its next signal
   *  is red or yellow, or its next link is a stop sign or yields to an approaching foe. */
  std::optional<StopLine> stop_line;
  /** A vehicle's leader (SUMO's getLeader) when one is close enough to matter (car_following.h):
   *  its expected acceleration follows it. */
  std::optional<Leader> leader;
  /** A person's walk goes on along the footway (plugin/footway.h, Pedestrian::stays_on_footway). */
  bool stays_on_footway{false};
  std::string lane;  ///< SUMO lane ID ("" when not on a lane)
  std::string edge;  ///< SUMO edge ID of that lane
};

/** One step's objects, each read once, and which of them surround each ego. */
struct Surroundings {
  struct Ego {
    int self{-1};             ///< index into objects
    std::vector<int> nearby;  ///< indices of objects near it (a superset of those in range)
  };
  std::vector<ObjectSnapshot> objects;
  std::vector<Ego> egos;
};

}  // namespace criticality::plugin
