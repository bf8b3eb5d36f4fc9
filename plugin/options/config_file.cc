#include "plugin/options/config_file.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace po = boost::program_options;
namespace fs = std::filesystem;

namespace criticality::plugin {

bool SumoKnowsOption(const std::string& name) {
  if (name.empty()) return false;
  std::FILE* p = popen("sumo --save-template /dev/stdout 2>/dev/null", "r");
  if (!p) return false;
  std::string text;
  char buf[4096];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) text.append(buf, n);
  pclose(p);
  return text.find("<" + name + " value=") != std::string::npos;
}

void CheckConfigFile(const std::string& path, const po::options_description& all) {
  std::ifstream in(path);
  if (!in) throw std::invalid_argument("--config '" + path + "': cannot read the file");
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::string where = path + ":" + std::to_string(number) + ": ";
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    const auto eq = line.find('=');
    if (eq == std::string::npos && line[first] == '<') {
      // An XML file (a SUMO configuration, a route or network file) given as our own.
      throw std::invalid_argument(where + "this is XML, not a scenario file ('name = value' "
                                  "lines); a SUMO configuration (.sumocfg) is run with -c " +
                                  path + " (or named in a scenario file: sumo-config = FILE)");
    }
    if (eq == std::string::npos)
      throw std::invalid_argument(where + "expected 'name = value', got '" + line + "'");
    std::string name = line.substr(first, eq - first);
    name.erase(name.find_last_not_of(" \t") + 1);
    if (!all.find_nothrow(name, false)) {
      throw std::invalid_argument(where + "unknown option '" + name + "'" +
                                  (SumoKnowsOption(name)
                                       ? " (a SUMO option: put it in the .sumocfg file)"
                                       : " (see --help)"));
    }
    std::istringstream one(line + "\n");
    po::variables_map scratch;
    try {
      po::store(po::parse_config_file(one, all), scratch);
    } catch (const po::error& e) {
      throw std::invalid_argument(where + e.what());
    }
  }
}

std::string RelativeToConfig(const std::string& config_path, const std::string& path) {
  if (fs::path(path).is_absolute()) return path;
  return (fs::path(config_path).parent_path() / path).lexically_normal().string();
}

}  // namespace criticality::plugin
