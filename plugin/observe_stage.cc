#include "plugin/observe_stage.h"

#include <algorithm>
#include <unordered_set>

namespace criticality::plugin {

const char* EgoEventName(EgoEventKind kind) {
  switch (kind) {
    case EgoEventKind::kDepart:
      return "depart";
    case EgoEventKind::kArrive:
      return "arrive";
    case EgoEventKind::kTeleportStart:
      return "teleport-start";
    case EgoEventKind::kTeleportEnd:
      return "teleport-end";
    case EgoEventKind::kVanish:
      return "vanish";
  }
  return "?";
}

ObserveStage::ObserveStage(const DriverOptions& options, SumoWorld* world,
                           const ExtractionConfig& config)
    : options_(options), world_(world), config_(config) {
  if (!options_.all_vehicles) {
    named_.insert(options_.egos.begin(), options_.egos.end());
    for (const std::string& e : named_) state_[e] = State::kPending;
  }
}

bool ObserveStage::IsEgo(const std::string& id) const {
  return options_.all_vehicles ? state_.count(id) > 0 : named_.count(id) > 0;
}

void ObserveStage::PersonEgo(const std::string& id) const {
  throw EgoError("--ego '" + id +
                 "' is a person in SUMO, not a vehicle: the ego must be a vehicle (persons are "
                 "taken into account as pedestrians around every ego)");
}

void ObserveStage::CheckNamedEgos() {
  bool scanned = false;
  for (const std::string& e : named_) {
    const Known known = world_->Lookup(e);
    if (known == Known::kVehicle) continue;
    if (known == Known::kPerson) PersonEgo(e);
    if (!scanned) {
      route_ids_ =
          ScanRouteIds({world_->Option("route-files"), world_->Option("additional-files")});
      scanned = true;
    }
    switch (Classify(route_ids_, e)) {
      case RouteIdKind::kVehicle:
      case RouteIdKind::kCannotTell:
        break;
      case RouteIdKind::kPerson:
        PersonEgo(e);
        break;
      case RouteIdKind::kAbsent:
        // Under --connect another client may still add it.
        if (!options_.connect.empty()) break;
        throw EgoError("--ego '" + e +
                       "': SUMO will never load this vehicle; no route or additional file "
                       "defines it (route-files: '" +
                       world_->Option("route-files") + "'). Check the ID");
    }
  }
}

void ObserveStage::Event(Observation* obs, const std::string& ego, EgoEventKind kind,
                         std::string detail) {
  obs->ego_events.push_back(EgoEvent{ego, kind, std::move(detail)});
}

Observation ObserveStage::Run() {
  Observation obs;
  obs.time_s = world_->StampOfLastStep();
  const StepReport report = world_->Report();
  obs.arrived = report.arrived;
  obs.arrived.insert(obs.arrived.end(), report.persons_arrived.begin(),
                     report.persons_arrived.end());
  for (const std::string& id : report.persons_departed) {
    if (named_.count(id)) PersonEgo(id);
  }

  // Collisions first: an ego that SUMO removed for one is still known as an ego here.
  std::set<std::string> now_pairs, colliding;
  for (const SumoCollision& c : report.collisions) {
    const std::string key = c.collider + "\n" + c.victim;
    now_pairs.insert(key);
    colliding.insert(c.collider);
    colliding.insert(c.victim);
    if (active_pairs_.count(key)) continue;
    obs.collisions.push_back(CollisionEvent{c, IsEgo(c.collider) || IsEgo(c.victim)});
  }
  active_pairs_.swap(now_pairs);

  auto state = [&](const std::string& id) -> State* {
    auto it = state_.find(id);
    return it == state_.end() ? nullptr : &it->second;
  };
  for (const std::string& id : report.departed) {
    State* s = state(id);
    if (options_.all_vehicles && !s) s = &(state_[id] = State::kPending);
    if (s && *s == State::kPending) {
      *s = State::kDriving;
      ++egos_seen_;
      Event(&obs, id, EgoEventKind::kDepart);
    }
  }
  // A teleport may start and end in the same step (SUMO found room at once).
  for (const std::string& id : report.teleport_start) {
    State* s = state(id);
    if (s && *s == State::kDriving) {
      *s = State::kTeleporting;
      Event(&obs, id, EgoEventKind::kTeleportStart,
            colliding.count(id) ? "after a collision (collision.action teleport)"
                                : "jammed or stuck (time-to-teleport)");
    }
  }
  for (const std::string& id : report.teleport_end) {
    State* s = state(id);
    if (s && *s == State::kTeleporting) {
      *s = State::kDriving;
      Event(&obs, id, EgoEventKind::kTeleportEnd);
    }
  }
  for (const std::string& id : report.arrived) {
    world_->Forget(id);
    State* s = state(id);
    if (!s || *s == State::kDone || *s == State::kPending) continue;
    Event(&obs, id, EgoEventKind::kArrive,
          *s == State::kTeleporting ? "at the end of a teleport" : "");
    if (options_.all_vehicles) {
      state_.erase(id);
    } else {
      *s = State::kDone;
    }
  }

  // Who drives now; an ego that left without arriving or teleporting vanished.
  auto vanish = [&](const std::string& id) {
    Event(&obs, id, EgoEventKind::kVanish,
          colliding.count(id) ? "removed after a collision (collision.action remove)"
                              : "left the network without arriving");
    world_->Forget(id);
  };
  std::vector<std::string> driving;
  if (options_.all_vehicles) {
    const std::vector<std::string> ids = world_->VehicleIds();
    const std::unordered_set<std::string> present(ids.begin(), ids.end());
    for (const std::string& id : ids) {
      State& s = state_[id];  // kPending when new: in the network when the run attached
      if (s == State::kPending) {
        s = State::kDriving;
        ++egos_seen_;
        Event(&obs, id, EgoEventKind::kDepart, "in the network when the run attached");
      }
    }
    for (auto it = state_.begin(); it != state_.end();) {
      if (it->second == State::kDriving && !present.count(it->first)) {
        vanish(it->first);
        it = state_.erase(it);
      } else {
        ++it;
      }
    }
    driving = ids;
  } else {
    if (first_step_) {  // under --connect an ego may have departed before the run attached
      for (const std::string& id : world_->VehicleIds()) {
        State* s = state(id);
        if (s && *s == State::kPending) {
          *s = State::kDriving;
          ++egos_seen_;
          Event(&obs, id, EgoEventKind::kDepart, "in the network when the run attached");
        }
      }
    }
    for (const std::string& e : options_.egos) {
      if (state_[e] == State::kDriving &&
          std::find(driving.begin(), driving.end(), e) == driving.end())
        driving.push_back(e);
    }
  }
  first_step_ = false;
  obs.surroundings = world_->Observe(driving, config_);
  if (!options_.all_vehicles) {
    std::set<std::string> observed;
    for (const Surroundings::Ego& e : obs.surroundings.egos)
      observed.insert(obs.surroundings.objects[e.self].id);
    for (const std::string& e : driving) {
      if (!observed.count(e)) {
        vanish(e);
        state_[e] = State::kDone;
      }
    }
  }
  obs.critical_events = critical_.Run(obs.time_s, obs.surroundings);
  return obs;
}

bool ObserveStage::AllNamedEgosDone() const {
  if (options_.all_vehicles) return false;
  for (const auto& [id, s] : state_) {
    if (s != State::kDone) return false;
  }
  return true;
}

std::string ObserveStage::NeverDeparted(double time_s) const {
  if (options_.all_vehicles) return "";
  for (const std::string& e : options_.egos) {
    if (state_.at(e) != State::kPending) continue;
    const bool loaded = world_->Lookup(e) == Known::kVehicle;
    return "--ego '" + e + "' never departed by t = " + std::to_string(time_s) + " s: " +
           (loaded ? "SUMO loaded it; its depart time may lie after the end of the run"
                   : "SUMO never loaded it; check the ID and the route files");
  }
  return "";
}

}  // namespace criticality::plugin
