#pragma once
// The plan: the list of runs of a campaign, never materialised. Run i is decoded from its index
// (mixed radix: scenario slowest, then the grid axes in file order, repetition fastest), so
// every machine that reads the same campaign file over the same files gets the same run i, and
// a 100,000-run plan costs nothing to build.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "tools/campaign/campaign_file.h"
#include "tools/campaign/scenario_files.h"

namespace criticality::campaign {

struct PlanRun {
  std::size_t index{0};
  std::size_t scenario{0};
  std::vector<std::size_t> value;  ///< per axis: index into Axis::values
  int repetition{0};
};

class Plan {
 public:
  /** Resolves the scenarios (scenario_files.h) and sizes the grid. Throws CampaignError when
   *  the plan would exceed 1,000,000,000 runs. */
  explicit Plan(CampaignSpec spec);
  Plan(CampaignSpec spec, std::vector<Scenario> scenarios);

  std::size_t size() const { return size_; }
  PlanRun Run(std::size_t index) const;
  /** The index of a run: Run(IndexOf(r)) is r. */
  std::size_t IndexOf(const PlanRun& run) const;

  /** The driver's command line for a run: DRIVER (--config F | -c F) [egos] [driver options]
   *  --output OUTPUT --no-progress [-- SUMO options]. Fixed options come before grid values. */
  std::vector<std::string> Command(const PlanRun& run, const std::string& driver,
                                   const std::string& output) const;

  /** (option name, value) of each grid axis for this run, in axis order. */
  std::vector<std::pair<std::string, std::string>> GridValues(const PlanRun& run) const;
  /** "profiles=6 seed=1" ("-" without a grid). */
  std::string Label(const PlanRun& run) const;

  /** What decides one run, whatever its index: the scenario (relative to the campaign file),
   *  the repetition, and the options the command gives, each "name=value" (a switch: "name"),
   *  sorted by name (repeated options keep their order). Two runs with one identity are the
   *  same run. Kept in run.json, so that a changed campaign file keeps the runs it still has. */
  std::string Identity(const PlanRun& run) const;

  /** Identity of the plan: a hash of what decides each run (scenario files relative to the
   *  campaign file, egos, options, grid, repetitions); not the output folder, limits or Slurm
   *  settings, which may change between sessions of one campaign. */
  std::uint64_t fingerprint() const { return fingerprint_; }
  std::string FingerprintHex() const;

  const CampaignSpec& spec() const { return spec_; }
  const std::vector<Scenario>& scenarios() const { return scenarios_; }
  const std::vector<Axis>& axes() const { return spec_.axes; }

 private:
  void Init();

  CampaignSpec spec_;
  std::vector<Scenario> scenarios_;
  std::size_t size_{0};
  std::uint64_t fingerprint_{0};
};

/** A run's identity (Plan::Identity) from its command line as recorded in run.json, for run
 *  folders written before run.json kept the identity. `scenario` relative to the campaign file. */
std::string RunIdentity(const std::string& scenario, int repetition,
                        const std::vector<std::string>& argv);

}  // namespace criticality::campaign
