#pragma once
// The --config file: the same options as the command line, one `name = value` per line (how a
// scenario folder describes its run). Checked line by line so that an error names the file and
// the line, and a SUMO option put there by mistake is named as one.
#include <boost/program_options.hpp>
#include <string>

namespace criticality::plugin {

/** True when SUMO has an option of this name (asks the sumo binary: `sumo --save-template`
 *  lists every option; only on error paths). */
bool SumoKnowsOption(const std::string& name);

/** Throws std::invalid_argument "FILE:LINE: ..." for the first line that is not a known
 *  option with a valid value. */
void CheckConfigFile(const std::string& path,
                     const boost::program_options::options_description& options);

/** A path given in the config file at `config_path`, made relative to the config file's folder
 *  (absolute paths unchanged). */
std::string RelativeToConfig(const std::string& config_path, const std::string& path);

}  // namespace criticality::plugin
