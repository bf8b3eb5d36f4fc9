#pragma once
// Stage 4 of a step: what the driver does with the estimates. Warning episodes on the --warn-on
// estimate (warning_episodes.h), the criticality published to SUMO (vehicle parameter
// "criticality", the ego red while warning), and under --act brake the closed loop
// (closed_loop.h). An ego that arrives, vanishes or starts a teleport ends its episode and its
// engagement. Every estimated ego gets its row of the step.
#include <functional>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "criticality/result.h"
#include "plugin/act/act_config.h"
#include "plugin/act/act_outcome.h"
#include "plugin/act/closed_loop.h"
#include "plugin/act/warning_episodes.h"
#include "plugin/observe/observation.h"
#include "plugin/scenes/scene_stage.h"
#include "plugin/sumo/sumo_world.h"

namespace criticality::plugin {

/** Which egos the criticality is published to: every one (the step was just made), every one but
 *  those that left SUMO or began a teleport since (the pipelined loop acts on a step after SUMO
 *  made the next one), or none (SUMO failed). Episodes and rows are the same either way. */
struct PublishTo {
  bool any{true};
  std::unordered_set<std::string> gone;
  bool Reaches(const std::string& ego) const { return any && gone.count(ego) == 0; }
};

class ActStage {
 public:
  /** `estimate`: the estimator, for the closed loop's hand-back check (ClosedLoop::HandBackRisk)
   *  and its scenes without the objects in contact now (CloseTheLoop); empty: neither. */
  ActStage(const ActConfig& config, SumoWorld* world, double step_s,
           std::function<Result(const Scene&)> estimate = {});
  ActOutcome Run(const Observation& obs, const SceneBatch& batch,
                 const std::vector<Result>& results, const PublishTo& publish = {});
  /** Egos whose warning episode is open (to close them when the run ends). */
  std::vector<std::string> OpenEpisodes() const { return episodes_.Open(); }

 private:
  /** Egos that left or started a teleport end their episode and engagement. */
  void Leaving(const Observation& obs, ActOutcome* out);
  void Warn(const ObjectSnapshot& ego, const Result& r, double t, double p, bool publish,
            ActOutcome* out);
  EgoStep Row(const ObjectSnapshot& ego, const Result& r) const;
  /** The closed loop's step for one ego; where objects are in contact with it now, on the
   *  scene without them, re-estimated (present_contacts.h): for a standing ego every such
   *  object, for a moving one those that were in contact with it already while it stood and
   *  have stayed so since (standing_contacts_). */
  void CloseTheLoop(double t, const ObjectSnapshot& ego, const Scene& scene, const Result& r,
                    double p, ActOutcome* out);

  ActConfig config_;
  SumoWorld* world_;
  std::function<Result(const Scene&)> estimate_;
  WarningEpisodes episodes_;
  ClosedLoop closed_loop_;
  /** ego -> the objects the loop decided without while the ego stood, as long as they stay in
   *  contact: a standing ego handed back for them creeps on and would otherwise be braked for
   *  the same contact again, and again (a bus with its tail in a junction and a car stopped
   *  against it: brake and release alternating every 1-2 s for 19 s). */
  std::unordered_map<std::string, std::vector<std::string>> standing_contacts_;
};

}  // namespace criticality::plugin
