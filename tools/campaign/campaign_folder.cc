#include "tools/campaign/campaign_folder.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>

#include "tools/campaign/campaign_error.h"
#include "tools/campaign/replan.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace criticality::campaign {
namespace {

std::string UtcNow() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

int Width(std::size_t runs) {
  int w = 1;
  for (std::size_t n = runs > 0 ? runs - 1 : 0; n >= 10; n /= 10) ++w;
  return w < 6 ? 6 : w;
}

}  // namespace

json PlanInfo(const Plan& plan) {
  json j;
  j["format"] = 1;
  j["fingerprint"] = plan.FingerprintHex();
  j["runs"] = plan.size();
  j["name"] = plan.spec().name;
  j["campaign_file"] = plan.spec().file.string();
  j["repetitions"] = plan.spec().repetitions;
  j["scenarios"] = json::array();
  for (const Scenario& s : plan.scenarios()) {
    j["scenarios"].push_back({{"name", s.name},
                              {"path", s.path.string()},
                              {"kind", s.kind == ScenarioKind::kDriverConfig ? "cfg" : "sumocfg"}});
  }
  j["axes"] = json::array();
  for (const Axis& a : plan.axes()) {
    j["axes"].push_back({{"name", a.name},
                         {"target", a.target == Target::kDriver ? "driver" : "sumo"},
                         {"values", a.values}});
  }
  return j;
}

namespace {

json ReadJson(const fs::path& p) {
  std::ifstream in(p);
  if (!in) throw CampaignError(p.string() + ": cannot read");
  try {
    return json::parse(in);
  } catch (const json::exception& e) {
    throw CampaignError(p.string() + ": not valid JSON (" + e.what() + ")");
  }
}

void WriteFileSynced(const fs::path& p, const std::string& text) {
  const int fd = ::open(p.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw CampaignError("cannot write '" + p.string() + "': " + std::strerror(errno));
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const std::string err = std::strerror(errno);
      ::close(fd);
      throw CampaignError("cannot write '" + p.string() + "': " + err);
    }
    done += static_cast<std::size_t>(n);
  }
  ::fsync(fd);
  ::close(fd);
}

void SyncPath(const fs::path& p, bool directory) {
  const int fd = ::open(p.c_str(), (directory ? O_RDONLY | O_DIRECTORY : O_RDONLY) | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

void RemoveTree(const fs::path& dir) {
  std::error_code ec;
  fs::remove_all(dir, ec);
  if (ec && fs::exists(dir))
    throw CampaignError("cannot remove '" + dir.string() + "': " + ec.message());
}

CampaignFolder CampaignFolder::Prepare(const fs::path& dir, const Plan& plan) {
  return Prepare(dir, plan, false);
}

CampaignFolder CampaignFolder::Layout(const fs::path& dir, std::size_t runs) {
  CampaignFolder f;
  f.dir_ = fs::absolute(dir).lexically_normal();
  f.runs_ = runs;
  f.width_ = Width(runs);
  return f;
}

CampaignFolder CampaignFolder::Prepare(const fs::path& dir, const Plan& plan, bool replan) {
  std::error_code ec;
  fs::create_directories(dir / "runs", ec);
  if (ec)
    throw CampaignError("cannot create campaign folder '" + dir.string() + "': " + ec.message());
  // One process at a time creates the folder's plan or changes it.
  const fs::path lock = dir / "campaign.lock";
  const int fd = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) throw CampaignError("cannot create '" + lock.string() + "': " + std::strerror(errno));
  struct Unlock {
    int fd;
    ~Unlock() { ::close(fd); }
  } unlock{fd};
  ::flock(fd, LOCK_EX);
  const fs::path info_path = dir / "campaign.json";
  json info = PlanInfo(plan);
  info["created_utc"] = UtcNow();
  if (!fs::exists(info_path)) {
    // Create-if-absent, atomically: write a private file, then link it (fails if another
    // process got there first; then its file is checked like any existing one).
    const fs::path tmp = dir / ("campaign.json.tmp." + std::to_string(::getpid()));
    WriteFileSynced(tmp, info.dump(2) + "\n");
    if (::link(tmp.c_str(), info_path.c_str()) == 0) {
      std::ifstream src(plan.spec().file, std::ios::binary);
      std::ofstream copy(dir / "campaign.yaml", std::ios::binary);
      copy << src.rdbuf();
    } else if (errno != EEXIST) {
      const std::string err = std::strerror(errno);
      fs::remove(tmp, ec);
      throw CampaignError("cannot create '" + info_path.string() + "': " + err);
    }
    fs::remove(tmp, ec);
  }
  CampaignFolder f = Open(dir);
  if (f.info_.value("fingerprint", "") == plan.FingerprintHex()) return f;
  // Another version of the campaign file: keep what it still has (replan.h).
  const PlanChanges changes = CompareWithFolder(dir, plan);
  if (!changes.busy.empty() || (!changes.superseded.empty() && !replan)) {
    throw CampaignError(
        "campaign folder '" + dir.string() + "': " + changes.Describe() +
        (changes.busy.empty()
             ? "run again with --replan to go on with the new plan (superseded runs are moved "
               "to " +
                   (dir / "superseded").string() + "), or use a new output folder"
             : "change the campaign file once no run command works on the folder"));
  }
  ApplyChanges(dir, plan, changes);
  CampaignFolder g = Open(dir);
  g.changes_ = changes.Describe();
  return g;
}

CampaignFolder CampaignFolder::Open(const fs::path& dir) {
  const fs::path info_path = dir / "campaign.json";
  if (!fs::exists(info_path)) {
    throw CampaignError("'" + dir.string() +
                        "' is not a campaign folder (no campaign.json): give the `output` folder "
                        "of a campaign that was run");
  }
  CampaignFolder f;
  f.dir_ = fs::absolute(dir).lexically_normal();
  f.info_ = ReadJson(info_path);
  if (!f.info_.contains("runs") || !f.info_["runs"].is_number_unsigned())
    throw CampaignError(info_path.string() + ": no run count; the folder is damaged");
  f.runs_ = f.info_["runs"].get<std::size_t>();
  f.width_ = Width(f.runs_);
  return f;
}

std::string CampaignFolder::RunName(std::size_t index) const {
  std::string s = std::to_string(index);
  if (static_cast<int>(s.size()) < width_) s.insert(0, width_ - s.size(), '0');
  return s;
}
fs::path CampaignFolder::RunDir(std::size_t index) const { return dir_ / "runs" / RunName(index); }
fs::path CampaignFolder::PartialDir(std::size_t index) const {
  return dir_ / "runs" / (RunName(index) + ".partial");
}
fs::path CampaignFolder::LockFile(std::size_t index) const {
  return dir_ / "runs" / (RunName(index) + ".lock");
}
bool CampaignFolder::IsComplete(std::size_t index) const {
  std::error_code ec;
  return fs::is_directory(RunDir(index), ec);
}

std::optional<RunClaim> RunClaim::TryClaim(const CampaignFolder& folder, std::size_t index,
                                           bool redo_complete) {
  if (!redo_complete && folder.IsComplete(index)) return std::nullopt;
  const fs::path lock = folder.LockFile(index);
  const int fd = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) throw CampaignError("cannot create '" + lock.string() + "': " + std::strerror(errno));
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    ::close(fd);
    return std::nullopt;  // another process runs it
  }
  // Another process may have completed it between the check and the lock.
  if (!redo_complete && folder.IsComplete(index)) {
    ::close(fd);
    return std::nullopt;
  }
  return RunClaim(folder, index, fd);
}

RunClaim::RunClaim(const CampaignFolder& folder, std::size_t index, int fd)
    : folder_(&folder), index_(index), fd_(fd) {}

RunClaim::RunClaim(RunClaim&& other) noexcept
    : folder_(other.folder_), index_(other.index_), fd_(other.fd_), completed_(other.completed_) {
  other.fd_ = -1;
}

RunClaim::~RunClaim() {
  if (fd_ < 0) return;
  // A complete run needs no lock file; whoever opens the old one later finds the run complete
  // after locking it, so unlinking before unlocking is safe.
  if (completed_) ::unlink(folder_->LockFile(index_).c_str());
  ::close(fd_);
}

fs::path RunClaim::StartWork() {
  const fs::path work = folder_->PartialDir(index_);
  RemoveTree(work);
  std::error_code ec;
  fs::create_directories(work, ec);
  if (ec) throw CampaignError("cannot create '" + work.string() + "': " + ec.message());
  return work;
}

void RunClaim::Complete() {
  const fs::path work = folder_->PartialDir(index_);
  const fs::path done = folder_->RunDir(index_);
  // The files' data and the folder's entries reach the disk before the rename can: a renamed
  // (complete) folder is never half-written. Empty files hold nothing to lose. The rename itself
  // is not synced: if a crash loses it, the .partial folder is simply redone.
  for (const auto& entry : fs::directory_iterator(work)) {
    if (entry.is_regular_file() && entry.file_size() > 0) SyncPath(entry.path(), false);
  }
  SyncPath(work, true);
  if (fs::exists(done)) {  // redoing a run: move the old result aside first
    const fs::path old = done.string() + ".old";
    RemoveTree(old);
    if (::rename(done.c_str(), old.c_str()) != 0)
      throw CampaignError("cannot replace '" + done.string() + "': " + std::strerror(errno));
    RemoveTree(old);
  }
  if (::rename(work.c_str(), done.c_str()) != 0)
    throw CampaignError("cannot complete '" + done.string() + "': " + std::strerror(errno));
  completed_ = true;
}

}  // namespace criticality::campaign
