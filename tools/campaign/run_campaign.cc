#include "tools/campaign/run_campaign.h"

#include <signal.h>
#include <sys/resource.h>

#include <atomic>
#include <chrono>
#include <fstream>
#include <map>
#include <memory>

#include "tools/campaign/campaign_error.h"
#include "tools/campaign/campaign_folder.h"
#include "tools/campaign/process_pool.h"
#include "tools/campaign/progress_bar.h"
#include "tools/campaign/run_record.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace criticality::campaign {
namespace {

volatile sig_atomic_t g_stop = 0;
extern "C" void OnStopSignal(int) { g_stop = 1; }

// Installs handlers for SIGINT/SIGTERM (without SA_RESTART, so that waits return) for the
// duration of a run session, restoring the previous ones after.
class StopSignals {
 public:
  StopSignals() {
    g_stop = 0;
    struct sigaction sa {};
    sa.sa_handler = OnStopSignal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, &old_int_);
    sigaction(SIGTERM, &sa, &old_term_);
  }
  ~StopSignals() {
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
  }

 private:
  struct sigaction old_int_ {};
  struct sigaction old_term_ {};
};

void WriteRecord(const fs::path& file, const json& record) {
  std::ofstream out(file);
  out << record.dump(2, ' ', false, json::error_handler_t::replace) << "\n";
  if (!out) throw CampaignError("cannot write '" + file.string() + "'");
}

struct Active {
  RunClaim claim;
  PlanRun run;
  std::vector<std::string> command;
  std::string started_utc;
  fs::path work;
};

}  // namespace

bool IsFailedRecord(const fs::path& run_dir) {
  std::ifstream in(run_dir / "run.json");
  if (!in) return true;  // a complete folder without a record is not a result
  try {
    const json r = json::parse(in);
    return r.value("status", "") != "ok";
  } catch (const json::exception&) {
    return true;
  }
}

RunTotals RunCampaign(const Plan& plan, const fs::path& out_dir, const RunOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  const CampaignFolder folder = CampaignFolder::Prepare(out_dir, plan, o.replan);
  if (!folder.changes().empty() && o.progress)
    std::fprintf(o.progress, "criticality-campaign: %s", folder.changes().c_str());
  RunTotals totals;
  if (plan.size() == 0) return totals;
  const std::size_t first = std::min(o.first, plan.size() - 1);
  const std::size_t last = std::min(o.last, plan.size() - 1);
  if (o.first > last) {
    throw CampaignError("run range starts at " + std::to_string(o.first) + " but the plan has " +
                        std::to_string(plan.size()) + " runs (0.." +
                        std::to_string(plan.size() - 1) + ")");
  }
  totals.in_range = last - first + 1;
  auto needs_work = [&](std::size_t i) {
    return !folder.IsComplete(i) || (o.retry_failed && IsFailedRecord(folder.RunDir(i)));
  };
  for (std::size_t i = first; i <= last; ++i) {
    if (needs_work(i)) continue;
    ++totals.done_before;
    if (IsFailedRecord(folder.RunDir(i))) ++totals.failed_before;
  }

  StopSignals signals;
  ProcessPool pool(o.jobs, o.time_limit_s, o.kill_after_s);
  ProgressBar bar(o.progress, o.progress_terminal, o.log_every_s);
  Progress progress;
  progress.total = totals.in_range;
  progress.done_before = totals.done_before;
  std::map<std::size_t, std::unique_ptr<Active>> active;

  auto finish = [&](const ChildResult& c) {
    auto it = active.find(c.id);
    if (it == active.end()) return;
    Active& a = *it->second;
    if (c.stopped) {  // interrupted: left as .partial, redone next time
      ++totals.interrupted;
      active.erase(it);
      return;
    }
    const json record =
        MakeRunRecord(plan, a.run, a.command, c, {a.started_utc, UtcNow()}, a.work, o.time_limit_s);
    WriteRecord(a.work / "run.json", record);
    a.claim.Complete();
    if (record["status"] == "ok") {
      ++totals.ok;
    } else {
      ++totals.failed;
      ++progress.failed;
      bar.Message("criticality-campaign: run " + std::to_string(c.id) + " (" +
                  record["scenario"].get<std::string>() + ", " +
                  record["label"].get<std::string>() + ") " + record["status"].get<std::string>() +
                  ": " + record.value("error", json("")).get<std::string>());
    }
    ++progress.done;
    active.erase(it);
  };

  std::size_t next = first;
  std::size_t elsewhere = 0;
  while (!g_stop) {
    // Fill the free slots with the next runs that need work and can be claimed.
    while (!pool.full() && next <= last && !g_stop) {
      const std::size_t i = next++;
      if (!needs_work(i)) continue;
      std::optional<RunClaim> claim = RunClaim::TryClaim(folder, i, o.retry_failed);
      if (!claim) {
        if (!folder.IsComplete(i)) ++elsewhere;
        continue;
      }
      auto a = std::make_unique<Active>(Active{std::move(*claim), plan.Run(i), {}, UtcNow(), {}});
      a->work = a->claim.StartWork();
      a->command = plan.Command(a->run, o.driver, "run.sqlite");
      pool.Start({i, a->command, a->work, a->work / "stdout.txt", a->work / "stderr.txt"});
      active.emplace(i, std::move(a));
    }
    progress.running = pool.running();
    progress.elsewhere = elsewhere;
    bar.Update(progress);
    if (pool.running() == 0) break;
    for (const ChildResult& c : pool.Wait(0.5)) finish(c);
  }
  if (g_stop) {
    totals.stopped_by_signal = true;
    for (const ChildResult& c : pool.StopAll()) finish(c);
  }
  // What is still not complete: held by another process, or stopped here.
  for (std::size_t i = first; i <= last; ++i) {
    if (!folder.IsComplete(i)) ++totals.remaining;
  }
  progress.running = 0;
  bar.Finish(progress);
  totals.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  rusage self{};
  getrusage(RUSAGE_SELF, &self);
  totals.max_rss_kb = self.ru_maxrss;
  totals.cpu_s = static_cast<double>(self.ru_utime.tv_sec + self.ru_stime.tv_sec) +
                 1e-6 * static_cast<double>(self.ru_utime.tv_usec + self.ru_stime.tv_usec);
  return totals;
}

}  // namespace criticality::campaign
