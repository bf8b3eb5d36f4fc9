#pragma once
// What scene building asks about the traffic of the current step beyond what each object's
// own report says: a vehicle's leader and its next traffic signal, as SUMO knows them now, and
// what its vehicle type says (accel, decel, emergencyDecel, maxSpeed, carriages). Raw
// answers (no thresholds, no plausibility: scene building decides what they mean). The SUMO
// adapter implements it (plugin/sumo/sumo_world.h); tests answer from memory.
#include <optional>
#include <string>

namespace criticality::plugin {

/** The vehicle ahead of a vehicle in its lanes (SUMO's getLeader), with its speed and
 *  acceleration. */
struct LeaderReport {
  std::string id;
  double gap_m{0.0};  ///< from the follower's front bumper + its minGap to the leader's back
  double speed_mps{0.0};
  double accel_mps2{0.0};
};

/** A vehicle's next traffic signal on its route (SUMO's getNextTLS, the first entry). */
struct SignalReport {
  double distance_m{0.0};  ///< from its front bumper to the signal's stop line
  char state{'G'};         ///< 'r' red, 'u' red-yellow, 'y'/'Y' yellow, 'g'/'G' green, ...
};

/** A vehicle type as SUMO defines it (VehicleType getters, read once per type); optional values
 *  are generic vType parameters that SUMO 1.15 keeps as such ("mass", and for trains and trams
 *  "locomotiveLength", "carriageLength", "carriageGap": how SUMO draws them). */
struct VehicleTypeReport {
  std::string vehicle_class;  ///< vClass: "passenger", "truck", "bicycle", "tram", "rail", ...
  double length_m{5.0};
  double width_m{1.8};
  double accel_mps2{2.6};
  double decel_mps2{4.5};
  double emergency_decel_mps2{9.0};
  double max_speed_mps{55.0};
  std::optional<double> mass_kg;
  std::optional<double> locomotive_length_m;
  std::optional<double> carriage_length_m;
  std::optional<double> carriage_gap_m;
};

class TrafficView {
 public:
  virtual ~TrafficView() = default;
  /** The leader within `look_ahead_m`; nullopt when there is none. */
  virtual std::optional<LeaderReport> Leader(const std::string& vehicle, double look_ahead_m) = 0;
  /** The next signal ahead; nullopt when none lies on its route. */
  virtual std::optional<SignalReport> NextSignal(const std::string& vehicle) = 0;
  /** The vehicle type `type_id` (cached: types do not change during a run). */
  virtual const VehicleTypeReport& TypeOf(const std::string& type_id) = 0;
};

}  // namespace criticality::plugin
