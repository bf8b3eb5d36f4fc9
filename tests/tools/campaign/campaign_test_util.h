#pragma once
// Helpers for the campaign tool's tests: a temporary folder removed at the end, files written
// from text, and the stand-in driver (tests/tools/campaign/stand_in_driver.cc).
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace criticality::campaign::testing {

class TempDir {
 public:
  TempDir() {
    std::string tmpl = (std::filesystem::temp_directory_path() / "campaign_test.XXXXXX").string();
    path_ = mkdtemp(tmpl.data());
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

inline std::filesystem::path WriteFile(const std::filesystem::path& p, const std::string& text) {
  std::filesystem::create_directories(p.parent_path());
  std::ofstream(p) << text;
  return p;
}

inline std::string ReadFile(const std::filesystem::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/** The stand-in driver built next to the tests. */
inline std::string StandInDriver() { return STAND_IN_DRIVER; }

}  // namespace criticality::campaign::testing
