#include "plugin/estimate_stage.h"

namespace criticality::plugin {

EstimateStage::EstimateStage(const DriverOptions& o) : estimator_(o.params, o.estimator) {}

std::vector<Result> EstimateStage::Run(const SceneBatch& batch) {
  std::vector<Result> results;
  for (const Scene& scene : batch.scenes) results.push_back(estimator_.Estimate(scene));
  return results;
}

}  // namespace criticality::plugin
