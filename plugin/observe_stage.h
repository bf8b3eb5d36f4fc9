#pragma once
// Stage 1 of a step: what SUMO reports after the step. The step's time stamp (the one SUMO's
// own outputs use), the egos' life cycle (depart, arrive, teleport start and end, vanish: normal
// events, recorded, never an abort), SUMO's collisions (each contact once, under every
// collision.action), the egos to estimate with what is around them, and the egos' overlaps
// and hard braking (critical_events.h). Estimation of an ego pauses while it is teleported.
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "plugin/critical_events.h"
#include "plugin/driver_options.h"
#include "plugin/object_snapshot.h"
#include "plugin/route_ids.h"
#include "plugin/sumo_world.h"

namespace criticality::plugin {

/** A problem with a named ego that stays an error: SUMO never loads it, or it is a person. */
class EgoError : public std::runtime_error {
 public:
  explicit EgoError(const std::string& what) : std::runtime_error(what) {}
};

enum class EgoEventKind { kDepart, kArrive, kTeleportStart, kTeleportEnd, kVanish };
/** depart, arrive, teleport-start, teleport-end, vanish (the ego_events table's `event`). */
const char* EgoEventName(EgoEventKind kind);

struct EgoEvent {
  std::string ego;
  EgoEventKind kind{EgoEventKind::kDepart};
  std::string detail;
};

struct CollisionEvent {
  SumoCollision sumo;
  bool involves_ego{false};
};

struct Observation {
  double time_s{0.0};  ///< SUMO's stamp of the step (see sumo_world.h)
  std::vector<EgoEvent> ego_events;
  /** Collisions that began in this step (SUMO reports an overlapping pair at every step under
   *  collision.action warn; a pair is recorded once per contact). */
  std::vector<CollisionEvent> collisions;
  /** Vehicles and persons that arrived in this step (any, ego or not). */
  std::vector<std::string> arrived;
  /** The egos driving now (not teleported), each with what is around it. */
  Surroundings surroundings;
  /** Overlaps and hard braking of the egos that began in this step (critical_events.h). */
  std::vector<CriticalEvent> critical_events;
};

class ObserveStage {
 public:
  ObserveStage(const DriverOptions& options, SumoWorld* world, const ExtractionConfig& config);
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
  void PersonEgo(const std::string& id) const;

  const DriverOptions& options_;
  SumoWorld* world_;
  ExtractionConfig config_;
  std::set<std::string> named_;
  std::unordered_map<std::string, State> state_;  ///< all-vehicles: only those in the network
  RouteIds route_ids_;
  bool first_step_{true};
  long long egos_seen_{0};
  std::set<std::string> active_pairs_;
  CriticalEventDetector critical_;
};

}  // namespace criticality::plugin
