#pragma once
// What SUMO reports, as it reports it: plain data in SUMO's own conventions (a vehicle's
// position is its FRONT BUMPER centre, angles are navigation degrees: 0 = north, clockwise),
// no conversion and no geometry. The stages turn it into the estimator's conventions
// (plugin/sumo/sumo_conventions.h) and into scenes (plugin/scenes/).
#include <limits>
#include <string>
#include <vector>

namespace criticality::plugin {

/** A vehicle, or a person walking (persons riding in a vehicle are not reported), in one step.
 *  Values exactly as SUMO gave them: SUMO 1.15 reports some persons on walking areas with NaN
 *  position and angle, and such values are passed on for the stages to judge. */
struct SumoObject {
  std::string id;
  bool person{false};
  double x_m{0.0};  ///< a vehicle's front bumper centre, a person's position
  double y_m{0.0};
  double angle_deg{0.0};  ///< navigation degrees
  double speed_mps{0.0};
  std::string lane;  ///< "" when not on a lane
  // ---- vehicles ----
  double accel_mps2{0.0};
  double length_m{0.0};
  /** The length of SUMO's box of the body (MSVehicle::getBoundingBox, along its angle): from
   *  its front to its back on the lanes it came by, shorter than length_m while a turn bends
   *  the way between them; 0 when not measured (BodyLengthOf: then length_m). Measured by the
   *  observe stage (plugin/observe/vehicle_bodies.h). */
  double body_length_m{0.0};
  double width_m{0.0};
  double height_m{0.0};  ///< <= 0: unknown
  double decel_mps2{0.0};  ///< the type's normal maximum deceleration (SUMO's decel)
  std::string vehicle_class;  ///< SUMO's vClass ("passenger", "truck", ...)
  std::string vehicle_type;   ///< its vType's ID
  double lane_position_m{0.0};  ///< of the front bumper, along the lane
  int lane_index{0};
  std::vector<std::string> route;  ///< the edges of its route
  int route_index{0};              ///< the edge of the route it is on
  /** SUMO's stop state bits (getStopState): 1 stopped, 2 parking, 4 triggered by persons, 8 by
   *  containers, 16 at a bus stop, 32 at a container stop, 64 at a charging station, 128 in a
   *  parking area. */
  int stop_state{0};
  /** SUMO's signal bits (getSignals): 1 right blinker, 2 left blinker, 4 emergency blinker,
   *  8 brake light, ... */
  int signals{0};
  // ---- persons ----
  /** Its next edge (crossings and walking areas included); "" when its walk ends here. */
  std::string next_edge;
};

/** One step's objects, each reported once, and which of them are near each ego: SUMO's
 *  context subscription around each named ego, or, when the whole network is read, nothing
 *  (the observe stage finds the neighbours). */
struct SumoSurroundings {
  struct Ego {
    int self{-1};             ///< index into objects
    std::vector<int> nearby;  ///< indices of objects near it (a superset of those in range)
  };
  std::vector<SumoObject> objects;
  std::vector<Ego> egos;
  bool whole_network{false};  ///< every object was read; Ego::nearby is left empty
};

/** One of SUMO's collisions (Simulation::getCollisions) as reported. */
struct SumoCollision {
  std::string collider, victim, collider_type, victim_type, type;
  /** The collider's lane and its position along it. SUMO reports the victim's lane for
   *  collisions with a person (type crossing, walkingarea, sharedLane): then the collider's own
   *  lane and position are read (it is still there: SUMO takes no action on those). */
  std::string lane;
  double pos_m{0.0};
  /** Where: the collider's front bumper (network coordinates) when it was still in the
   *  network to be read; NaN otherwise (the observe stage then places it from lane and pos). */
  double x_m{0.0}, y_m{0.0};
  double collider_speed_mps{0.0}, victim_speed_mps{0.0};
  bool collider_present{true};  ///< still on the lane where it collided when it was read
};

/** SUMO's lists for the step just made. */
struct StepReport {
  std::vector<std::string> departed, arrived, teleport_start, teleport_end;
  std::vector<std::string> persons_departed, persons_arrived;
  std::vector<SumoCollision> collisions;
};

/** What the closed loop reads about a vehicle before acting on it. */
struct VehicleControl {
  /** SUMO's own choice of speed for the next step: a speed the scenario forces (a scripted
   *  setSpeed, or the ramp of a scripted slowDown, capped by the model's speed when the
   *  user's speed mode regards the safe speed), else the speed SUMO's model chose without
   *  TraCI (getSpeedWithoutTraCI: its car following, a route's stop; one step old). */
  double own_speed_mps{0.0};
  bool forced{false};  ///< own_speed_mps is a speed the scenario forces
  /** The fastest SUMO's own choice of speed could be once handed back: own_speed_mps, except
   *  while a speed of the closed loop is in force and the scenario forces none. SUMO 1.15's
   *  getSpeedWithoutTraCI then reports the speed driven, and this is the type's acceleration up
   *  to its allowed speed (getAllowedSpeed). Not capped by follow_speed_mps: a stopped car
   *  whose getFollowSpeed behind its getLeader was 0 drove off at 2.4 m/s^2 once handed back
   *  (bench/RESULTS.md, sixteenth stop). */
  double resume_speed_mps{0.0};
  /** The speed SUMO's car following gives now behind the vehicle's leader (getFollowSpeed
   *  with getLeader's gap, within its braking distance at the forced speed plus 50 m),
   *  whatever the scenario forces; +inf without a leader there. */
  double follow_speed_mps{std::numeric_limits<double>::infinity()};
  double accel_mps2{2.6};
  double emergency_decel_mps2{9.0};
  int speed_mode{31};       ///< the user's (as set before or while the closed loop acts)
  int lane_change_mode{0};  ///< as SUMO has it now
  std::string lane;
  int lane_index{0};
  int lanes{1};  ///< lanes of its edge
  double lane_width_m{3.2};
  double lateral_offset_m{0.0};  ///< from its lane's centre (getLateralLanePosition)
};

/** How SUMO moves vehicles sideways. */
struct LaneChanging {
  bool sublane{false};     ///< lateral-resolution > 0
  double duration_s{0.0};  ///< lanechange.duration: 0 = a lane change takes one step
};

/** Whether SUMO knows an ID (loaded, whether or not it departed yet). */
enum class Known { kUnknown, kVehicle, kPerson };

}  // namespace criticality::plugin
