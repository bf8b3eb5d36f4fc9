#pragma once
// Stage 5 of a step: everything the step produced goes to the results database (and, with
// --record-scenes, each estimated scene to a file), committed once per step.
#include <map>
#include <string>

#include "plugin/act/act_outcome.h"
#include "plugin/observe/observation.h"
#include "plugin/record/results_db.h"
#include "plugin/scenes/scene_stage.h"

namespace criticality::plugin {

struct RecordConfig {
  /** --record-scenes: a folder for the scene files ("": none). */
  std::string scene_folder;
};

class RecordStage {
 public:
  RecordStage(const RecordConfig& config, ResultsDb* db);
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
  void Scenes(double t, const SceneBatch& batch);
  void Warnings(double t, const std::vector<WarningEvent>& warnings);

  RecordConfig config_;
  ResultsDb* db_;
  std::map<std::string, long long> open_episode_;  ///< ego -> warnings row
};

}  // namespace criticality::plugin
