#pragma once
// Each object SUMO reported in a step becomes an ObjectSnapshot: its centre pose and math yaw
// (plugin/sumo/sumo_conventions.h), its yaw rate (SUMO has no getter: the heading change since
// the previous step, or with steps longer than kLongStepS the yaw rate of following its lane),
// its acceleration (SUMO's, or its mean over SceneConfig::accel_window_s),
// and for a vehicle on a lane its lanes from its own view (object_lanes.h), its stop line
// (stop_lines.h), its leader (car_following.h: three SUMO questions per moving vehicle), its type
// (road_users.h), the carriages of a long body (carriages.h), whether it is stopped or parked;
// for a walking person whether it keeps to the footway (footway.h). What each driver is then
// expected to do is set once the whole step is read (expected_accel.h). A state no vehicle of
// its kind can be in is made plausible and counted (Plausible: a yaw rate or an acceleration;
// HeadingOf: SUMO's heading jumping for a few steps at a junction's corners; after a lane change
// just past a junction the heading of the way behind the new lane, SceneConfig::way_heading);
// values that are not numbers (NaN) are passed on: scene building leaves out what the estimator
// cannot use.
#include <deque>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "plugin/network/counter_lanes.h"
#include "plugin/network/road_network.h"
#include "plugin/network/traffic_view.h"
#include "plugin/scenes/footway.h"
#include "plugin/scenes/object_lanes.h"
#include "plugin/scenes/object_snapshot.h"
#include "plugin/scenes/scene_config.h"
#include "plugin/sumo/sumo_reports.h"

namespace criticality::plugin {

class ObjectReader {
 public:
  /** @param step_s the simulation's step length. */
  ObjectReader(const SceneConfig& config, double step_s, RoadNetwork* network,
               TrafficView* traffic);
  /** The snapshots of `objects` (same order), read at SUMO time `sumo_time_s`. */
  std::vector<ObjectSnapshot> Read(const std::vector<SumoObject>& objects, double sumo_time_s);
  /** A vehicle left the simulation or was teleported: its heading is no longer remembered. */
  void Forget(const std::string& id) {
    last_yaw_.erase(id);
    accel_reads_.erase(id);
  }
  /** Object reads whose state was made plausible (a yaw rate or an acceleration no vehicle of
   *  its kind can have), so far. */
  long long conditioned() const { return conditioned_; }

 private:
  ObjectSnapshot Vehicle(const SumoObject& o, double sumo_time_s);
  ObjectSnapshot Person(const SumoObject& o);
  /** The vehicle ahead that its driver is expected to follow, with its acceleration over the
   *  window (WindowAccel); nullopt when it stands still itself, nothing is within
   *  LeaderLookAhead, or SUMO's values are not finite. */
  std::optional<Leader> LeaderOf(const std::string& id, double speed, double sumo_time_s);
  /** A parked vehicle beside its lane: its position is more than half a lane width off the
   *  lane's centre line (a parking area beside the road). */
  bool OffItsLane(const SumoObject& o);
  /** Its front is on a normal lane that no link of its previous route edge leads to: it changed
   *  lanes since it left the junction (remembered per edge and lane: the links do not change). */
  bool ChangedLanesSinceTheJunction(const SumoObject& o);
  /** The largest yaw rate a vehicle at this speed can turn at within grip: v r <= mu g. */
  double GripYawRate(double speed_mps) const;
  /** The yaw rate a vehicle is read with, `measured` its heading change since the last step:
   *  with steps longer than kLongStepS its lane's; with shorter ones, where it follows its
   *  lanes (its `heading` SUMO's along them, not `held`), the turn of that heading
   *  (SceneConfig::lane_heading_yaw_rate); with continuous lane changes, where SUMO moves it
   *  sideways just past a junction (its back behind its normal lane's start, its heading
   *  within kSidewaysMaxAngleRad of the lane's), its lane's
   *  (SceneConfig::lane_change_yaw_rate); else `measured`. */
  double LaneYawRateOr(double measured, const ObjectLanes& lanes, double heading, bool held) const;
  /** Plausible states: a yaw rate within grip (the lane's where SUMO's heading jumped), an
   *  acceleration within the type's limits; counted unless `counted` (the read's heading was
   *  held and counted already). */
  void Plausible(double lane_yaw_rate, bool counted, ObjectSnapshot* s);

  SceneConfig config_;
  double step_s_;
  RoadNetwork* network_;
  TrafficView* traffic_;
  CounterLanes counter_lanes_;
  CrossingEntries crossing_entries_;  ///< the links persons obey to enter crossings
  /** What the previous read of a vehicle saw: when, the heading used (SUMO's, or the held one,
   *  HeadingOf), the yaw rate used, and when SUMO's heading was last taken as it was. */
  struct LastHeading {
    double time_s{0.0};
    double yaw_rad{0.0};
    double yaw_rate_radps{0.0};
    double taken_s{0.0};
    bool in_junction{false};  ///< it was on a junction's internal lane
  };
  /** The heading a vehicle is read with: SUMO's (`angle_deg`, SceneConfig::way_heading's
   *  where it replaced it), except where it changed since the previous
   *  step faster than the vehicle can turn, after an instantaneous lane change or at a
   *  junction's corner (SceneConfig::heading_hold): then the previous heading turned on at the
   *  previous yaw rate, for at most kMaxHeadingHoldS since SUMO's was last taken. */
  double HeadingOf(const SumoObject& o, double angle_deg, double sumo_time_s, bool* held) const;

  std::unordered_map<std::string, LastHeading> last_yaw_;  ///< id -> its previous read
  /** SUMO's acceleration of one read of a vehicle. */
  struct AccelRead {
    double time_s{0.0};
    double accel_mps2{0.0};
  };
  /** Remembers SUMO's acceleration of each vehicle read at `sumo_time_s`, keeping its
   *  consecutive reads within SceneConfig::accel_window_s (a read more than 1.5 steps after the
   *  previous one starts afresh). */
  void RememberAccels(const std::vector<SumoObject>& objects, double sumo_time_s);
  /** A vehicle's acceleration over SceneConfig::accel_window_s: the mean of its remembered
   *  reads, where it was read at `sumo_time_s`; else `sumo_accel`. */
  double WindowAccel(const std::string& id, double sumo_accel, double sumo_time_s) const;
  /** id -> its reads within the window, oldest first (only with accel_window_s > 0). */
  std::unordered_map<std::string, std::deque<AccelRead>> accel_reads_;
  /** "previous edge\nlane" -> whether a link of that edge leads to the lane. */
  std::unordered_map<std::string, bool> reached_from_;
  long long conditioned_{0};
};

}  // namespace criticality::plugin
