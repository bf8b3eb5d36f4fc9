#pragma once
// The driver's view of a running SUMO, the same whether SUMO runs in-process (libsumo) or is
// attached through TraCI (libtraci): both APIs are identical, so sumo_world_impl.inc is
// compiled once for each (sumo_world_libsumo.cc, sumo_world_libtraci.cc).
// Errors: SumoError for anything SUMO reports (TraCIException, FatalTraCIError, load errors).
//
// Time stamps: after Step(), Time() is the time of the NEXT step; the state read then is the
// state SUMO's outputs (FCD, collision output) stamp with Time() - StepLength(). The driver
// stamps everything it records with that value (StampOfLastStep()).
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "criticality/scene.h"
#include "plugin/lane_corridor.h"
#include "plugin/object_snapshot.h"
#include "plugin/scenario_event.h"

namespace criticality::plugin {

class SumoError : public std::runtime_error {
 public:
  explicit SumoError(const std::string& what) : std::runtime_error(what) {}
};

/** One of SUMO's collisions (Simulation::getCollisions) as recorded. */
struct SumoCollision {
  std::string collider, victim, collider_type, victim_type, type;
  /** The collider's lane and its position along it. SUMO reports the victim's lane for
   *  collisions with a person (type crossing, walkingarea, sharedLane): then the collider's own
   *  lane and position are read (it is still there: SUMO takes no action on those). */
  std::string lane;
  double pos_m{0.0};
  /** Where: the collider's front bumper (network coordinates); NaN when unknown. */
  double x_m{0.0}, y_m{0.0};
  double collider_speed_mps{0.0}, victim_speed_mps{0.0};
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
  double accel_mps2{2.6};
  double emergency_decel_mps2{9.0};
  int speed_mode{31};        ///< the user's (as set before or while the closed loop acts)
  int lane_change_mode{0};   ///< as SUMO has it now
  std::string lane;
  int lane_index{0};
  int lanes{1};              ///< lanes of its edge
  double lane_width_m{3.2};
  double lateral_offset_m{0.0};  ///< from its lane's centre (getLateralLanePosition)
};

/** How SUMO moves vehicles sideways. */
struct LaneChanging {
  bool sublane{false};      ///< lateral-resolution > 0
  double duration_s{0.0};   ///< lanechange.duration: 0 = a lane change takes one step
};

/** Whether SUMO knows an ID (loaded, whether or not it departed yet). */
enum class Known { kUnknown, kVehicle, kPerson };

struct ExtractionConfig {
  double range_m{80.0};
  double horizon_s{2.0};
  double max_accel_mps2{9.7};  ///< for a lane corridor's length: v T + a T^2 / 2
  /** Every vehicle is an ego (--all-vehicles): read the whole network with one subscription
   *  per object and find neighbours here, instead of one context subscription per ego. */
  bool whole_network{false};
  /** How far lanes are sampled into a turn (LaneSamplingFor the estimator's parameters). */
  LaneSampling lane_sampling{};
};

class SumoWorld {
 public:
  virtual ~SumoWorld() = default;
  virtual std::string Version() = 0;
  virtual void Step() = 0;
  virtual double Time() = 0;
  virtual double StepLength() = 0;
  /** The configuration's end time (s); negative when none is set. */
  virtual double EndTime() = 0;
  /** A SUMO option's value ("" when unknown). */
  virtual std::string Option(const std::string& name) = 0;
  /** Vehicles and persons still expected (0: the simulation is over). */
  virtual int ExpectedObjects() = 0;
  /** Departures, arrivals, teleports and collisions of the step just made. */
  virtual StepReport Report() = 0;
  /** Vehicles in the network now (teleporting ones are not). */
  virtual std::vector<std::string> VehicleIds() = 0;
  virtual Known Lookup(const std::string& id) = 0;
  /** Reads `egos` (vehicles in the network) and the vehicles and persons around each, within
   *  cfg.range_m of its centre and more (scene building applies the exact range); every object
   *  is read once per step. */
  virtual Surroundings Observe(const std::vector<std::string>& egos,
                               const ExtractionConfig& cfg) = 0;
  /** A vehicle left the simulation: drop what is kept about it (memory stays flat). */
  virtual void Forget(const std::string& vehicle) = 0;
  /** Vehicle parameter "criticality" = p; the ego turns red while warning. */
  virtual void Publish(const std::string& ego, double p, bool warning) = 0;

  // ---- The closed loop (--act brake; act_stage.cc) ----------------------------------------
  /** What acting on a vehicle needs, read now (before this step's commands). */
  virtual VehicleControl ReadControl(const std::string& vehicle) = 0;
  /** Commands `speed` for the next step, under the user's speed mode with "regard maximum
   *  deceleration" (bit 2) cleared so that SUMO applies a deceleration up to the type's
   *  emergencyDecel (the caller never asks for more). Scripted speed events for the vehicle
   *  are then recorded (ReadControl's own speed includes them) but not sent until
   *  ReleaseSpeed. */
  virtual void CommandSpeed(const std::string& ego, double speed) = 0;
  /** Hands the speed back: the speed mode the user set, and the speed a scenario forces
   *  (setSpeed, or the rest of a slowDown still running), else setSpeed(-1). */
  virtual void ReleaseSpeed(const std::string& ego) = 0;
  /** changeLane(lane_index, hold_s): SUMO keeps trying for hold_s, subject to the vehicle's
   *  lane-change mode (bits 8-9: how a TraCI change regards other drivers). */
  virtual void ChangeLane(const std::string& ego, int lane_index, double hold_s) = 0;
  /** changeSublane(lateral_m) (sublane model; positive left). */
  virtual void ChangeSublane(const std::string& ego, double lateral_m) = 0;
  /** How this SUMO moves vehicles sideways (options lateral-resolution, lanechange.duration). */
  virtual LaneChanging LaneChangingModel() = 0;
  /** Applies a scripted event; returns false when its target is not in the network (yet). */
  virtual bool Apply(const ScenarioEvent& e) = 0;
  virtual void Close() = 0;

  /** The stamp of the step just made (see the file comment). */
  double StampOfLastStep() { return std::round((Time() - StepLength()) * 1e6) / 1e6; }
};

/** Loads SUMO in this process with these arguments (e.g. {"-c", "x.sumocfg", ...}). */
std::unique_ptr<SumoWorld> StartLibsumo(const std::vector<std::string>& args);
/** Attaches to a SUMO started with --remote-port; fails within a few seconds when nothing
 *  listens there. */
std::unique_ptr<SumoWorld> ConnectLibtraci(const std::string& host, int port);

}  // namespace criticality::plugin
