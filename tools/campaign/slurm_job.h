#pragma once
// `slurm`: a Slurm job-array script for a campaign, and its submission. Array task t runs the
// runs t*K .. t*K+K-1 (K runs per task: 1, or more when the plan exceeds the cluster's array
// size) with `criticality-campaign run --runs A-B`, so a task resumes like any `run`: complete
// runs are skipped, so re-submitting the same script redoes only what is missing.
#include <filesystem>
#include <string>

#include "tools/campaign/campaign_folder.h"
#include "tools/campaign/plan.h"

namespace criticality::campaign {

struct SlurmJob {
  std::string script;    ///< the sbatch script's text
  std::size_t tasks{0};  ///< array size
  std::size_t runs_per_task{1};
  /** Non-empty when a task's runs, each up to the time limit, may outlast `slurm.time`. */
  std::string time_warning;
};

/** Seconds of a Slurm time ("M", "M:S", "H:M:S", "D-H", "D-H:M", "D-H:M:S"); -1 when the text
 *  is none of these (or "infinite"/"unlimited"). */
double SlurmTimeSeconds(const std::string& text);

/** The script for `plan` in the campaign folder; `self` and `driver` are absolute paths of
 *  criticality-campaign and sumo-criticality as the compute nodes see them. */
SlurmJob MakeSlurmJob(const Plan& plan, const CampaignFolder& folder, const std::string& self,
                      const std::string& driver, double time_limit_s);

/** Runs `sbatch --parsable SCRIPT`; returns the job ID. Throws CampaignError with sbatch's
 *  message when it fails. */
std::string SubmitSlurmJob(const std::filesystem::path& script);

/** Polls `squeue -h -j ID` every `poll_s` until the job has left the queue (sbatch --wait needs
 *  accounting, which small clusters often lack). */
void WaitForSlurmJob(const std::string& job_id, double poll_s);

}  // namespace criticality::campaign
