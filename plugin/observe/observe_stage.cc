#include "plugin/observe/observe_stage.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <unordered_set>

#include "plugin/network/polyline.h"
#include "plugin/observe/neighbour_grid.h"
#include "plugin/observe/vehicle_bodies.h"

namespace criticality::plugin {
namespace {

// Collision types in which SUMO reports the person's lane, not the vehicle's.
bool IsPersonCollision(const std::string& type) {
  return type == "crossing" || type == "walkingarea" || type == "sharedLane";
}

}  // namespace

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

ObserveStage::ObserveStage(const ObserveConfig& config, SumoWorld* world)
    : config_(config), world_(world) {
  if (!config_.all_vehicles) {
    named_.insert(config_.egos.begin(), config_.egos.end());
    for (const std::string& e : named_) state_[e] = State::kPending;
  }
}

bool ObserveStage::IsEgo(const std::string& id) const {
  return config_.all_vehicles ? state_.count(id) > 0 : named_.count(id) > 0;
}

ObserveStage::State* ObserveStage::StateOf(const std::string& id) {
  auto it = state_.find(id);
  return it == state_.end() ? nullptr : &it->second;
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
        if (config_.attached) break;
        if (route_ids_.vehicle_flows.count(e)) {  // a flow's ID, not one of its vehicles'
          throw EgoError("--ego '" + e + "': that is a flow; its vehicles are '" + e + ".0', '" +
                         e + ".1', ...: name one of them (or use --all-vehicles)");
        }
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
  obs.sumo_time_s = world_->Time();
  const StepReport report = world_->Report();
  obs.arrived = report.arrived;
  obs.arrived.insert(obs.arrived.end(), report.persons_arrived.begin(),
                     report.persons_arrived.end());
  for (const std::string& id : report.persons_departed) {
    if (named_.count(id)) PersonEgo(id);
  }
  // Collisions first: an ego that SUMO removed for one is still known as an ego here.
  const std::set<std::string> colliding = Collisions(report, &obs);
  LifeCycle(report, colliding, &obs);
  const std::vector<std::string> driving = Driving(colliding, &obs);
  first_step_ = false;
  Read(driving, colliding, &obs);
  KeepEgoClassEvents(&obs);
  obs.critical_events = critical_.Run(obs.time_s, obs.surroundings);
  return obs;
}

void ObserveStage::KeepEgoClassEvents(Observation* obs) {
  if (!config_.all_vehicles || !config_.ego_class) return;
  for (const SumoObject& o : obs->surroundings.objects) {
    if (!o.person && !config_.ego_class(o.vehicle_class)) other_class_.insert(o.id);
  }
  auto& events = obs->ego_events;
  events.erase(std::remove_if(events.begin(), events.end(),
                              [&](const EgoEvent& e) { return other_class_.count(e.ego) > 0; }),
               events.end());
  for (const std::string& id : obs->left) other_class_.erase(id);
}

std::set<std::string> ObserveStage::Collisions(const StepReport& report, Observation* obs) {
  std::set<std::string> now_pairs, colliding;
  for (const SumoCollision& c : report.collisions) {
    const std::string key = c.collider + "\n" + c.victim;
    now_pairs.insert(key);
    colliding.insert(c.collider);
    colliding.insert(c.victim);
    if (active_pairs_.count(key)) continue;
    CollisionEvent e{c, IsEgo(c.collider) || IsEgo(c.victim)};
    if (!c.collider_present) Place(&e.sumo);
    obs->collisions.push_back(std::move(e));
  }
  active_pairs_.swap(now_pairs);
  return colliding;
}

void ObserveStage::Place(SumoCollision* c) {
  if (IsPersonCollision(c->type) || c->lane.empty()) return;  // the collider's place is gone
  const Point2 p = PointAlong(world_->Lane(c->lane).shape, c->pos_m, nullptr);
  c->x_m = p.x;
  c->y_m = p.y;
}

void ObserveStage::LifeCycle(const StepReport& report, const std::set<std::string>& colliding,
                             Observation* obs) {
  for (const std::string& id : report.departed) {
    State* s = StateOf(id);
    if (config_.all_vehicles && !s) s = &(state_[id] = State::kPending);
    if (s && *s == State::kPending) {
      *s = State::kDriving;
      ++egos_seen_;
      Event(obs, id, EgoEventKind::kDepart);
    }
  }
  // A teleport may start and end in the same step (SUMO found room at once).
  obs->teleported.insert(obs->teleported.end(), report.teleport_start.begin(),
                         report.teleport_start.end());
  obs->teleported.insert(obs->teleported.end(), report.teleport_end.begin(),
                         report.teleport_end.end());
  for (const std::string& id : report.teleport_start) {
    State* s = StateOf(id);
    if (s && *s == State::kDriving) {
      *s = State::kTeleporting;
      Event(obs, id, EgoEventKind::kTeleportStart,
            colliding.count(id) ? "after a collision (collision.action teleport)"
                                : "jammed or stuck (time-to-teleport)");
    }
  }
  for (const std::string& id : report.teleport_end) {
    State* s = StateOf(id);
    if (s && *s == State::kTeleporting) {
      *s = State::kDriving;
      Event(obs, id, EgoEventKind::kTeleportEnd);
    }
  }
  for (const std::string& id : report.arrived) {
    Leave(id, obs);
    State* s = StateOf(id);
    if (!s || *s == State::kDone || *s == State::kPending) continue;
    Event(obs, id, EgoEventKind::kArrive,
          *s == State::kTeleporting ? "at the end of a teleport" : "");
    if (config_.all_vehicles) {
      state_.erase(id);
    } else {
      *s = State::kDone;
    }
  }
}

void ObserveStage::Leave(const std::string& id, Observation* obs) {
  world_->Forget(id);
  obs->left.push_back(id);
}

void ObserveStage::Vanish(const std::string& id, const std::set<std::string>& colliding,
                          Observation* obs) {
  Event(obs, id, EgoEventKind::kVanish,
        colliding.count(id) ? "removed after a collision (collision.action remove)"
                            : "left the network without arriving");
  Leave(id, obs);
}

std::vector<std::string> ObserveStage::Driving(const std::set<std::string>& colliding,
                                               Observation* obs) {
  std::vector<std::string> driving;
  if (config_.all_vehicles) {
    const std::vector<std::string> ids = world_->VehicleIds();
    const std::unordered_set<std::string> present(ids.begin(), ids.end());
    for (const std::string& id : ids) {
      State& s = state_[id];  // kPending when new: in the network when the run attached
      if (s == State::kPending) {
        s = State::kDriving;
        ++egos_seen_;
        Event(obs, id, EgoEventKind::kDepart, "in the network when the run attached");
      }
    }
    for (auto it = state_.begin(); it != state_.end();) {
      if (it->second == State::kDriving && !present.count(it->first)) {
        Vanish(it->first, colliding, obs);
        it = state_.erase(it);
      } else {
        ++it;
      }
    }
    return ids;
  }
  if (first_step_) {  // under --connect an ego may have departed before the run attached
    for (const std::string& id : world_->VehicleIds()) {
      State* s = StateOf(id);
      if (s && *s == State::kPending) {
        *s = State::kDriving;
        ++egos_seen_;
        Event(obs, id, EgoEventKind::kDepart, "in the network when the run attached");
      }
    }
  }
  for (const std::string& e : config_.egos) {
    if (state_[e] == State::kDriving &&
        std::find(driving.begin(), driving.end(), e) == driving.end())
      driving.push_back(e);
  }
  return driving;
}

void ObserveStage::Read(const std::vector<std::string>& driving,
                        const std::set<std::string>& colliding, Observation* obs) {
  ReadScope scope;
  scope.context_range_m = config_.range_m + kReadMarginM;
  scope.whole_network = config_.all_vehicles;
  obs->surroundings = world_->Observe(driving, scope);
  MeasureBodies(*world_, &obs->surroundings);  // before anything places a body
  if (obs->surroundings.whole_network) FindNeighbours(scope.context_range_m, &obs->surroundings);
  if (config_.all_vehicles) return;
  std::set<std::string> observed;
  for (const SumoSurroundings::Ego& e : obs->surroundings.egos)
    observed.insert(obs->surroundings.objects[e.self].id);
  for (const std::string& e : driving) {
    if (!observed.count(e)) {
      Vanish(e, colliding, obs);
      state_[e] = State::kDone;
    }
  }
}

bool ObserveStage::AllNamedEgosDone() const {
  if (config_.all_vehicles) return false;
  for (const auto& [id, s] : state_) {
    if (s != State::kDone) return false;
  }
  return true;
}

std::string ObserveStage::NeverDeparted(double time_s) const {
  if (config_.all_vehicles) return "";
  for (const std::string& e : config_.egos) {
    if (state_.at(e) != State::kPending) continue;
    const bool loaded = world_->Lookup(e) == Known::kVehicle;
    std::ostringstream t;  // 0.5, 120, 3.25: no trailing zeros
    t << time_s;
    return "--ego '" + e + "' never departed by t = " + t.str() + " s: " +
           (loaded ? "SUMO loaded it; its depart time may lie after the end of the run"
                   : "SUMO never loaded it; check the ID and the route files");
  }
  return "";
}

}  // namespace criticality::plugin
