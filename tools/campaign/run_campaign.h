#pragma once
// `run`: the runs of a campaign (or of a range of it) through a local process pool, resuming
// what earlier sessions left: complete runs are skipped, a .partial run is redone, a run claimed
// by another live process is left to it.
#include <cstdio>
#include <filesystem>
#include <string>

#include "tools/campaign/plan.h"

namespace criticality::campaign {

struct RunOptions {
  int jobs{1};
  std::size_t first{0};        ///< the range of run indices worked on
  std::size_t last{SIZE_MAX};  ///< inclusive; clipped to the plan
  bool retry_failed{false};    ///< redo complete runs whose status is not ok
  std::string driver;          ///< absolute path of sumo-criticality
  double time_limit_s{0.0};
  double kill_after_s{10.0};
  std::FILE* progress{stderr};  ///< nullptr: silent
  bool progress_terminal{false};
  double log_every_s{30.0};
  /** The folder holds successful runs of an earlier version of the campaign file that the new
   *  plan no longer has: move them aside and go on (CampaignFolder::Prepare). */
  bool replan{false};
};

struct RunTotals {
  std::size_t in_range{0};
  std::size_t done_before{0};
  std::size_t ok{0};
  std::size_t failed{0};
  /** Complete before and failed then, not redone (no --retry-failed): the folder still holds
   *  them as failed. */
  std::size_t failed_before{0};
  std::size_t remaining{0};    ///< not complete at the end (another process holds it, or stopped)
  std::size_t interrupted{0};  ///< stopped here by SIGINT/SIGTERM, left to redo
  bool stopped_by_signal{false};
  double wall_s{0.0};
  long max_rss_kb{0};  ///< of this process
  double cpu_s{0.0};   ///< user + system CPU time of this process (not of the runs)
};

/** Whether a complete run's folder holds no successful result (run.json missing, unreadable,
 *  or its status not ok). */
bool IsFailedRecord(const std::filesystem::path& run_dir);

/** Runs the plan's runs in `o.first..o.last` in the campaign folder (created or checked).
 *  SIGINT/SIGTERM stop it: running runs are stopped and left to be redone. */
RunTotals RunCampaign(const Plan& plan, const std::filesystem::path& out_dir, const RunOptions& o);

}  // namespace criticality::campaign
