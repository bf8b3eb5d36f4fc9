#pragma once
// Stage 1 of a step: what SUMO reports after the step (plugin/observe/observation.h). The egos'
// life cycle is a small state machine per ego:
//
//   pending --depart--> driving --teleport start--> teleporting --teleport end--> driving
//   driving | teleporting --arrive--> done          driving --gone without arriving--> done
//
// (with --all-vehicles an ego that is done is forgotten; a vehicle already in the network when
// the run attaches under --connect departs at the first step). Estimation of an ego pauses
// while it is teleported. Collisions are recorded once per contact; a vehicle's memory (SUMO
// subscriptions, colours, what the user commanded) is dropped when it leaves.
#include <set>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "plugin/network/road_network.h"
#include "plugin/observe/critical_events.h"
#include "plugin/observe/observation.h"
#include "plugin/observe/observe_config.h"
#include "plugin/sumo/route_ids.h"
#include "plugin/sumo/sumo_world.h"

namespace criticality::plugin {

/** A problem with a named ego that stays an error: SUMO never loads it, or it is a person. */
class EgoError : public std::runtime_error {
 public:
  explicit EgoError(const std::string& what) : std::runtime_error(what) {}
};

class ObserveStage {
 public:
  ObserveStage(const ObserveConfig& config, SumoWorld* world);
  /** Before the first step: a named ego that is a person, or that no route or additional file
   *  defines, is an EgoError now (as early as it can be known). */
  void CheckNamedEgos();
  Observation Run();
  /** Named egos only: every one of them has arrived or left the simulation. */
  bool AllNamedEgosDone() const;
  /** At the end: the error for a named ego that never departed ("" when none). */
  std::string NeverDeparted(double time_s) const;
  long long EgosSeen() const { return egos_seen_; }
  bool IsEgo(const std::string& vehicle) const;

 private:
  enum class State { kPending, kDriving, kTeleporting, kDone };
  void Event(Observation* obs, const std::string& ego, EgoEventKind kind, std::string detail = "");
  [[noreturn]] void PersonEgo(const std::string& id) const;
  /** New contacts into obs->collisions; returns every vehicle in a collision now. */
  std::set<std::string> Collisions(const StepReport& report, Observation* obs);
  /** Departures, teleports and arrivals of the step. */
  void LifeCycle(const StepReport& report, const std::set<std::string>& colliding,
                 Observation* obs);
  /** The egos driving now; with --all-vehicles every vehicle present (a vehicle gone without
   *  arriving vanished). */
  std::vector<std::string> Driving(const std::set<std::string>& colliding, Observation* obs);
  /** Reads the driving egos and what is around them; a named ego that cannot be read has
   *  vanished. */
  void Read(const std::vector<std::string>& driving, const std::set<std::string>& colliding,
            Observation* obs);
  /** With --all-vehicles and ego_class: drops the step's ego events of vehicles whose class
   *  is no ego's (learnt from the step's snapshots; forgotten when they leave). */
  void KeepEgoClassEvents(Observation* obs);
  void Vanish(const std::string& id, const std::set<std::string>& colliding, Observation* obs);
  void Leave(const std::string& id, Observation* obs);
  /** A collision whose collider SUMO already removed: its front bumper from its lane and
   *  position (SUMO's for vehicle-vehicle collisions; unknown for collisions with a person,
   *  whose lane SUMO reports). */
  void Place(SumoCollision* c);
  State* StateOf(const std::string& id);

  ObserveConfig config_;
  std::unordered_set<std::string> other_class_;  ///< vehicles of no ego class (KeepEgoClassEvents)
  SumoWorld* world_;
  std::set<std::string> named_;
  std::unordered_map<std::string, State> state_;  ///< all-vehicles: only those in the network
  RouteIds route_ids_;
  bool first_step_{true};
  long long egos_seen_{0};
  std::set<std::string> active_pairs_;
  CriticalEventDetector critical_;
};

}  // namespace criticality::plugin
