#pragma once
// `plan` proves that every run can start before any runs: the files behind each scenario exist,
// every driver option set goes through the driver's own parser (`sumo-criticality
// --check-options`: values, the scenario.cfg, the SUMO configuration) and every SUMO option set
// through SUMO (`sumo --save-configuration`, which knows every option name, then a dry start of
// the saved configuration without its outputs: values, network and route files). Errors name
// the campaign file, the line and the key whose value a program rejected, and what it said.
//
// An option set is what one run gives a program: the driver sees the scenario and the driver
// options (fixed and grid), SUMO the scenario's .sumocfg and the SUMO options. Up to `max_sets`
// of each kind every distinct set is checked; beyond, a cover in which every grid value appears
// at least once per scenario (combination j takes value j mod n of each axis), and the result
// says so.
#include <string>
#include <vector>

#include "tools/campaign/plan.h"

namespace criticality::campaign {

struct CheckSettings {
  std::string driver;          ///< sumo-criticality; empty: driver options not checked
  bool driver_checks{false};   ///< it has --check-options (else: names against --help only)
  std::string sumo;            ///< the sumo binary; empty: SUMO options not checked
  int jobs{1};                 ///< checks at once
  std::size_t max_sets{200};   ///< per kind: every distinct set up to this many, else a cover
  double time_limit_s{120.0};  ///< per check (a large network takes a while to load)
};

struct PlanCheck {
  std::vector<std::string> errors;     ///< one line each: FILE:LINE: KEY: what is wrong
  std::vector<std::string> checked;    ///< what was checked, one line each
  std::vector<std::string> unchecked;  ///< what was not, and why
  std::size_t driver_sets{0}, driver_checked{0};
  std::size_t sumo_sets{0}, sumo_checked{0};
  std::size_t scenario_files{0};
};

PlanCheck CheckPlan(const Plan& plan, const CheckSettings& settings);

/** The sumo binary: `option` when given, else $SUMO_HOME/bin/sumo, else `sumo` on PATH; empty
 *  when there is none (`why` says where it looked). */
std::string FindSumo(const std::string& option, std::string& why);

/** Combinations of values of axes with these sizes: all (in mixed-radix order, the first axis
 *  slowest) when there are at most `limit`, else max(sizes) combinations where combination j
 *  takes value j mod n of each axis. `all` says which. No axes: one empty combination. */
std::vector<std::vector<std::size_t>> OptionCombinations(const std::vector<std::size_t>& sizes,
                                                         std::size_t limit, bool* all);

/** One option as the campaign file gives it, for naming it in an error. */
struct OptionSource {
  std::string name;   ///< without dashes
  std::string value;  ///< the value of this run
  std::string key;    ///< "grid.driver.act", "sumo.step-length"
  int line{0};
  bool grid{false};
};

/** The source whose option a program's error message names first (as --name, 'name' or the
 *  name as a word); nullptr when it names none of them. */
const OptionSource* NamedOption(const std::string& message,
                                const std::vector<OptionSource>& sources);

/** SUMO's messages: the "Error: ..." lines with their continuation lines, joined into one line
 *  ("" when there is none). */
std::string SumoErrors(const std::string& output);

/** A configuration that SUMO saved (--save-configuration) without what it would write: the
 *  <output> section, log files, device output files, saved states; and without its end time.
 *  `begin` gets the configuration's begin time ("0" when it gives none). */
std::string WithoutOutputs(const std::string& saved_config, std::string* begin);

}  // namespace criticality::campaign
