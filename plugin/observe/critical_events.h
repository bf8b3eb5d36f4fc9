#pragma once
// What happened to each ego that a warning should have foreseen, as SUMO moved it, besides the
// collisions SUMO reports: its body overlapping another's, and braking harder than its normal
// maximum. Both are read from the step's snapshots (no SUMO calls), so that an evaluation can
// tell a warning before a near-crash from a false alarm (tools/evaluate).
//  - overlap: the ego's rectangle and another object's (the estimator's footprints: a vehicle's
//    length x width, a person's 0.5 m square; core::BoxesOverlap, touching counts) intersect.
//    SUMO's own check does not see every such contact: it does not check a person on a walking
//    area against a vehicle whose internal lane sweeps over that corner, for example.
//  - hard-braking: the ego decelerates harder than its vehicle type's decel (SUMO's normal
//    maximum; its drivers brake harder only when they must, up to emergencyDecel).
//  - pass-through: the ego's body and another's overlap neither at the step before nor at this
//    one, but do in between, with both moved along the straight line from one pose to the next
//    (heading turned evenly). SUMO checks collisions only at its steps; at 1 s steps two cars
//    crossing at 13 m/s can pass through each other between two steps unseen (bench/RESULTS.md,
//    2026-12-05, twelfth stop). A body that moved farther than its speeds allow (a teleport)
//    is not interpolated.
// Each overlap is reported once per contact (when a pair starts to overlap), each hard braking
// once per spell (when it starts), each pass-through once per step it happens in.
#include <set>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "criticality/geometry.h"
#include "plugin/sumo/sumo_reports.h"

namespace criticality::plugin {

struct CriticalEvent {
  enum class Kind { kOverlap, kHardBraking, kPassThrough };
  double time_s{0.0};
  std::string ego;
  Kind kind{Kind::kOverlap};
  std::string other;  ///< kOverlap, kPassThrough: the other object; kHardBraking: ""
  /** kOverlap, kPassThrough: the ego's speed (m/s); kHardBraking: its deceleration (m/s^2,
   *  positive). */
  double value{0.0};
};

/** overlap | hard-braking | pass-through (the critical_events table's `kind`). */
const char* CriticalEventName(CriticalEvent::Kind kind);

/** Margin above a vehicle's decel before its braking counts as hard (SUMO brakes at exactly
 *  decel when it stops normally). */
inline constexpr double kHardBrakingMarginMps2 = 0.1;

class CriticalEventDetector {
 public:
  /** The events that start in this step (time_s) among the egos of `s` and the objects near
   *  them. Objects with a non-finite position or heading are skipped. */
  std::vector<CriticalEvent> Run(double time_s, const SumoSurroundings& s);

  /** A footprint where SUMO places an object (see critical_events.cc), and its speed. */
  struct Body {
    Pose2 centre;
    double half_length{0.0}, half_width{0.0}, speed_mps{0.0};
  };

 private:
  double last_time_s_{0.0};
  std::unordered_map<std::string, Body> last_;  ///< every placed object's body at the last step
  std::set<std::pair<std::string, std::string>> overlapping_;  ///< (ego, other) in contact
  std::set<std::string> braking_;                              ///< egos braking hard
};

}  // namespace criticality::plugin
