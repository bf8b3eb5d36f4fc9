#include "src/validation.h"

#include <cmath>
#include <sstream>
#include <string>

#include "core/hypothesis_set.h"
#include "criticality/errors.h"

namespace criticality {
namespace {

template <typename T>
[[noreturn]] void Fail(const std::string& field, T value, const std::string& rule) {
  std::ostringstream msg;
  msg << field << " = " << value << ": " << rule;
  throw InputError(msg.str());
}

void RequireFinite(const std::string& field, double v) {
  if (!std::isfinite(v)) Fail(field, v, "must be a finite number");
}

void RequirePositive(const std::string& field, double v) {
  RequireFinite(field, v);
  if (!(v > 0.0)) Fail(field, v, "must be > 0");
}

void RequireRange(const std::string& field, int v, int lo, int hi) {
  if (v < lo || v > hi) {
    Fail(field, v, "must be between " + std::to_string(lo) + " and " + std::to_string(hi));
  }
}

void ValidateState(const std::string& where, const ObjectState& s) {
  RequireFinite(where + ".x_m", s.x_m);
  RequireFinite(where + ".y_m", s.y_m);
  RequireFinite(where + ".yaw_rad", s.yaw_rad);
  RequireFinite(where + ".speed_mps", s.speed_mps);
  if (s.speed_mps < 0.0) Fail(where + ".speed_mps", s.speed_mps, "must be >= 0");
  if (s.speed_mps > 150.0) Fail(where + ".speed_mps", s.speed_mps, "must be <= 150 m/s");
  RequireFinite(where + ".accel_mps2", s.accel_mps2);
  if (s.expected_accel_mps2) RequireFinite(where + ".expected_accel_mps2", *s.expected_accel_mps2);
  if (s.route_end_m && !(*s.route_end_m >= 0.0 && std::isfinite(*s.route_end_m))) {
    std::ostringstream msg;
    msg << where << ".route_end_m = " << *s.route_end_m
        << ": must be a finite distance >= 0 (m), or unset when the vehicle stays";
    throw InputError(msg.str());
  }
  RequireFinite(where + ".yaw_rate_radps", s.yaw_rate_radps);
  RequireFinite(where + ".sideslip_rad", s.sideslip_rad);
  if (std::fabs(s.sideslip_rad) > 1.0)
    Fail(where + ".sideslip_rad", s.sideslip_rad, "must be within +-1 rad");
}

void ValidateSize(const std::string& where, double length, double width,
                  const std::optional<double>& height) {
  RequirePositive(where + ".length_m", length);
  RequirePositive(where + ".width_m", width);
  if (length > kMaxBoxLengthM)
    Fail(where + ".length_m", length,
         "must be <= 400 m (a longer body is a vehicle with carriages)");
  if (width > kMaxBoxWidthM) Fail(where + ".width_m", width, "must be <= 5 m");
  if (height) RequirePositive(where + ".height_m", *height);
}

void ValidateType(const std::string& where, const VehicleType& t) {
  const int c = static_cast<int>(t.road_user);
  if (c < static_cast<int>(RoadUser::kCar) || c > static_cast<int>(RoadUser::kRail))
    Fail(where + ".road_user", c, "must be kCar, kMotorcycle, kBicycle, kHeavy or kRail");
  auto positive = [&](const char* field, const std::optional<double>& v) {
    if (v) RequirePositive(where + "." + field, *v);
  };
  positive("mass_kg", t.mass_kg);
  positive("accel_mps2", t.accel_mps2);
  positive("decel_mps2", t.decel_mps2);
  positive("emergency_decel_mps2", t.emergency_decel_mps2);
  positive("max_speed_mps", t.max_speed_mps);
}

void ValidateCarriages(const std::string& where, const std::vector<Carriage>& carriages) {
  if (carriages.size() > static_cast<size_t>(kMaxCarriages))
    Fail(where + ".carriages (count)", carriages.size(),
         "must be at most 64 (join neighbouring carriages into boxes of up to 400 m)");
  for (size_t k = 0; k < carriages.size(); ++k) {
    const Carriage& c = carriages[k];
    const std::string at = where + ".carriages[" + std::to_string(k) + "]";
    RequireFinite(at + ".x_m", c.x_m);
    RequireFinite(at + ".y_m", c.y_m);
    RequireFinite(at + ".yaw_rad", c.yaw_rad);
    RequireFinite(at + ".yaw_rate_radps", c.yaw_rate_radps);
    ValidateSize(at, c.length_m, c.width_m, std::nullopt);
  }
}

void ValidateWay(const std::string& where, const Way& way) {
  const size_t n = way.points.size();
  if (n < 2 || n > static_cast<size_t>(kMaxWayPoints))
    Fail(where + ".points (count)", n, "must be from 2 to 48");
  double length = 0.0;
  for (size_t k = 0; k < n; ++k) {
    const std::string at = where + ".points[" + std::to_string(k) + "]";
    RequireFinite(at + ".x", way.points[k].x);
    RequireFinite(at + ".y", way.points[k].y);
    if (k == 0) continue;
    const double d =
        std::hypot(way.points[k].x - way.points[k - 1].x, way.points[k].y - way.points[k - 1].y);
    if (d < 0.01) Fail(at, d, "must lie at least 1 cm from the point before it");
    length += d;
  }
  RequireFinite(where + ".front_m", way.front_m);
  RequireFinite(where + ".back_m", way.back_m);
  if (way.back_m < 0.0) Fail(where + ".back_m", way.back_m, "must be >= 0 (on the way)");
  if (!(way.front_m > way.back_m))
    Fail(where + ".front_m", way.front_m, "must lie ahead of back_m");
  if (way.front_m > length) Fail(where + ".front_m", way.front_m, "must lie on the way");
}

void ValidateLimits(const std::string& where, const RoadUserLimits& c) {
  RequirePositive(where + ".accel_mps2", c.accel_mps2);
  RequirePositive(where + ".decel_mps2", c.decel_mps2);
  RequirePositive(where + ".emergency_decel_mps2", c.emergency_decel_mps2);
  RequirePositive(where + ".max_speed_mps", c.max_speed_mps);
  RequirePositive(where + ".mass_kg", c.mass_kg);
  RequirePositive(where + ".power_per_mass_wpkg", c.power_per_mass_wpkg);
  RequirePositive(where + ".wheelbase_share", c.wheelbase_share);
  RequirePositive(where + ".wheelbase_min_m", c.wheelbase_min_m);
  RequireFinite(where + ".wheelbase_max_m", c.wheelbase_max_m);
  if (c.wheelbase_max_m < c.wheelbase_min_m)
    Fail(where + ".wheelbase_max_m", c.wheelbase_max_m, "must be >= wheelbase_min_m");
  RequirePositive(where + ".cornering_stiffness_per_kg", c.cornering_stiffness_per_kg);
}

}  // namespace

int Params::TimeSteps() const { return static_cast<int>(std::llround(horizon_s / step_s)); }

const RoadUserLimits* Params::LimitsOf(RoadUser road_user) const {
  switch (road_user) {
    case RoadUser::kCar:
      return nullptr;
    case RoadUser::kMotorcycle:
      return &motorcycle;
    case RoadUser::kBicycle:
      return &bicycle;
    case RoadUser::kHeavy:
      return &heavy;
    case RoadUser::kRail:
      return &rail;
  }
  return nullptr;
}

void ValidateParams(const Params& p) {
  RequirePositive("params.horizon_s", p.horizon_s);
  RequirePositive("params.step_s", p.step_s);
  if (p.step_s > p.horizon_s) Fail("params.step_s", p.step_s, "must not exceed horizon_s");
  const double steps = p.horizon_s / p.step_s;
  if (steps > 32767.0)
    Fail("params.horizon_s / params.step_s", steps, "must be at most 32767 steps");
  if (std::fabs(steps - std::round(steps)) > 1e-6 * steps) {
    Fail("params.horizon_s / params.step_s", steps, "must be a whole number of steps");
  }
  RequireRange("params.profiles", p.profiles, 3, core::kMaxProfiles);
  RequireFinite("params.vehicle_accel_min_mps2", p.vehicle_accel_min_mps2);
  RequireFinite("params.vehicle_accel_max_mps2", p.vehicle_accel_max_mps2);
  if (!(p.vehicle_accel_min_mps2 < 0.0))
    Fail("params.vehicle_accel_min_mps2", p.vehicle_accel_min_mps2, "must be < 0");
  if (!(p.vehicle_accel_max_mps2 > 0.0))
    Fail("params.vehicle_accel_max_mps2", p.vehicle_accel_max_mps2, "must be > 0");
  RequireFinite("params.ego_slip_min", p.ego_slip_min);
  RequireFinite("params.ego_slip_max", p.ego_slip_max);
  if (!(p.ego_slip_min < 0.0 && p.ego_slip_min >= -1.0))
    Fail("params.ego_slip_min", p.ego_slip_min, "must be in [-1, 0)");
  if (!(p.ego_slip_max > 0.0 && p.ego_slip_max <= 1.0))
    Fail("params.ego_slip_max", p.ego_slip_max, "must be in (0, 1]");
  RequireFinite("params.latency_s", p.latency_s);
  if (p.latency_s < 0.0) Fail("params.latency_s", p.latency_s, "must be >= 0");
  RequirePositive("params.jerk_mps3", p.jerk_mps3);
  const int n_instants = static_cast<int>(p.path_sample_times_s.size());
  RequireRange("params.path_sample_times_s (count)", n_instants, 1, core::kMaxSampleInstants);
  for (int k = 0; k < n_instants; ++k) {
    const std::string f = "params.path_sample_times_s[" + std::to_string(k) + "]";
    RequirePositive(f, p.path_sample_times_s[k]);
    if (k > 0 && !(p.path_sample_times_s[k] > p.path_sample_times_s[k - 1]))
      Fail(f, p.path_sample_times_s[k], "must be greater than the previous sample time");
    if (p.path_sample_times_s[k] > p.horizon_s + 1e-9)
      Fail(f, p.path_sample_times_s[k], "must not exceed horizon_s");
  }
  RequireRange("params.own_lane_samples", p.own_lane_samples, 1, 8);
  RequireRange("params.neighbour_lane_samples", p.neighbour_lane_samples, 0, 4);
  RequireRange("params.hold_line_max_width_share", p.hold_line_max_width_share, 0.0, 1.0);
  if (p.LateralSamplesThreeLanes() > core::kMaxLateralSamples) {
    Fail("params.own_lane_samples + 2 * neighbour_lane_samples", p.LateralSamplesThreeLanes(),
         "must be at most " + std::to_string(core::kMaxLateralSamples));
  }
  RequireRange("params.pedestrian_headings", p.pedestrian_headings, 1, core::kMaxLateralSamples);
  RequireFinite("params.pedestrian_accel_min_mps2", p.pedestrian_accel_min_mps2);
  RequireFinite("params.pedestrian_accel_max_mps2", p.pedestrian_accel_max_mps2);
  if (!(p.pedestrian_accel_min_mps2 < p.pedestrian_accel_max_mps2))
    Fail("params.pedestrian_accel_min_mps2", p.pedestrian_accel_min_mps2,
         "must be < pedestrian_accel_max_mps2");
  RequirePositive("params.pedestrian_max_speed_mps", p.pedestrian_max_speed_mps);
  RequirePositive("params.max_steer_rad", p.max_steer_rad);
  if (p.max_steer_rad > 1.2) Fail("params.max_steer_rad", p.max_steer_rad, "must be <= 1.2 rad");
  RequirePositive("params.max_steer_rate_radps", p.max_steer_rate_radps);
  RequirePositive("params.preview_s_per_mps", p.preview_s_per_mps);
  RequireFinite("params.preview_min_s", p.preview_min_s);
  if (p.preview_min_s < 0.0) Fail("params.preview_min_s", p.preview_min_s, "must be >= 0");
  RequireFinite("params.preview_max_s", p.preview_max_s);
  if (p.preview_max_s < p.preview_min_s)
    Fail("params.preview_max_s", p.preview_max_s, "must be >= preview_min_s");
  RequireFinite("params.kinematic_below_mps", p.kinematic_below_mps);
  if (p.kinematic_below_mps < 0.0)
    Fail("params.kinematic_below_mps", p.kinematic_below_mps, "must be >= 0");
  RequirePositive("params.euler_stability_factor", p.euler_stability_factor);
  RequirePositive("params.friction", p.friction);
  if (p.friction > 2.0) Fail("params.friction", p.friction, "must be <= 2");
  RequirePositive("params.virtual_lane_width_m", p.virtual_lane_width_m);
  RequireFinite("params.w_acc", p.w_acc);
  RequireFinite("params.w_str", p.w_str);
  if (p.w_acc < 0.0) Fail("params.w_acc", p.w_acc, "must be >= 0");
  if (p.w_str < 0.0) Fail("params.w_str", p.w_str, "must be >= 0");
  if (!(p.w_acc + p.w_str > 0.0))
    Fail("params.w_acc + params.w_str", p.w_acc + p.w_str, "must be > 0");
  RequireFinite("params.steer_latency_s", p.steer_latency_s);
  if (p.steer_latency_s < 0.0) Fail("params.steer_latency_s", p.steer_latency_s, "must be >= 0");
  RequirePositive("params.drive_traction_share", p.drive_traction_share);
  if (p.drive_traction_share > 1.0)
    Fail("params.drive_traction_share", p.drive_traction_share, "must be <= 1");
  if (p.scoring != Params::Scoring::kPaperLiteral && p.scoring != Params::Scoring::kNaturalistic)
    Fail("params.scoring", static_cast<int>(p.scoring), "must be kPaperLiteral or kNaturalistic");
  RequirePositive("params.accel_score_sigma_mps2", p.accel_score_sigma_mps2);
  RequirePositive("params.decel_score_sigma_mps2", p.decel_score_sigma_mps2);
  RequirePositive("params.lateral_offset_sigma_m", p.lateral_offset_sigma_m);
  RequirePositive("params.heading_score_sigma_rad", p.heading_score_sigma_rad);
  RequirePositive("params.pedestrian_speed_sigma_mps", p.pedestrian_speed_sigma_mps);
  RequireFinite("params.lane_crossing_penalty", p.lane_crossing_penalty);
  if (p.lane_crossing_penalty < 1.0)
    Fail("params.lane_crossing_penalty", p.lane_crossing_penalty, "must be >= 1");
  RequirePositive("params.accel_score_scale", p.accel_score_scale);
  RequirePositive("params.path_score_scale_m", p.path_score_scale_m);
  RequirePositive("params.heading_score_scale_rad", p.heading_score_scale_rad);
  RequireFinite("params.complexity_penalty", p.complexity_penalty);
  if (p.complexity_penalty < 0.0)
    Fail("params.complexity_penalty", p.complexity_penalty, "must be >= 0");
  RequireFinite("params.counter_traffic_penalty", p.counter_traffic_penalty);
  if (p.counter_traffic_penalty < 1.0)
    Fail("params.counter_traffic_penalty", p.counter_traffic_penalty, "must be >= 1");
  RequireFinite("params.stop_violation_probability", p.stop_violation_probability);
  if (p.stop_violation_probability < 0.0 || p.stop_violation_probability > 1.0)
    Fail("params.stop_violation_probability", p.stop_violation_probability, "must be within 0..1");
  RequirePositive("params.stop_comfortable_decel_mps2", p.stop_comfortable_decel_mps2);
  RequirePositive("params.curve_lateral_accel_mps2", p.curve_lateral_accel_mps2);
  RequirePositive("params.curve_decel_max_mps2", p.curve_decel_max_mps2);
  RequireFinite("params.turn_lane_frame_min_rad", p.turn_lane_frame_min_rad);
  if (p.turn_lane_frame_min_rad < 0.0)
    Fail("params.turn_lane_frame_min_rad", p.turn_lane_frame_min_rad, "must be >= 0");
  ValidateLimits("params.motorcycle", p.motorcycle);
  ValidateLimits("params.bicycle", p.bicycle);
  ValidateLimits("params.heavy", p.heavy);
  ValidateLimits("params.rail", p.rail);
  RequirePositive("params.yaw_inertia_box_share", p.yaw_inertia_box_share);
  if (p.max_escape_routes < 0)
    Fail("params.max_escape_routes", p.max_escape_routes, "must be >= 0");
  if (p.max_memory_bytes == 0) Fail("params.max_memory_bytes", p.max_memory_bytes, "must be > 0");
}

Params ParamsPreset(const std::string& name) {
  Params p;
  if (name == "default") return p;
  if (name == "paper-literal") {
    p.steer_latency_s = 0.0;
    p.friction_limited_lateral = false;
    p.power_limited_drive = false;
    p.ego_profiles_in_accel = false;
    p.profiles_include_current_accel = false;
    p.expected_accel_reference = false;
    p.scoring = Params::Scoring::kPaperLiteral;
    p.w_acc = 1.0;
    p.w_str = 1.0;
    p.counter_traffic_penalty = 4.0;
    p.stop_obligations = false;
    p.turn_lane_frame = false;
    p.steer_curvature_feedforward = false;
    p.footway_pedestrians = false;
    p.curve_speed_reference = false;
    p.straight_before_turn = false;
    p.straight_before_turn_by_fit = false;
    p.hold_line_max_width_share = 0.0;
    p.lane_fit_within_lane = false;
    p.expected_accel_at_once = false;
    p.stop_obligation_at_once = false;
    p.route_end_leaves = false;
    p.road_user_classes = false;
    p.bodies_on_way = false;
    return p;
  }
  std::string names;
  for (const std::string& n : ParamsPresetNames()) names += (names.empty() ? "" : " or ") + n;
  throw InputError("preset = '" + name + "': unknown; use " + names);
}

std::vector<std::string> ParamsPresetNames() { return {"default", "paper-literal"}; }

namespace internal {

std::string ObjectName(const std::string& list, size_t index, const std::string& id) {
  std::string name = list + "[" + std::to_string(index) + "]";
  if (!id.empty()) name += " ('" + id + "')";
  return name;
}

void ValidateScene(const Scene& scene, const Params& /*params*/) {
  const size_t objects = scene.vehicles.size() + scene.pedestrians.size();
  if (objects > 65535)
    Fail("scene.vehicles + scene.pedestrians (count)", objects, "must be at most 65535 objects");
  RequireFinite("scene.euler_update_step_s", scene.euler_update_step_s);
  if (scene.euler_update_step_s < 0.0 || scene.euler_update_step_s > 10.0)
    Fail("scene.euler_update_step_s", scene.euler_update_step_s,
         "must be in [0, 10] s (0: continuous motion)");
  ValidateState("scene.ego.state", scene.ego.state);
  ValidateSize("scene.ego", scene.ego.length_m, scene.ego.width_m, scene.ego.height_m);
  ValidateType("scene.ego.type", scene.ego.type);
  if (scene.ego.way) ValidateWay("scene.ego.way", *scene.ego.way);
  if (const auto& stop = scene.ego.stop_line) {
    RequireFinite("scene.ego.stop_line.distance_m", stop->distance_m);
    if (stop->distance_m < 0.0)
      Fail("scene.ego.stop_line.distance_m", stop->distance_m, "must be >= 0");
  }
  for (size_t i = 0; i < scene.vehicles.size(); ++i) {
    const Vehicle& v = scene.vehicles[i];
    const std::string where = ObjectName("scene.vehicles", i, v.id);
    ValidateState(where + ".state", v.state);
    ValidateSize(where, v.length_m, v.width_m, v.height_m);
    if (const auto& stop = v.stop_line) {
      RequireFinite(where + ".stop_line.distance_m", stop->distance_m);
      if (stop->distance_m < 0.0)
        Fail(where + ".stop_line.distance_m", stop->distance_m, "must be >= 0");
    }
    ValidateType(where + ".type", v.type);
    ValidateCarriages(where, v.carriages);
    if (v.way) ValidateWay(where + ".way", *v.way);
  }
  for (size_t i = 0; i < scene.pedestrians.size(); ++i) {
    const std::string where = ObjectName("scene.pedestrians", i, scene.pedestrians[i].id);
    ValidateState(where + ".state", scene.pedestrians[i].state);
    ValidateSize(where, scene.pedestrians[i].length_m, scene.pedestrians[i].width_m, std::nullopt);
  }
}

}  // namespace internal
}  // namespace criticality
