#pragma once
// The campaign folder on disk, shared by every process working on one campaign (local `run`
// commands, Slurm array tasks, merge, report):
//
//   OUT/campaign.json          the plan's identity (fingerprint, run count, scenarios, axes)
//   OUT/campaign.yaml          the campaign file as first started (for the record)
//   OUT/runs/000042/           a complete run: run.json, run.sqlite, stdout.txt, stderr.txt
//   OUT/runs/000042.partial/   a run in progress, or one killed half way (redone, never merged)
//   OUT/runs/000042.lock       its claim: flock(2) held by the process running it
//   OUT/campaign.sqlite        merge's output;  OUT/report/  report's;  OUT/slurm/  the job script
//
// A run becomes complete by one atomic rename of its .partial folder, after its files are
// synced, so a kill -9 or a lost node leaves at worst a .partial folder that the next `run`
// removes and redoes. Claims use flock, so two `run` commands on one folder share out the runs.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "tools/campaign/plan.h"

namespace criticality::campaign {

class CampaignFolder {
 public:
  /** Creates the folder for `plan`, or checks that an existing one was made for the same plan
   *  (same fingerprint): CampaignError otherwise. Safe against concurrent callers. */
  static CampaignFolder Prepare(const std::filesystem::path& dir, const Plan& plan);
  /** The same, and when the folder holds runs of an earlier version of the campaign file,
   *  keeps the runs the new plan still has (replan.h): failed or half-done changed runs are
   *  redone; successful ones the new plan no longer has need `replan` (CampaignError listing
   *  them otherwise). changes() then says what was done. */
  static CampaignFolder Prepare(const std::filesystem::path& dir, const Plan& plan, bool replan);
  /** Opens an existing campaign folder (merge, report). */
  static CampaignFolder Open(const std::filesystem::path& dir);
  /** The names of a folder for `runs` runs, without reading or writing anything. */
  static CampaignFolder Layout(const std::filesystem::path& dir, std::size_t runs);

  /** What Prepare did with the runs of an earlier plan ("" when nothing). */
  const std::string& changes() const { return changes_; }

  const std::filesystem::path& dir() const { return dir_; }
  std::size_t runs() const { return runs_; }
  /** campaign.json: fingerprint, runs, name, campaign_file, scenarios, axes, repetitions. */
  const nlohmann::json& info() const { return info_; }

  std::string RunName(std::size_t index) const;  ///< "000042"
  std::filesystem::path RunDir(std::size_t index) const;
  std::filesystem::path PartialDir(std::size_t index) const;
  std::filesystem::path LockFile(std::size_t index) const;
  bool IsComplete(std::size_t index) const;

 private:
  std::filesystem::path dir_;
  std::size_t runs_{0};
  int width_{6};
  nlohmann::json info_;
  std::string changes_;
};

/** campaign.json for a plan: format, fingerprint, runs, name, campaign file, repetitions,
 *  scenarios, axes. */
nlohmann::json PlanInfo(const Plan& plan);

/** The right to run one run: an flock on its lock file, held until destruction (or until the
 *  process dies, when the kernel releases it). */
class RunClaim {
 public:
  /** Claims run `index` unless another process holds it or it is already complete (then
   *  nullopt). With `redo_complete`, a complete run is claimed too (its folder is replaced). */
  static std::optional<RunClaim> TryClaim(const CampaignFolder& folder, std::size_t index,
                                          bool redo_complete = false);
  RunClaim(RunClaim&& other) noexcept;
  RunClaim& operator=(RunClaim&&) = delete;
  RunClaim(const RunClaim&) = delete;
  ~RunClaim();

  /** A fresh, empty .partial folder (a stale one from a killed run is removed). */
  std::filesystem::path StartWork();
  /** Syncs the .partial folder's files and renames it to the run folder (replacing an older
   *  complete one when redoing); the run is then complete. */
  void Complete();

 private:
  RunClaim(const CampaignFolder& folder, std::size_t index, int fd);
  const CampaignFolder* folder_;
  std::size_t index_;
  int fd_{-1};
  bool completed_{false};
};

/** Removes a folder tree; no error when it does not exist. */
void RemoveTree(const std::filesystem::path& dir);

}  // namespace criticality::campaign
