#pragma once
// The scenarios of a campaign, resolved: globs expanded (sorted, so that run i is the same run
// everywhere), each file classified (a driver scenario.cfg or a plain .sumocfg), egos chosen,
// and the SUMO files behind a scenario found (configuration, network, routes).
#include <filesystem>
#include <string>
#include <vector>

#include "tools/campaign/campaign_file.h"

namespace criticality::campaign {

enum class ScenarioKind {
  kDriverConfig,  ///< a driver option file (`--config`), e.g. scenarios/NAME/scenario.cfg
  kSumoConfig,    ///< a plain SUMO .sumocfg (`-c`); egos come from the campaign
};

struct Scenario {
  std::string name;
  std::filesystem::path path;  ///< absolute
  std::string rel_path;        ///< relative to the campaign file's folder (the plan's identity)
  ScenarioKind kind{ScenarioKind::kSumoConfig};
  std::size_t entry{0};  ///< its entry of `scenarios:` (errors name it)
  int line{0};           ///< that entry's line in the campaign file
  /** Egos for the command line: kAll (--all-vehicles) or kIds (--ego, one per ID; a vType is
   *  resolved to the IDs of its vehicles here). Unset for a scenario.cfg that names its own. */
  bool has_egos{false};
  EgoSelection egos;
};

/** Expands and checks `spec.scenarios`. Throws CampaignError naming the entry and its line for a
 *  pattern matching nothing, a file of another kind, a .sumocfg without egos, a vType without
 *  vehicles. */
std::vector<Scenario> ResolveScenarios(const CampaignSpec& spec);

/** The SUMO configuration a scenario runs: the .sumocfg itself, or the `sumo-config` line of a
 *  scenario.cfg (relative to its folder). Empty when it names none. */
std::filesystem::path SumoConfigOf(const Scenario& s);

/** The files a .sumocfg names under `key` (net-file, route-files, additional-files), absolute
 *  (relative to the .sumocfg's folder). */
std::vector<std::filesystem::path> SumoConfigFiles(const std::filesystem::path& sumocfg,
                                                   const std::string& key);

/** IDs of the vehicles of vType `type` in route files: <vehicle> and <trip> elements (default
 *  type DEFAULT_VEHTYPE) and <flow number="N"> (IDs flow.0 .. flow.N-1). Flows without a number
 *  are not counted: their IDs are not known before SUMO runs. */
std::vector<std::string> VehiclesOfType(const std::vector<std::filesystem::path>& route_files,
                                        const std::string& type);

}  // namespace criticality::campaign
