#pragma once
// Scripted events of a scenario ("at 4.0 s set vehicle ego's speed mode to 0"). They live in
// the scenario's config file as `event = TIME TARGET ACTION [ARGS...]` lines, never in code.
#include <string>
#include <vector>

namespace criticality::plugin {

enum class EventAction {
  kSpeedMode,       ///< speed-mode VEH BITS        (Vehicle::setSpeedMode)
  kLaneChangeMode,  ///< lane-change-mode VEH BITS  (Vehicle::setLaneChangeMode)
  kSpeed,           ///< speed VEH MPS              (Vehicle::setSpeed; -1 hands back to SUMO)
  kSlowDown,        ///< slow-down VEH MPS SECONDS  (Vehicle::slowDown)
  kLaneChange,      ///< lane-change VEH INDEX SECONDS (Vehicle::changeLane)
  kParam,           ///< param VEH KEY VALUE        (Vehicle::setParameter)
  kPersonSpeed,     ///< person-speed PERSON MPS    (Person::setSpeed)
};

struct ScenarioEvent {
  double time_s{0.0};
  std::string target;
  EventAction action{EventAction::kSpeed};
  std::string text;    ///< the line as written, for messages
  double number{0.0};  ///< speed, mode bits or lane index
  double duration_s{0.0};
  std::string key, value;  ///< for param
};

/** Parses "TIME TARGET ACTION ARGS..."; throws std::invalid_argument naming the problem. */
ScenarioEvent ParseEvent(const std::string& line);

}  // namespace criticality::plugin
