#pragma once
// The driver's view of a running SUMO, the same whether SUMO runs in-process (libsumo) or is
// attached through TraCI (libtraci): both APIs are identical, so sumo_world_impl.inc is
// compiled once for each (sumo_world_libsumo.cc, sumo_world_libtraci.cc).
// Errors: SumoError for anything SUMO reports (TraCIException, FatalTraCIError, load errors).
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "criticality/scene.h"
#include "plugin/scenario_event.h"

namespace criticality::plugin {

class SumoError : public std::runtime_error {
 public:
  explicit SumoError(const std::string& what) : std::runtime_error(what) {}
};

struct SumoCollision {
  std::string collider, victim, collider_type, victim_type, type, lane;
  double collider_speed{0.0}, victim_speed{0.0}, pos{0.0};
};

struct ExtractionConfig {
  double range_m{80.0};
  double horizon_s{2.0};
  double max_accel_mps2{9.7};  ///< for the reach: v T + a T^2 / 2
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
  /** Vehicles and persons still expected (0: the simulation is over). */
  virtual int ExpectedObjects() = 0;
  virtual std::vector<std::string> VehicleIds() = 0;
  virtual std::vector<std::string> ArrivedIds() = 0;
  virtual std::vector<std::string> TeleportingIds() = 0;
  virtual double Speed(const std::string& vehicle) = 0;
  virtual double EmergencyDecel(const std::string& vehicle) = 0;
  /** The ego, its lanes and every vehicle (with its own lanes) and pedestrian within range. */
  virtual Scene ExtractScene(const std::string& ego, const ExtractionConfig& cfg) = 0;
  /** Vehicle parameter "criticality" = p; the ego turns red while warning. */
  virtual void Publish(const std::string& ego, double p, bool warning) = 0;
  virtual void CommandSpeed(const std::string& ego, double speed) = 0;
  virtual void ReleaseSpeed(const std::string& ego) = 0;
  virtual std::vector<SumoCollision> Collisions() = 0;
  /** Applies a scripted event; returns false when its target is not in the simulation (yet). */
  virtual bool Apply(const ScenarioEvent& e) = 0;
  virtual void Close() = 0;
};

/** Loads SUMO in this process with these arguments (e.g. {"-c", "x.sumocfg", ...}). */
std::unique_ptr<SumoWorld> StartLibsumo(const std::vector<std::string>& args);
/** Attaches to a SUMO started with --remote-port. */
std::unique_ptr<SumoWorld> ConnectLibtraci(const std::string& host, int port);

}  // namespace criticality::plugin
