#pragma once
// A changed campaign file over a folder that holds runs of the earlier one. Each complete run
// is matched by its identity (Plan::Identity: scenario, repetition, the options its command
// gives, whatever its index) with a run of the new plan:
//   kept        the new plan has the same run: its folder stays (renumbered when its index
//               changed, run.json updated so that `merge` takes it at its new place);
//   redone      a run that did not succeed (failed, timeout, killed) or was left half done, and
//               that the new plan does not have as it was: removed, the new plan runs its index;
//   superseded  a successful run the new plan no longer has (an option, a value, a scenario
//               changed): a result would be thrown away, so this needs consent (`run --replan`)
//               and is then moved to OUT/superseded/FINGERPRINT/, never deleted.
// Nothing changes while another process holds a run of the folder.
#include <filesystem>
#include <string>
#include <vector>

#include "tools/campaign/plan.h"

namespace criticality::campaign {

struct ReplannedRun {
  std::size_t old_index{0};
  std::size_t new_index{0};  ///< kept runs: where the run goes
  std::string what;          ///< "rear_end, act=warn seed=1 (ok)"
};

struct PlanChanges {
  bool changed{false};  ///< the folder was made for another plan
  std::string old_fingerprint;
  std::size_t old_runs{0};
  std::vector<ReplannedRun> kept, redone, superseded;
  std::vector<std::string> busy;  ///< runs another process holds now

  /** What applying would do, one line per run (at most `max_lines` per kind, then a count). */
  std::string Describe(std::size_t max_lines = 20) const;
};

/** What the new plan would do with the runs in `dir` (nothing is changed). Throws
 *  CampaignError for a plan of more than 2,000,000 runs over a changed folder (matching would
 *  need every run's identity in memory). */
PlanChanges CompareWithFolder(const std::filesystem::path& dir, const Plan& plan);

/** Applies `changes` (CompareWithFolder's, under the folder's lock): moves, removes, updates
 *  run.json files, writes the new campaign.json and campaign.yaml (the old ones stay as
 *  campaign.FINGERPRINT.json/.yaml). */
void ApplyChanges(const std::filesystem::path& dir, const Plan& plan, const PlanChanges& changes);

}  // namespace criticality::campaign
