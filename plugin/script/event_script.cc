#include "plugin/script/event_script.h"

#include <stdexcept>

namespace criticality::plugin {

EventScript::EventScript(const std::vector<ScenarioEvent>& events, SumoWorld* world)
    : events_(events), world_(world), applied_(events.size(), false) {}

void EventScript::Left(const std::vector<std::string>& ids) {
  for (const std::string& id : ids) {
    for (const ScenarioEvent& e : events_) {
      if (e.target == id) left_.insert(id);
    }
  }
}

void EventScript::ApplyDue(double time_s, double step_s) {
  for (size_t k = 0; k < events_.size(); ++k) {
    const ScenarioEvent& e = events_[k];
    if (applied_[k] || e.time_s > time_s + 0.5 * step_s) continue;
    if (world_->Apply(e)) {
      applied_[k] = true;
      continue;
    }
    const bool person = e.action == EventAction::kPersonSpeed;
    const std::string what = (person ? "person '" : "vehicle '") + e.target + "'";
    if (left_.count(e.target)) {
      throw std::invalid_argument("event '" + e.text + "' at t = " + std::to_string(time_s) +
                                  " s: " + what + " has already left the simulation");
    }
    if (world_->Lookup(e.target) != Known::kUnknown) continue;  // loaded, departs later
    if (!scanned_) {
      route_ids_ =
          ScanRouteIds({world_->Option("route-files"), world_->Option("additional-files")});
      scanned_ = true;
    }
    const RouteIdKind kind = Classify(route_ids_, e.target);
    if (kind == RouteIdKind::kCannotTell) continue;
    if (kind == (person ? RouteIdKind::kPerson : RouteIdKind::kVehicle))
      continue;  // not loaded yet
    throw std::invalid_argument("event '" + e.text + "' at t = " + std::to_string(time_s) +
                                " s: SUMO has no " + what +
                                " and no route file defines one; check the ID");
  }
}

std::vector<std::string> EventScript::Pending() const {
  std::vector<std::string> out;
  for (size_t k = 0; k < events_.size(); ++k) {
    if (!applied_[k]) out.push_back(events_[k].text);
  }
  return out;
}

}  // namespace criticality::plugin
