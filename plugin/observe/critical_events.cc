#include "plugin/observe/critical_events.h"

#include <algorithm>
#include <cmath>

#include "criticality/geometry.h"
#include "criticality/scene.h"
#include "plugin/sumo/sumo_conventions.h"

namespace criticality::plugin {
namespace {

// An object's footprint where SUMO places it: a vehicle's box from its front to its back
// (BodyLengthOf: SUMO's box, shorter than the vehicle in a turn) x its width, a person the
// estimator's default pedestrian square.
struct Body {
  Pose2 centre;
  double half_length{0.0}, half_width{0.0};
};

Body BodyOf(const SumoObject& o) {
  const Pedestrian walker;
  Body b;
  b.centre = CentreOf(o);
  b.half_length = 0.5 * (o.person ? walker.length_m : BodyLengthOf(o));
  b.half_width = 0.5 * (o.person ? walker.width_m : o.width_m);
  return b;
}

bool Placed(const Body& b) {
  return std::isfinite(b.centre.x) && std::isfinite(b.centre.y) && std::isfinite(b.centre.yaw) &&
         b.half_length > 0.0 && b.half_width > 0.0;
}

bool Overlap(const Body& a, const Body& b) {
  return RectanglesOverlap(a.centre, a.half_length, a.half_width, b.centre, b.half_length,
                           b.half_width);
}

}  // namespace

const char* CriticalEventName(CriticalEvent::Kind kind) {
  return kind == CriticalEvent::Kind::kOverlap ? "overlap" : "hard-braking";
}

std::vector<CriticalEvent> CriticalEventDetector::Run(double time_s, const SumoSurroundings& s) {
  std::vector<CriticalEvent> out;
  std::set<std::pair<std::string, std::string>> overlapping;
  std::set<std::string> braking;
  for (const SumoSurroundings::Ego& e : s.egos) {
    const SumoObject& ego = s.objects[e.self];
    const double decel = -ego.accel_mps2;
    if (std::isfinite(decel) && ego.decel_mps2 > 0.0 &&
        decel > ego.decel_mps2 + kHardBrakingMarginMps2) {
      braking.insert(ego.id);
      if (!braking_.count(ego.id))
        out.push_back({time_s, ego.id, CriticalEvent::Kind::kHardBraking, "", decel});
    }
    const Body body = BodyOf(ego);
    if (!Placed(body)) continue;
    for (int k : e.nearby) {
      const SumoObject& o = s.objects[k];
      if (k == e.self) continue;
      const Body other = BodyOf(o);
      if (!Placed(other) || !Overlap(body, other)) continue;
      std::pair<std::string, std::string> pair{ego.id, o.id};
      if (!overlapping_.count(pair)) {
        out.push_back({time_s, ego.id, CriticalEvent::Kind::kOverlap, o.id,
                       std::isnan(ego.speed_mps) ? ego.speed_mps : std::max(0.0, ego.speed_mps)});
      }
      overlapping.insert(std::move(pair));
    }
  }
  overlapping_.swap(overlapping);
  braking_.swap(braking);
  return out;
}

}  // namespace criticality::plugin
