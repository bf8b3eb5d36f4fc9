#pragma once
// What the observe stage hands on after each step: the step's stamp, the egos' life cycle
// (depart, arrive, teleport start and end, vanish: normal events, recorded, never an abort),
// SUMO's collisions (each contact once), the egos to estimate with what SUMO reports around
// them (raw, plugin/sumo/sumo_reports.h), and the egos' overlaps and hard braking.
#include <string>
#include <vector>

#include "plugin/observe/critical_events.h"
#include "plugin/sumo/sumo_reports.h"

namespace criticality::plugin {

enum class EgoEventKind { kDepart, kArrive, kTeleportStart, kTeleportEnd, kVanish };
/** depart, arrive, teleport-start, teleport-end, vanish (the ego_events table's `event`). */
const char* EgoEventName(EgoEventKind kind);
/** The ego leaves the road with this event (it arrives, vanishes or begins a teleport): its
 *  warning episode and engagement end, and nothing is written to it in SUMO any more. */
inline bool LeavesTheRoad(EgoEventKind kind) {
  return kind == EgoEventKind::kArrive || kind == EgoEventKind::kVanish ||
         kind == EgoEventKind::kTeleportStart;
}

struct EgoEvent {
  std::string ego;
  EgoEventKind kind{EgoEventKind::kDepart};
  std::string detail;
};

struct CollisionEvent {
  SumoCollision sumo;  ///< placed: x_m, y_m are the collider's front bumper where known
  bool involves_ego{false};
};

struct Observation {
  double time_s{0.0};  ///< SUMO's stamp of the step (plugin/sumo/sumo_world.h)
  /** SUMO's clock after the step (SumoWorld::Time()): rates between steps (a yaw rate from
   *  the heading change) are taken over its differences. */
  double sumo_time_s{0.0};
  std::vector<EgoEvent> ego_events;
  /** Collisions that began in this step (SUMO reports an overlapping pair at every step under
   *  collision.action warn; a pair is recorded once per contact). */
  std::vector<CollisionEvent> collisions;
  /** Vehicles and persons that arrived in this step (any, ego or not). */
  std::vector<std::string> arrived;
  /** Vehicles that left the simulation in this step (arrived, or egos that vanished): what is
   *  kept about them may go. */
  std::vector<std::string> left;
  /** Vehicles whose teleport started or ended in this step (any, ego or not): a heading read
   *  before it says nothing about the one after it. */
  std::vector<std::string> teleported;
  /** The egos driving now (not teleported), each with what is around it (Ego::nearby always
   *  filled, also when the whole network was read). */
  SumoSurroundings surroundings;
  /** Overlaps and hard braking of the egos that began in this step. */
  std::vector<CriticalEvent> critical_events;
};

}  // namespace criticality::plugin
