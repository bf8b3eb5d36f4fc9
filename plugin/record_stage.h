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
  /** Writes the step's rows; Commit() ends the step. */
  void Run(const Observation& obs, const SceneBatch& batch, const ActOutcome& acted);
  /** The step's time breakdown (written last, with the time the writing took so far). */
  void Commit(const StepTimeRow& times);
  /** Ends the open warning episode of `ego` at `time_s` (the run ends). */
  void CloseEpisode(const std::string& ego, double time_s);

  /** File name of a recorded scene: t<time>_<ego>.scene, the ego ID made safe for a file name
   *  ('/' and other unsafe bytes written as %XX). */
  static std::string SceneFileName(double time_s, const std::string& ego);

 private:
  const DriverOptions& options_;
  ResultsDb* db_;
  std::map<std::string, long long> open_episode_;  ///< ego -> warnings row
};

}  // namespace criticality::plugin
