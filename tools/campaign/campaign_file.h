#pragma once
// The campaign file (YAML): what a campaign runs, as written, checked key by key. Paths stay
// as written here; scenario_files.h resolves them. Format: tools/campaign/README.md and the
// commented example scenarios/campaigns/example.yaml.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace criticality::campaign {

/** Which vehicles of a plain .sumocfg are egos. */
struct EgoSelection {
  enum class Kind { kAll, kIds, kType };
  Kind kind{Kind::kAll};
  std::vector<std::string> ids;  ///< kIds
  std::string type;              ///< kType: a vType ID of the route files
  int line{0};
};

/** One entry of `scenarios:`: a path or glob, relative to the campaign file's folder. */
struct ScenarioEntry {
  std::string pattern;
  std::string name;                  ///< empty: derived from the path
  std::optional<EgoSelection> egos;  ///< overrides the campaign's `egos`
  int line{0};
};

/** A fixed option: `name: value` (a list repeats a repeatable option). A YAML boolean is a
 *  switch for the driver (`true`: `--name`, `false`: left out) and `true`/`false` for SUMO. */
struct FixedOption {
  std::string name;
  std::vector<std::string> values;
  bool boolean{false};
  int line{0};
};

/** Where an option goes: the driver's own options, or SUMO's (after `--`). */
enum class Target { kDriver, kSumo };

/** One axis of the grid: the values one option takes. */
struct Axis {
  Target target{Target::kDriver};
  std::string name;
  std::vector<std::string> values;
  bool boolean{false};
  int line{0};
};

struct SlurmSettings {
  std::string time;       ///< per array task, sbatch --time (empty: the cluster's default)
  std::string mem;        ///< per array task, sbatch --mem
  std::string partition;  ///< sbatch --partition
  int cpus_per_task{1};   ///< also the task's -j
  int throttle{0};        ///< at most this many array tasks at once (`%M`), 0: no limit
  int runs_per_task{0};   ///< 0: 1, or more when the runs exceed max_array_size
  int max_array_size{1000};
  std::vector<std::string> extra;  ///< further `#SBATCH` lines, e.g. "--account=traffic"
};

struct CampaignSpec {
  std::filesystem::path file;      ///< the campaign file, absolute
  std::filesystem::path base_dir;  ///< its folder: relative paths start here
  std::string name;
  std::filesystem::path output;  ///< absolute
  std::vector<ScenarioEntry> scenarios;
  std::optional<EgoSelection> egos;
  std::vector<FixedOption> driver_options;
  std::vector<FixedOption> sumo_options;
  std::vector<Axis> axes;  ///< in file order: driver axes, then SUMO axes
  int repetitions{1};
  double time_limit_s{0.0};   ///< per run; 0: none
  double kill_after_s{10.0};  ///< SIGKILL this long after the time limit's SIGTERM
  SlurmSettings slurm;
};

/** Reads and checks a campaign file. Throws CampaignError "FILE:LINE: KEY: problem" for YAML
 *  syntax errors, unknown keys, missing required keys, empty grids and wrong value types. */
CampaignSpec LoadCampaignFile(const std::filesystem::path& file);

/** The same from text (tests); `file` names it in errors and gives the base folder. */
CampaignSpec ParseCampaign(const std::string& text, const std::filesystem::path& file);

}  // namespace criticality::campaign
