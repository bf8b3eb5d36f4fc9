#pragma once
// Stage 5 of a step: everything the step produced goes to the results database (and, with
// --record-scenes, each estimated scene to a file), committed once per step.
#include <map>
#include <string>

#include "plugin/act_stage.h"
#include "plugin/driver_options.h"
#include "plugin/observe_stage.h"
#include "plugin/results_db.h"
#include "plugin/scene_stage.h"

namespace criticality::plugin {

class RecordStage {
 public:
  RecordStage(const DriverOptions& options, ResultsDb* db);
  void Run(const Observation& obs, const SceneBatch& batch, const ActOutcome& acted);
  /** Ends the open warning episode of `ego` at `time_s` (it left, or the run ends). */
  void CloseEpisode(const std::string& ego, double time_s);

 private:
  const DriverOptions& options_;
  ResultsDb* db_;
  std::map<std::string, long long> open_episode_;  ///< ego -> warnings row
};

}  // namespace criticality::plugin
