#pragma once
// Stage 4 of a step: what the driver does with the estimates. Warning episodes (hysteresis
// between --warn-threshold and --warn-release), the criticality published to SUMO, and under
// --act brake a braking command while p >= --brake-threshold. An ego that arrives, vanishes or
// starts a teleport ends its episode. The closed loop changes only this stage.
#include <map>
#include <set>
#include <string>
#include <vector>

#include "criticality/result.h"
#include "plugin/driver_options.h"
#include "plugin/observe_stage.h"
#include "plugin/scene_stage.h"
#include "plugin/sumo_world.h"

namespace criticality::plugin {

/** One ego's row of the step. */
struct EgoStep {
  const ObjectSnapshot* ego{nullptr};
  double p_collision{0.0};
  double p_reference{0.0};
  double unavoidability{0.0};
  double estimator_ms{0.0};
  int objects{0};
  int objects_in_reach{0};
  bool shortcut{false};  ///< answered without trajectories (no object in reach)
  bool acting{false};
};

enum class WarningChange { kOpen, kPeak, kClose };
struct WarningEvent {
  std::string ego;
  WarningChange change{WarningChange::kOpen};
  double p_collision{0.0};
  double x_m{0.0}, y_m{0.0};  ///< where the ego was (kOpen)
  std::string edge;           ///< its edge (kOpen)
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
  ActOutcome Run(const Observation& obs, const SceneBatch& batch,
                 const std::vector<Result>& results);
  /** Egos whose warning episode is open (to close them when the run ends). */
  std::vector<std::string> OpenEpisodes() const;

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
  std::set<std::string> release_after_teleport_;
};

}  // namespace criticality::plugin
