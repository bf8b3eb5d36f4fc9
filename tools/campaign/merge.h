#pragma once
// `merge`: the complete runs of a campaign folder in one SQLite database, OUT/campaign.sqlite.
// Every table of a run's file is copied as it is, with the run's index added as its first
// column `run_index` (tables and columns a newer driver adds are picked up: a table is created
// at its first appearance, a column added at its first appearance), next to the campaign's own
// tables: campaign (key/value), campaign_runs (one row per complete run: plan, status, exit
// code, wall time, stderr tail, the driver's summary) and plan_params (run_index, name, value).
// Incremental and idempotent: a run already merged from the same attempt is skipped, a redone
// run replaces its rows, a run that is no longer complete is removed; each run goes in one
// transaction, so a killed merge leaves a consistent database that the next merge completes.
// .partial runs are never merged.
#include <filesystem>
#include <string>
#include <vector>

#include "tools/campaign/campaign_folder.h"

namespace criticality::campaign {

struct MergeTotals {
  std::size_t runs{0};        ///< in the plan
  std::size_t complete{0};    ///< complete run folders
  std::size_t merged{0};      ///< added or replaced now
  std::size_t unchanged{0};   ///< already merged from the same attempt
  std::size_t removed{0};     ///< in the database but no longer complete
  std::size_t incomplete{0};  ///< not (yet) complete: not in the database
  std::size_t tables{0};      ///< run-file tables in the database
  /** Runs whose results file could not be read: only their campaign_runs row (with
   *  merge_note) is in the database. */
  std::vector<std::string> unreadable;
  double wall_s{0.0};
  std::filesystem::path database;
};

MergeTotals MergeCampaign(const CampaignFolder& folder);

}  // namespace criticality::campaign
