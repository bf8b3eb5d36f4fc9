#pragma once
/** @file
 * The input of one estimate: plain data, no SUMO types.
 *
 * Frames: every object state is given in one common planar frame W (the "scene frame": SUMO's
 * network coordinates, or any frame the caller likes), x and y in metres, yaw in radians
 * counter-clockwise from +x (math convention, NOT SUMO's navigation angle). Positions are the
 * object's centre of gravity, which we take as the centre of its rectangle.
 *
 * Lanes are given the way a camera delivers them (paper Sec. IV-A): each lane divider as three
 * points (closest, middle, farthest) in the LOCAL frame of the object that sees them: origin at
 * its centre of gravity, +x forward along its heading, +y to its left.
 */
#include <array>
#include <optional>
#include <string>
#include <vector>

namespace criticality {

/** A point in some planar frame, metres. */
struct Point2 {
  double x{0.0};
  double y{0.0};
};

/** One lane divider: three points (closest, middle, farthest) in the observer's local frame.
 *  Their x values (forward distances) must differ by at least 1 cm. */
struct LaneDivider {
  std::array<Point2, 3> points{};
};

/** One lane, delimited by two dividers as seen by the observer. */
struct Lane {
  LaneDivider left;   ///< the divider with the larger y (left of the lane, in the lane's direction)
  LaneDivider right;  ///< the divider with the smaller y
  /** True when traffic on this lane runs against the observer's direction of travel. */
  bool counter_traffic{false};
  /** True when the road runs straight from the closest to the middle samples and turns only
   *  beyond the middle one (the straight road before a junction turn): each divider is then
   *  fitted as the line through its first two points, continued by the parabola tangent to it
   *  through the third (Params::straight_before_turn). Needs x0 < x1 < x2 on both dividers. */
  bool straight_to_middle{false};
  /** > 0: the lane turns at a corner (a junction turn, a bend between two straights). The
   *  middle sample of each divider is then not on it but the corner: where the divider's
   *  straight through its first sample, along the road's direction there, meets its straight
   *  through its last sample, along the road's direction there. The divider follows the first
   *  straight, turns along the parabola tangent to both straights, and follows the second; the
   *  turn begins and ends this far (m, along the straights) from the corner. Lets three points
   *  carry a straight road into a sharp turn and out of it, which a parabola through three
   *  points on the road cannot (it swings out before the turn and on past its end;
   *  Params::lane_corners). Needs x0 < x1 < x2 on both dividers. */
  double corner_tangent_m{0.0};
};

/** Up to three lanes around an observer (paper Sec. IV-A): its own, the immediate left and the
 *  immediate right. A missing own lane is replaced by a virtual lane
 * (Params::virtual_lane_width_m); missing neighbours are simply not used. */
struct LaneSet {
  std::optional<Lane> own;
  std::optional<Lane> left;
  std::optional<Lane> right;
};

/** Kinematic state of an object in the scene frame W. */
struct ObjectState {
  double x_m{0.0};  ///< centre of gravity
  double y_m{0.0};
  double yaw_rad{0.0};         ///< heading, counter-clockwise from +x
  double speed_mps{0.0};       ///< speed over ground, >= 0
  double accel_mps2{0.0};      ///< current longitudinal acceleration
  double yaw_rate_radps{0.0};  ///< current yaw rate
  double sideslip_rad{0.0};    ///< current sideslip angle beta (0 when unknown)
  /** The longitudinal acceleration its driver is expected to choose next, when the caller knows
   *  something that asks for it: a slower vehicle ahead in its lane (car following), a stop line
   *  it must stop at. When set and below accel_mps2, it is the reference ("most likely")
   *  hypothesis' acceleration and the centre of the acceleration scores instead of the current
   *  acceleration (Params::expected_accel_reference). Vehicles, pedestrians (a person stopping
   *  where it must wait) and the ego. */
  std::optional<double> expected_accel_mps2;
  /** How far ahead along its way the vehicle leaves the scene, when the caller knows: the end
   *  of its route in a traffic simulation, where SUMO removes it. From there on its hypotheses
   *  collide with nothing (Params::route_end_leaves). Vehicles and the ego only; >= 0. */
  std::optional<double> route_end_m;
  /** The caller gave every reason to brake that it knows of this vehicle: its leader and its
   *  stop line (expected_accel_mps2, Vehicle::stop_line), with its lane's curve, which the
   *  estimator reads itself. A traffic simulation's scene does. With
   *  Params::release_unexplained_braking, a vehicle that brakes harder than all of them ask is
   *  expected to release its brake rather than brake on. Vehicles and the ego only. */
  bool braking_causes_known{false};
};

/** What kind of road user a vehicle is: its motion model and the range of its hypotheses
 *  (Params::road_user_classes; estimator/ALGORITHM.md, "Road users by class"). */
enum class RoadUser {
  kCar,         ///< passenger cars, vans, taxis: the paper's classes (vehicle_class.h)
  kMotorcycle,  ///< motorcycles and mopeds
  kBicycle,     ///< bicycles (and e-scooters): low speed, low acceleration, narrow
  kHeavy,       ///< trucks, trailers, buses, coaches: heavy, braking well below a car
  kRail,        ///< trains, trams, light rail: bound to their track, no lateral hypotheses
};

/** What the traffic simulation knows of a vehicle's type (SUMO's vType). Each value that is set
 *  bounds the vehicle's hypotheses; unset values take its road user class's
 *  (Params::RoadUserLimits). */
struct VehicleType {
  RoadUser road_user{RoadUser::kCar};
  std::optional<double> mass_kg;
  std::optional<double> accel_mps2;            ///< the largest acceleration it drives with (> 0)
  std::optional<double> decel_mps2;            ///< its normal largest deceleration (> 0)
  std::optional<double> emergency_decel_mps2;  ///< the largest deceleration it can brake at (> 0)
  std::optional<double> max_speed_mps;         ///< the type's top speed (> 0)
};

/** One more box of a long or articulated vehicle behind the ones before it (a train's or
 *  tram's carriages, a truck's trailer), placed by the caller along the vehicle's way (SUMO
 *  draws carriages along the lane). It moves with the vehicle's speed and acceleration along
 *  its own lane; the vehicle and its carriages are one object whose hypotheses are the
 *  vehicle's (estimator/ALGORITHM.md, "Long and articulated bodies"). */
struct Carriage {
  double x_m{0.0};  ///< centre (scene frame)
  double y_m{0.0};
  double yaw_rad{0.0};
  double yaw_rate_radps{0.0};
  double length_m{10.0};
  double width_m{2.5};
  /** Its lanes in ITS local frame (a carriage on a curved track follows its own piece of it);
   *  none: as for a vehicle without lanes, the ego's lanes seen from its frame when its centre
   *  lies in one of them along their direction, else a virtual lane along its heading. */
  std::optional<LaneSet> lanes;
};

/** Input limits (ValidateScene): every box (the ego's, a vehicle's, each carriage's, a
 *  pedestrian's) at most kMaxBoxLengthM long and kMaxBoxWidthM wide, at most kMaxCarriages
 *  carriages per vehicle. A longer body (a 700 m freight train) is more boxes: a caller whose
 *  object has more parts than kMaxCarriages + 1 joins neighbouring parts into boxes of up to
 *  kMaxBoxLengthM (estimator/ALGORITHM.md, "Long and articulated bodies"). */
constexpr double kMaxBoxLengthM = 400.0;
constexpr double kMaxBoxWidthM = 5.0;
constexpr int kMaxCarriages = 64;

/** The vehicle whose criticality is estimated. Simulated with the two-track model (with its
 *  type's limits and model parameters; a rail ego moves along its track). */
/** A line ahead of a vehicle at which the traffic rules oblige it to stop, as the traffic
 *  simulation (or a map and a signal detector) knows it. */
struct StopLine {
  enum class Reason {
    kRedLight,     ///< its next signal shows red (or red-yellow)
    kYellowLight,  ///< its next signal shows yellow
    kYield,        ///< a stop sign, or a yield line with a conflicting vehicle approaching
  };
  Reason reason{Reason::kRedLight};
  /** Distance along its path from its front bumper to the line, >= 0. */
  double distance_m{0.0};
};

/** The line a vehicle's body moves along as the traffic simulation moves it: SUMO keeps the
 *  middle of its front and of its back on the centre lines of its lanes and points it from its
 *  back to its front (MSVehicle::computeAngle), also through a junction, where its lanes turn
 *  tighter than a car steers and no parabola of the paper's lanes follows them. In the
 *  vehicle's local frame; at most kMaxWayPoints points, consecutive ones at least 1 cm apart,
 *  from at or behind its back (back_m >= 0) to as far ahead as it may go (beyond the last
 *  point it goes straight on). estimator/ALGORITHM.md, "Bodies on their way". */
struct Way {
  std::vector<Point2> points;
  double front_m{0.0};  ///< arc length along `points` of the middle of its front
  double back_m{0.0};   ///< ... and of its back (front_m minus its length along the way)
};
constexpr int kMaxWayPoints = 48;

struct Ego {
  std::string id{"ego"};
  ObjectState state;
  double length_m{4.5};
  double width_m{1.8};
  std::optional<double> height_m;  ///< when known, the vehicle class uses 8 classes instead of 6
  LaneSet lanes;                   ///< in the ego's local frame
  /** Its type: the class and limits of its hypotheses. The ego's body is one box (a long ego's
   *  carriages are not modelled). */
  VehicleType type;
  /** Where it must stop, when it must: with Params::ego_stop_obligations, a credible stop there
   *  becomes its reference (estimator/ALGORITHM.md, "Stop obligations"). */
  std::optional<StopLine> stop_line;
  /** Its way through a junction, as another vehicle's (Vehicle::way): with Params::ego_on_way
   *  (an experiment, off) its hypotheses move along it, each path beside it by its lateral
   *  samples (estimator/ALGORITHM.md, "Bodies on their way"). */
  std::optional<Way> way;
};

/** Another vehicle (a collision object, CO). Simulated with the one-track model (by its type:
 *  bicycles with the kinematic single-track model, rail vehicles along their track). */

struct Vehicle {
  std::string id;
  ObjectState state;
  double length_m{4.5};
  double width_m{1.8};
  std::optional<double> height_m;
  /** The vehicle's own lanes in ITS local frame, when known (e.g. crossing traffic at a junction
   *  follows its own road). When absent, the vehicle is associated by its centre of gravity to
   *  one of the ego's lanes and uses the ego's lanes seen from its own frame (paper Sec. IV-A);
   *  outside every ego lane it gets a virtual lane along its heading. */
  std::optional<LaneSet> lanes;
  /** Where it must stop, when it must (estimator/ALGORITHM.md, "Stop obligations"): its
   *  hypotheses then include braking to stop before the line as the most probable one. */
  std::optional<StopLine> stop_line;
  /** Its type: the class and limits of its hypotheses. */
  VehicleType type;
  /** The boxes of its body behind this one (length_m x width_m at state), front to back, at
   *  most kMaxCarriages. Each is simulated with the vehicle's speed and acceleration profiles
   *  along its own lane and checked for collisions like the vehicle's own box; the pair matrix
   *  and every result know only the vehicle (estimator/ALGORITHM.md, "Long and articulated
   *  bodies"). */
  std::vector<Carriage> carriages;
  /** Where given (and Params::bodies_on_way), its box moves along it: front and back on the
   *  way at every step of every hypothesis, which differ only in their speed (one path). */
  std::optional<Way> way;
};

/** A pedestrian (kinematic model, no lanes). SUMO's default person is 0.215 m x 0.478 m; a
 *  0.5 m square is the default footprint here. */
struct Pedestrian {
  std::string id;
  ObjectState state;
  double length_m{0.5};
  double width_m{0.5};
  /** Its walk goes on along the footway (a sidewalk or a corner's walking area, and no crossing
   *  next), as SUMO knows it: outside the ego's lanes, stepping onto them is then a manoeuvre
   *  whatever its heading (Params::footway_pedestrians; estimator/ALGORITHM.md, "Pedestrians on
   *  the footway"). */
  bool stays_on_footway{false};
};

/** Everything one estimate needs. */
struct Scene {
  Ego ego;
  std::vector<Vehicle> vehicles;
  std::vector<Pedestrian> pedestrians;
  /** How the world the scene comes from moves its objects. 0 (default): continuously, as in
   *  the real world (and SUMO's ballistic update). > 0: by the Euler update of a simulation
   *  with steps of this length, which moves each object over a step by its speed at the END of
   *  the step (SUMO's default: x += v_new * dt). A vehicle braking there stops v * dt / 2 short
   *  of where continuous braking stops it (6.5 m from 13 m/s with 1 s steps), and every future
   *  position is continuous motion's shifted along the course by (v(t) - v(0)) * dt / 2: the
   *  estimator predicts those positions (estimator/ALGORITHM.md, "The simulator's position
   *  update"). */
  double euler_update_step_s{0.0};
  /** Where a vehicle's body stands in a turn (experimental; estimator/ALGORITHM.md, "Bodies on
   *  their path"). false (default, the paper's): its box is centred on the path its centre
   *  follows, along its heading. true (SUMO's boxes, whose front and back both lie on the
   *  path): its box is centred at the centre of that chord, the sagitta kappa c^2 / 8 inside
   *  the path (c: the box's length, kappa: the curvature of its course, its yaw rate over its
   *  speed), still along its heading. Every vehicle's measured pose is then such a box: its
   *  model's centre starts the sagitta of its measured yaw rate outside it. */
  bool bodies_on_path{false};
};

}  // namespace criticality
