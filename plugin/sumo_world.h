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

/** Whether SUMO knows an ID (loaded, whether or not it departed yet). */
enum class Known { kUnknown, kVehicle, kPerson };

struct ExtractionConfig {
  double range_m{80.0};
  double horizon_s{2.0};
  double max_accel_mps2{9.7};  ///< for a lane corridor's length: v T + a T^2 / 2
  /** Every vehicle is an ego (--all-vehicles): read the whole network with one subscription
   *  per object and find neighbours here, instead of one context subscription per ego. */
  bool whole_network{false};
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
  virtual double EmergencyDecel(const std::string& vehicle) = 0;
  /** Vehicle parameter "criticality" = p; the ego turns red while warning. */
  virtual void Publish(const std::string& ego, double p, bool warning) = 0;
  virtual void CommandSpeed(const std::string& ego, double speed) = 0;
  virtual void ReleaseSpeed(const std::string& ego) = 0;
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
