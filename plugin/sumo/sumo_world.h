#pragma once
// The driver's view of a running SUMO, the same whether SUMO runs in-process (libsumo) or is
// attached through TraCI (libtraci): both APIs are identical, so sumo_world_impl.inc is
// compiled once for each (sumo_world_libsumo.cc, sumo_world_libtraci.cc). It reports what SUMO
// says (plugin/sumo/sumo_reports.h: raw values, no geometry), answers questions about the
// network and the traffic (RoadNetwork, TrafficView), and carries out commands. It builds no
// scene. Errors: SumoError for anything SUMO reports (TraCIException, FatalTraCIError, load
// errors).
//
// Time stamps: after Step(), Time() is the time of the NEXT step; the state read then is the
// state SUMO's outputs (FCD, collision output) stamp with Time() - StepLength(). The driver
// stamps everything it records with that value (StampOfLastStep()).
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "plugin/network/road_network.h"
#include "plugin/network/traffic_view.h"
#include "plugin/script/scenario_event.h"
#include "plugin/sumo/sumo_reports.h"

namespace criticality::plugin {

class SumoError : public std::runtime_error {
 public:
  explicit SumoError(const std::string& what) : std::runtime_error(what) {}
};

/** Which objects Observe reads. */
struct ReadScope {
  /** Named egos: each ego's context subscription reaches this far from its position (SUMO
   *  measures between front bumpers). */
  double context_range_m{115.0};
  /** Every vehicle is an ego (--all-vehicles): read the whole network with one subscription
   *  per object instead of one context subscription per ego. */
  bool whole_network{false};
};

class SumoWorld : public RoadNetwork, public TrafficView {
 public:
  ~SumoWorld() override = default;
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
  /** Reads `egos` (vehicles in the network) and the vehicles and walking persons around each
   *  (as ReadScope says); every object is read once per step. An ego that cannot be read
   *  (it left the network) is missing from the result's egos. */
  virtual SumoSurroundings Observe(const std::vector<std::string>& egos,
                                   const ReadScope& scope) = 0;
  /** A vehicle left the simulation: drop what is kept about it (memory stays flat). */
  virtual void Forget(const std::string& vehicle) = 0;
  /** Vehicle parameter "criticality" = p; the ego turns red while warning. */
  virtual void Publish(const std::string& ego, double p, bool warning) = 0;

  // ---- The closed loop (--act brake; plugin/act/closed_loop.cc) ---------------------------
  /** What acting on a vehicle needs, read now (before this step's commands). */
  virtual VehicleControl ReadControl(const std::string& vehicle) = 0;
  /** Commands `speed` for the next step, under the user's speed mode; with "regard maximum
   *  deceleration" (bit 2) set the vehicle's decel is its emergencyDecel until ReleaseSpeed,
   *  so that SUMO applies a deceleration up to emergencyDecel and never more, to our speed and
   *  to its own safe speed (the caller never asks for more). Scripted speed events for the
   *  vehicle are then recorded (ReadControl's own speed includes them) but not sent until
   *  ReleaseSpeed. */
  virtual void CommandSpeed(const std::string& ego, double speed) = 0;
  /** Hands the speed back: the type's decel, and the speed a scenario forces
   *  (setSpeed, or the rest of a slowDown still running), else setSpeed(-1). */
  virtual void ReleaseSpeed(const std::string& ego) = 0;
  /** changeLane(lane_index, hold_s): SUMO keeps trying for hold_s, subject to the vehicle's
   *  lane-change mode (bits 8-9: how a TraCI change regards other drivers). */
  virtual void ChangeLane(const std::string& ego, int lane_index, double hold_s) = 0;
  /** changeSublane(lateral_m) (sublane model; positive left). */
  virtual void ChangeSublane(const std::string& ego, double lateral_m) = 0;
  /** How this SUMO moves vehicles sideways (options lateral-resolution, lanechange.duration). */
  virtual LaneChanging LaneChangingModel() = 0;
  /** Whether SUMO moves vehicles by its ballistic update now instead of its Euler update: with
   *  --step-method.ballistic, and where SUMO switches to it by itself: a
   *  --default.action-step-length given (above 0), or a vehicle type loaded whose
   *  actionStepLength differs from the step length (SUMO warns "Setting it now"). Once true,
   *  always true; asked again each step, as SUMO switches when it loads such a type. SUMO keeps
   *  its Euler update where --step-method.ballistic false is given explicitly with such types,
   *  which the option's value cannot show: then this says ballistic all the same. */
  virtual bool BallisticUpdate() = 0;
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
