#pragma once
// Stage 1 of a step: what SUMO reports after the step — the step's time stamp, the egos to
// estimate, and SUMO's own collisions (each contact once).
#include <set>
#include <string>
#include <vector>

#include "plugin/driver_options.h"
#include "plugin/sumo_world.h"

namespace criticality::plugin {

struct Observation {
  double time_s{0.0};
  /** Collisions that began in this step (a pair already in contact is not reported again). */
  std::vector<SumoCollision> collisions;
  /** The egos present in the network, to be estimated in this step. */
  std::vector<std::string> egos;
};

class ObserveStage {
 public:
  ObserveStage(const DriverOptions& options, SumoWorld* world);
  /** Reads the step SUMO just made. */
  Observation Run();
  /** Egos that were estimated at least once. */
  const std::set<std::string>& seen() const { return seen_; }

 private:
  const DriverOptions& options_;
  SumoWorld* world_;
  std::set<std::string> seen_;
  std::set<std::string> active_pairs_;
};

}  // namespace criticality::plugin
