#pragma once
// Stage 3 of a step: every ego's scene estimated, all egos of the step as one batch.
#include <vector>

#include "criticality/estimator.h"
#include "plugin/driver_options.h"
#include "plugin/scene_stage.h"

namespace criticality::plugin {

class EstimateStage {
 public:
  explicit EstimateStage(const DriverOptions& options);
  /** results[k] belongs to batch.scenes[k]. */
  std::vector<Result> Run(const SceneBatch& batch);

 private:
  Estimator estimator_;
};

}  // namespace criticality::plugin
