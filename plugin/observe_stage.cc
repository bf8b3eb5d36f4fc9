#include "plugin/observe_stage.h"

#include <algorithm>

#include "plugin/driver.h"

namespace criticality::plugin {

ObserveStage::ObserveStage(const DriverOptions& options, SumoWorld* world)
    : options_(options), world_(world) {}

Observation ObserveStage::Run() {
  Observation obs;
  obs.time_s = world_->Time();
  const double t = obs.time_s;
  auto named = [&](const std::string& id) {
    return !options_.all_vehicles && std::count(options_.egos.begin(), options_.egos.end(), id) > 0;
  };
  for (const std::string& id : world_->TeleportingIds()) {
    if (seen_.count(id) || named(id)) {
      throw EgoError("ego '" + id + "' was teleported by SUMO at t = " + std::to_string(t) +
                     " s (jam or collision with teleport action); its estimates would jump. "
                     "Use --collision.action warn, or another ego");
    }
  }
  for (const std::string& id : world_->ArrivedIds()) {
    const bool run_goes_on = world_->ExpectedObjects() > 0;
    if (named(id) && run_goes_on) {
      throw EgoError("ego '" + id + "' arrived (its route ended) at t = " + std::to_string(t) +
                     " s while the simulation goes on; give it a route that lasts the run, "
                     "stop the run then with --end, or use --all-vehicles");
    }
  }
  // SUMO reports an overlapping pair at every step (collision.action warn): count events.
  std::set<std::string> now_pairs;
  for (const SumoCollision& c : world_->Collisions()) {
    const std::string key = c.collider + "\n" + c.victim;
    now_pairs.insert(key);
    if (!active_pairs_.count(key)) obs.collisions.push_back(c);
  }
  active_pairs_.swap(now_pairs);

  const std::vector<std::string> present = world_->VehicleIds();
  if (options_.all_vehicles) {
    obs.egos = present;
  } else {
    for (const std::string& e : options_.egos) {
      if (std::find(present.begin(), present.end(), e) != present.end()) obs.egos.push_back(e);
    }
  }
  seen_.insert(obs.egos.begin(), obs.egos.end());
  return obs;
}

}  // namespace criticality::plugin
