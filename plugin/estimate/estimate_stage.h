#pragma once
// Stage 3 of a step: every ego's scene estimated, all egos of the step as one batch
// (Estimator::EstimateBatch: one set of launches on the GPU; on the CPU the backend spreads the
// batch over its threads). Results do not depend on how the batch is split: each estimate is
// deterministic.
#include <vector>

#include "criticality/estimator.h"
#include "plugin/scenes/scene_stage.h"

namespace criticality::plugin {

class EstimateStage {
 public:
  EstimateStage(const Params& params, const EstimatorOptions& options)
      : estimator_(params, options) {}
  /** results[k] belongs to batch.scenes[k]. */
  std::vector<Result> Run(const SceneBatch& batch) { return estimator_.EstimateBatch(batch.scenes); }
  /** One scene alone (the closed loop's hand-back check, between batches). */
  Result One(const Scene& scene) { return estimator_.Estimate(scene); }
  const Params& params() const { return estimator_.params(); }

 private:
  Estimator estimator_;
};

}  // namespace criticality::plugin
