#include "tools/campaign/replan.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "tools/campaign/campaign_error.h"
#include "tools/campaign/campaign_folder.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace criticality::campaign {
namespace {

constexpr std::size_t kMaxMatchedRuns = 2'000'000;

std::uint64_t Hash(const std::string& s) {
  std::uint64_t h = 14695981039346656037ULL;
  for (unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  return h;
}

std::optional<json> ReadRecord(const fs::path& file) {
  std::ifstream in(file);
  if (!in) return std::nullopt;
  try {
    return json::parse(in);
  } catch (const json::exception&) {
    return std::nullopt;
  }
}

// The run's identity as its record gives it: kept since identities were recorded, else from
// its command line.
std::string IdentityOf(const json& r, const fs::path& base_dir) {
  if (r.contains("identity") && r["identity"].is_string()) return r["identity"].get<std::string>();
  std::vector<std::string> argv;
  for (const json& a : r.value("command", json::array())) {
    if (a.is_string()) argv.push_back(a.get<std::string>());
  }
  const std::string path = r.value("scenario_path", "");
  const std::string rel = fs::path(path).lexically_relative(base_dir).string();
  return RunIdentity(rel, r.value("repetition", 0), argv);
}

// The index in a run folder's name ("000042", "000042.partial", "000042.lock"); -1 for others.
long long IndexOfName(const std::string& name, std::string* suffix) {
  std::size_t digits = 0;
  while (digits < name.size() && std::isdigit(static_cast<unsigned char>(name[digits]))) ++digits;
  if (digits == 0) return -1;
  *suffix = name.substr(digits);
  return std::stoll(name.substr(0, digits));
}

// Whether another process holds a run's claim now (its flock).
bool Held(const fs::path& lock) {
  const int fd = ::open(lock.c_str(), O_RDWR | O_CLOEXEC);
  if (fd < 0) return false;
  const bool held = ::flock(fd, LOCK_EX | LOCK_NB) != 0;
  ::close(fd);
  return held;
}

std::string What(const json& r) {
  return r.value("scenario", "?") + ", " + r.value("label", "-") + " (" + r.value("status", "?") +
         ")";
}

// Identity hash -> index of every run of the new plan.
std::multimap<std::uint64_t, std::size_t> NewIdentities(const Plan& plan) {
  if (plan.size() > kMaxMatchedRuns) {
    throw CampaignError("the campaign file changed and its plan has " +
                        std::to_string(plan.size()) +
                        " runs: matching the folder's runs is limited to " +
                        std::to_string(kMaxMatchedRuns) + "; use a new output folder");
  }
  std::multimap<std::uint64_t, std::size_t> out;
  for (std::size_t i = 0; i < plan.size(); ++i) out.emplace(Hash(plan.Identity(plan.Run(i))), i);
  return out;
}

void WriteJson(const fs::path& file, const json& j) {
  const fs::path tmp = file.string() + ".tmp";
  {
    std::ofstream out(tmp);
    out << j.dump(2, ' ', false, json::error_handler_t::replace) << "\n";
    if (!out) throw CampaignError("cannot write '" + tmp.string() + "'");
  }
  fs::rename(tmp, file);
}

void Lines(std::ostream& o, const std::string& title, const std::vector<ReplannedRun>& runs,
           std::size_t max_lines, bool arrows) {
  if (runs.empty()) return;
  o << title << " (" << runs.size() << "):\n";
  for (std::size_t k = 0; k < runs.size() && k < max_lines; ++k) {
    const ReplannedRun& r = runs[k];
    o << "  run " << r.old_index;
    if (arrows) o << " -> " << r.new_index;
    o << ": " << r.what << "\n";
  }
  if (runs.size() > max_lines) o << "  ... and " << runs.size() - max_lines << " more\n";
}

}  // namespace

std::string PlanChanges::Describe(std::size_t max_lines) const {
  std::ostringstream o;
  o << "the campaign file changed since the folder was started (plan " << old_fingerprint << ", "
    << old_runs << " runs):\n";
  std::vector<ReplannedRun> moved;
  for (const ReplannedRun& r : kept) {
    if (r.old_index != r.new_index) moved.push_back(r);
  }
  o << "kept: " << kept.size() << " complete runs the new plan has unchanged";
  o << (moved.empty() ? "\n" : ", " + std::to_string(moved.size()) + " of them renumbered\n");
  Lines(o, "renumbered", moved, max_lines, true);
  Lines(o, "to be redone (not successful or half done, and changed)", redone, max_lines, false);
  Lines(o, "superseded (successful, but the new plan no longer has them)", superseded, max_lines,
        false);
  for (const std::string& b : busy) o << "busy: " << b << "\n";
  return o.str();
}

PlanChanges CompareWithFolder(const fs::path& dir, const Plan& plan) {
  PlanChanges c;
  const std::optional<json> info = ReadRecord(dir / "campaign.json");
  if (!info) return c;
  c.old_fingerprint = info->value("fingerprint", "");
  c.old_runs = info->value("runs", std::size_t{0});
  if (c.old_fingerprint == plan.FingerprintHex()) return c;
  c.changed = true;
  const auto identities = NewIdentities(plan);
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir / "runs", ec)) {
    std::string suffix;
    const long long index = IndexOfName(e.path().filename().string(), &suffix);
    if (index < 0) continue;
    const std::size_t i = static_cast<std::size_t>(index);
    if (suffix == ".lock") {
      if (Held(e.path())) c.busy.push_back("run " + std::to_string(i) + " is being run now");
      continue;
    }
    if (suffix == ".partial") {
      c.redone.push_back({i, 0, "half done"});
      continue;
    }
    if (!suffix.empty() || !e.is_directory()) continue;
    const std::optional<json> r = ReadRecord(e.path() / "run.json");
    if (!r) {
      c.redone.push_back({i, 0, "no readable run.json"});
      continue;
    }
    const std::string id = IdentityOf(*r, plan.spec().base_dir);
    std::optional<std::size_t> to;
    const auto [lo, hi] = identities.equal_range(Hash(id));
    for (auto it = lo; it != hi && !to; ++it) {
      if (plan.Identity(plan.Run(it->second)) == id) to = it->second;
    }
    if (to)
      c.kept.push_back({i, *to, What(*r)});
    else if (r->value("status", "") == "ok")
      c.superseded.push_back({i, 0, What(*r)});
    else
      c.redone.push_back({i, 0, What(*r)});
  }
  auto by_index = [](const ReplannedRun& a, const ReplannedRun& b) {
    return a.old_index < b.old_index;
  };
  for (auto* v : {&c.kept, &c.redone, &c.superseded}) std::sort(v->begin(), v->end(), by_index);
  return c;
}

void ApplyChanges(const fs::path& dir, const Plan& plan, const PlanChanges& c) {
  if (!c.changed) return;
  if (!c.busy.empty())
    throw CampaignError("'" + dir.string() + "': " + c.busy.front() +
                        "; change the campaign file once no run command works on the folder");
  const fs::path runs = dir / "runs";
  std::map<std::size_t, fs::path> old_names;  // old index -> its folder (any digit count)
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(runs, ec)) {
    std::string suffix;
    const long long index = IndexOfName(e.path().filename().string(), &suffix);
    if (index < 0) continue;
    if (suffix.empty() && e.is_directory()) {
      old_names[static_cast<std::size_t>(index)] = e.path();
    } else if (suffix == ".partial" || suffix == ".lock" || suffix == ".old") {
      RemoveTree(e.path());  // half done or stale: the new plan runs its index afresh
    }
  }
  const fs::path aside = dir / "superseded" / c.old_fingerprint;
  for (const ReplannedRun& r : c.superseded) {
    fs::create_directories(aside);
    fs::rename(old_names.at(r.old_index), aside / old_names.at(r.old_index).filename());
  }
  for (const ReplannedRun& r : c.redone) {
    if (old_names.count(r.old_index)) RemoveTree(old_names.at(r.old_index));
  }
  // Kept runs in two moves (to a temporary name, then to the new one), so that a chain of
  // renumberings never overwrites a run that has not moved yet.
  const CampaignFolder shape = CampaignFolder::Layout(dir, plan.size());
  std::vector<std::pair<fs::path, const ReplannedRun*>> moving;
  for (const ReplannedRun& r : c.kept) {
    const fs::path tmp = runs / (std::to_string(r.old_index) + ".moving");
    fs::rename(old_names.at(r.old_index), tmp);
    moving.emplace_back(tmp, &r);
  }
  for (const auto& [tmp, r] : moving) {
    const fs::path to = shape.RunDir(r->new_index);
    std::optional<json> rec = ReadRecord(tmp / "run.json");
    if (rec) {
      const PlanRun run = plan.Run(r->new_index);
      json params = json::object();
      for (const auto& [name, value] : plan.GridValues(run)) params[name] = value;
      const bool relabel = (*rec)["index"] != r->new_index || (*rec)["params"] != params ||
                           (*rec)["label"] != plan.Label(run);
      (*rec)["index"] = r->new_index;
      (*rec)["params"] = params;
      (*rec)["label"] = plan.Label(run);
      (*rec)["scenario"] = plan.scenarios()[run.scenario].name;
      (*rec)["fingerprint"] = plan.FingerprintHex();
      (*rec)["identity"] = plan.Identity(run);
      // merge takes a run again when its attempt differs from the one it merged.
      if (relabel)
        (*rec)["attempt"] = rec->value("attempt", "") + "+replan:" + plan.FingerprintHex();
      WriteJson(tmp / "run.json", *rec);
    }
    fs::rename(tmp, to);
  }
  // The plan's record: the new one, the old one kept beside it.
  fs::copy_file(dir / "campaign.json", dir / ("campaign." + c.old_fingerprint + ".json"),
                fs::copy_options::overwrite_existing);
  if (fs::exists(dir / "campaign.yaml")) {
    fs::copy_file(dir / "campaign.yaml", dir / ("campaign." + c.old_fingerprint + ".yaml"),
                  fs::copy_options::overwrite_existing);
  }
  fs::copy_file(plan.spec().file, dir / "campaign.yaml", fs::copy_options::overwrite_existing);
  json info = PlanInfo(plan);
  const std::optional<json> old = ReadRecord(dir / "campaign.json");
  info["created_utc"] = old ? old->value("created_utc", "") : "";
  info["previous_plans"] = old ? old->value("previous_plans", json::array()) : json::array();
  info["previous_plans"].push_back(c.old_fingerprint);
  WriteJson(dir / "campaign.json", info);
}

}  // namespace criticality::campaign
