#include "tools/campaign/driver_locator.h"

#include <unistd.h>

#include <array>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <vector>

#include "tools/campaign/campaign_error.h"

namespace fs = std::filesystem;

namespace criticality::campaign {
namespace {

bool IsExecutable(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec) && access(p.c_str(), X_OK) == 0;
}

fs::path SelfDir() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path() : self.parent_path();
}

std::string ShellQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'')
      out += "'\\''";
    else
      out += c;
  }
  return out + "'";
}

}  // namespace

std::string FindDriver(const std::string& option) {
  if (!option.empty()) {
    if (!IsExecutable(option))
      throw CampaignError("--driver '" + option + "': not an executable file");
    return fs::absolute(option).lexically_normal().string();
  }
  if (const char* env = std::getenv("SUMO_CRITICALITY_DRIVER"); env && *env) {
    if (!IsExecutable(env))
      throw CampaignError(std::string("SUMO_CRITICALITY_DRIVER='") + env +
                          "': not an executable file");
    return fs::absolute(env).lexically_normal().string();
  }
  std::vector<fs::path> tried;
  const fs::path self = SelfDir();
  if (!self.empty()) {
    tried.push_back((self / "../../plugin/sumo-criticality").lexically_normal());
    tried.push_back(self / "sumo-criticality");
  }
  for (const fs::path& p : tried) {
    if (IsExecutable(p)) return p.string();
  }
  if (const char* path = std::getenv("PATH")) {
    std::stringstream dirs(path);
    std::string d;
    while (std::getline(dirs, d, ':')) {
      if (!d.empty() && IsExecutable(fs::path(d) / "sumo-criticality"))
        return fs::absolute(fs::path(d) / "sumo-criticality").lexically_normal().string();
    }
  }
  std::string where;
  for (const fs::path& p : tried) where += p.string() + ", ";
  throw CampaignError("sumo-criticality not found (looked at " + where +
                      "PATH): build it (tools/setup.sh) or give --driver PATH or "
                      "SUMO_CRITICALITY_DRIVER");
}

std::set<std::string> DriverOptionNames(const std::string& driver) {
  const std::string cmd = ShellQuote(driver) + " --help 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) throw CampaignError("cannot run '" + driver + " --help'");
  std::string text;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) text.append(buf.data(), n);
  const int status = pclose(pipe);
  // Every "--name" that starts a word (or follows '['): Boost.Program_options lists options as
  // "  --name arg" or "  -c [ --sumo-config ] arg".
  std::set<std::string> names;
  auto is_name_char = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '.' || c == '_';
  };
  for (std::size_t i = text.find("--"); i != std::string::npos; i = text.find("--", i + 2)) {
    const bool starts_word =
        i == 0 || std::isspace(static_cast<unsigned char>(text[i - 1])) || text[i - 1] == '[';
    if (!starts_word || i + 2 >= text.size() ||
        !std::isalnum(static_cast<unsigned char>(text[i + 2])))
      continue;
    std::size_t end = i + 2;
    while (end < text.size() && is_name_char(text[end])) ++end;
    names.insert(text.substr(i + 2, end - i - 2));
  }
  if (status != 0 || names.empty()) {
    throw CampaignError("'" + driver + " --help' " + (status != 0 ? "failed" : "lists no options") +
                        ": is it sumo-criticality? (give the right one with --driver)");
  }
  return names;
}

void CheckDriverOptions(const CampaignSpec& spec, const std::set<std::string>& known) {
  auto check = [&](const std::string& name, int line, const std::string& key) {
    if (name.size() > 1 && !known.count(name)) {
      throw CampaignError(spec.file.string() + ":" + std::to_string(line) + ": " + key +
                          ": sumo-criticality has no option --" + name +
                          " (see sumo-criticality --help; SUMO options go under `sumo:`)");
    }
  };
  for (const FixedOption& o : spec.driver_options) check(o.name, o.line, "driver." + o.name);
  for (const Axis& a : spec.axes) {
    if (a.target == Target::kDriver) check(a.name, a.line, "grid.driver." + a.name);
  }
}

}  // namespace criticality::campaign
