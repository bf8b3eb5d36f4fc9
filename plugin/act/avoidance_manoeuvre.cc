#include "plugin/act/avoidance_manoeuvre.h"

#include <algorithm>
#include <cmath>

namespace criticality::plugin {

bool MainThreatBehind(const Scene& scene, const Result& result) {
  const ObjectResult* main = MainObject(result);
  if (!main) return false;
  const ObjectState* state = nullptr;
  for (const Vehicle& v : scene.vehicles) {
    if (v.id == main->id) state = &v.state;
  }
  for (const Pedestrian& ped : scene.pedestrians) {
    if (ped.id == main->id) state = &ped.state;
  }
  if (!state) return false;
  const ObjectState& e = scene.ego.state;
  const double ahead =
      (state->x_m - e.x_m) * std::cos(e.yaw_rad) + (state->y_m - e.y_m) * std::sin(e.yaw_rad);
  return ahead < -0.5 * scene.ego.length_m;  // behind its rear, not beside its body
}

LateralPlan LateralPlanOf(const EscapeRoute& r, double lane_width_m) {
  LateralPlan plan;
  for (int lane : r.target_lanes) {
    if (lane != 0) {
      plan.direction = lane > 0 ? 1 : -1;
      break;
    }
  }
  if (plan.direction == 0) return plan;
  const size_t m = std::min(r.lateral_offset_m.size(), r.time_s.size());
  if (m == 0) return plan;
  double largest = 0.0;
  for (size_t k = 0; k < m; ++k)
    largest = std::max(largest, plan.direction * r.lateral_offset_m[k]);
  plan.cross_s = r.time_s[m - 1];
  for (size_t k = 0; k < m; ++k) {
    if (plan.direction * r.lateral_offset_m[k] >= 0.5 * lane_width_m) {
      plan.cross_s = r.time_s[k];
      break;
    }
  }
  plan.duration_s = r.time_s[m - 1];
  for (size_t k = 0; k < m; ++k) {
    if (plan.direction * r.lateral_offset_m[k] >= 0.9 * largest) {
      plan.duration_s = r.time_s[k];
      break;
    }
  }
  plan.final_offset_m = r.lateral_offset_m[m - 1];
  return plan;
}

const EscapeRoute* ChooseRoute(const std::vector<EscapeRoute>& ranked, bool may_steer) {
  for (const EscapeRoute& r : ranked) {
    if (may_steer || LateralPlanOf(r, 1.0).direction == 0) return &r;
  }
  return nullptr;
}

SpeedCommand ClosedLoopSpeed(const SpeedInputs& in, const BrakeModel& model, double step_s) {
  SpeedCommand out;
  if (!in.active) {
    if (in.route_accel_mps2 >= 0.0) return out;             // nothing to brake for
    if (in.elapsed_s + 1e-9 < model.latency_s) return out;  // the brake acts later
  }
  const double e = in.emergency_decel_mps2;
  const double ramp = model.jerk_mps3 * step_s;
  const double target = std::max(in.route_accel_mps2, -e);
  double a = target < in.previous_accel_mps2 ? std::max(target, in.previous_accel_mps2 - ramp)
                                             : std::min(target, in.previous_accel_mps2 + ramp);
  a = std::max(a, -e);
  out.command = true;
  out.accel_mps2 = a;
  const double lowest = std::max(0.0, in.speed_mps - e * step_s);  // emergencyDecel, no more
  out.speed_mps = std::max(lowest, std::min(in.own_speed_mps, in.speed_mps + a * step_s));
  return out;
}

}  // namespace criticality::plugin
