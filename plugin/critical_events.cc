#include "plugin/critical_events.h"

#include <cmath>

#include "core/oriented_box.h"

namespace criticality::plugin {
namespace {

bool Placed(const ObjectSnapshot& o) {
  return std::isfinite(o.state.x_m) && std::isfinite(o.state.y_m) &&
         std::isfinite(o.state.yaw_rad) && o.length_m > 0.0 && o.width_m > 0.0;
}

core::OrientedBox<double> Body(const ObjectSnapshot& o) {
  return core::MakeBox(o.state.x_m, o.state.y_m, o.state.yaw_rad, 0.5 * o.length_m,
                       0.5 * o.width_m);
}

}  // namespace

const char* CriticalEventName(CriticalEvent::Kind kind) {
  return kind == CriticalEvent::Kind::kOverlap ? "overlap" : "hard-braking";
}

std::vector<CriticalEvent> CriticalEventDetector::Run(double time_s, const Surroundings& s) {
  std::vector<CriticalEvent> out;
  std::set<std::pair<std::string, std::string>> overlapping;
  std::set<std::string> braking;
  for (const Surroundings::Ego& e : s.egos) {
    const ObjectSnapshot& ego = s.objects[e.self];
    const double decel = -ego.state.accel_mps2;
    if (std::isfinite(decel) && ego.normal_decel_mps2 > 0.0 &&
        decel > ego.normal_decel_mps2 + kHardBrakingMarginMps2) {
      braking.insert(ego.id);
      if (!braking_.count(ego.id))
        out.push_back({time_s, ego.id, CriticalEvent::Kind::kHardBraking, "", decel});
    }
    if (!Placed(ego)) continue;
    const core::OrientedBox<double> body = Body(ego);
    for (int k : e.nearby) {
      const ObjectSnapshot& o = s.objects[k];
      if (k == e.self || !Placed(o) || !core::BoxesOverlap(body, Body(o))) continue;
      std::pair<std::string, std::string> pair{ego.id, o.id};
      if (!overlapping_.count(pair)) {
        out.push_back({time_s, ego.id, CriticalEvent::Kind::kOverlap, o.id, ego.state.speed_mps});
      }
      overlapping.insert(std::move(pair));
    }
  }
  overlapping_.swap(overlapping);
  braking_.swap(braking);
  return out;
}

}  // namespace criticality::plugin
