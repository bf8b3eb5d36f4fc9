#pragma once
// Stage 4 of a step: what the driver does with the estimates. Warning episodes (hysteresis
// between --warn-threshold and --warn-release), the criticality published to SUMO, and under
// --act brake a braking command while p >= --brake-threshold. The closed loop changes only this
// stage.
#include <map>
#include <string>
#include <vector>

#include "criticality/result.h"
#include "plugin/driver_options.h"
#include "plugin/scene_stage.h"
#include "plugin/sumo_world.h"

namespace criticality::plugin {

/** One ego's row of the step. */
struct EgoStep {
  std::string ego;
  double p_collision{0.0};
  double estimator_ms{0.0};
  int objects{0};
  double speed_mps{0.0};
  bool acting{false};
};

enum class WarningChange { kOpen, kPeak, kClose };
struct WarningEvent {
  std::string ego;
  WarningChange change{WarningChange::kOpen};
  double p_collision{0.0};
};

struct ActionEvent {
  std::string ego;
  std::string kind;  ///< brake | release
  double accel_mps2{0.0};
  double speed_mps{0.0};
  double p_collision{0.0};
};

struct ActOutcome {
  std::vector<EgoStep> steps;
  std::vector<WarningEvent> warnings;
  std::vector<ActionEvent> actions;
};

class ActStage {
 public:
  ActStage(const DriverOptions& options, SumoWorld* world);
  ActOutcome Run(const SceneBatch& batch, const std::vector<Result>& results);
  /** Warning episodes still open (ego -> true), e.g. to close them at the end. */
  std::vector<std::string> OpenEpisodes() const;
  /** Forgets an ego that left the simulation (its episode is closed by the caller). */
  void Forget(const std::string& ego) { state_.erase(ego); }

 private:
  struct EgoState {
    bool warning{false};
    double peak{0.0};
    bool braking{false};
  };
  const DriverOptions& options_;
  SumoWorld* world_;
  double dt_{0.1};
  std::map<std::string, EgoState> state_;
};

}  // namespace criticality::plugin
