#pragma once
// Stage 5 of a step: everything the step produced goes to the results database (and, with
// --record-scenes, each estimated scene to a file), committed once per step.
#include <map>
#include <set>
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
  /** Rows written to the egos table: egos estimated (again for one that left and came back). */
  long long EgosEstimated() const { return egos_estimated_; }

 private:
  void Scenes(double t, const SceneBatch& batch);
  /** Each ego once, at its first estimate (again after it left and came back). */
  void Egos(double t, const Observation& obs, const SceneBatch& batch);
  void Warnings(double t, const std::vector<WarningEvent>& warnings, const SceneBatch& batch);
  /** The scene of the warning's ego at the warning's start. */
  void StoreScene(double t, long long warning, const std::string& ego, const SceneBatch& batch);

  RecordConfig config_;
  ResultsDb* db_;
  std::map<std::string, long long> open_episode_;  ///< ego -> warnings row
  std::set<std::string> recorded_;                 ///< egos in the egos table (in the network)
  long long egos_estimated_{0};
};

}  // namespace criticality::plugin
