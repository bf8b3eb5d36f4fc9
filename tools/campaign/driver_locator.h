#pragma once
// Finding sumo-criticality, the program each run starts, and the options it accepts.
#include <set>
#include <string>

#include "tools/campaign/campaign_file.h"

namespace criticality::campaign {

/** The driver executable, absolute: `option` (--driver) when given, else $SUMO_CRITICALITY_DRIVER,
 *  else sumo-criticality in the build tree next to this program (../../plugin/), in this
 *  program's folder, or on PATH. Throws CampaignError saying where it looked. */
std::string FindDriver(const std::string& option);

/** The long option names (without dashes) that `driver --help` lists. Throws CampaignError when
 *  the program does not run or lists none. */
std::set<std::string> DriverOptionNames(const std::string& driver);

/** Every driver option of the campaign file (fixed and grid) must be one the driver knows:
 *  CampaignError names the key and its line otherwise. */
void CheckDriverOptions(const CampaignSpec& spec, const std::set<std::string>& known);

}  // namespace criticality::campaign
