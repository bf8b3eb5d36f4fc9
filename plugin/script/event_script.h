#pragma once
// A scenario's scripted events, applied before the step they are due in. A target that is not
// in the network yet but will be (SUMO has loaded it, or a route file defines it) is waited
// for; a target SUMO does not know and no route file defines, or one that already left the
// simulation, is an error at the event's time (std::invalid_argument: bad scenario input).
#include <set>
#include <string>
#include <vector>

#include "plugin/script/scenario_event.h"
#include "plugin/sumo/route_ids.h"
#include "plugin/sumo/sumo_world.h"

namespace criticality::plugin {

class EventScript {
 public:
  EventScript(const std::vector<ScenarioEvent>& events, SumoWorld* world);
  /** Applies the events due by `time_s` (within half a step). */
  void ApplyDue(double time_s, double step_s);
  /** Vehicles and persons that left the simulation in the last step. */
  void Left(const std::vector<std::string>& ids);
  /** Events never applied (their target never entered the network), as written. */
  std::vector<std::string> Pending() const;

 private:
  const std::vector<ScenarioEvent>& events_;
  SumoWorld* world_;
  std::vector<bool> applied_;
  std::set<std::string> left_;
  bool scanned_{false};
  RouteIds route_ids_;
};

}  // namespace criticality::plugin
