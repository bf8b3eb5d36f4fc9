#include "tools/campaign/slurm_job.h"

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <sstream>
#include <thread>
#include <vector>

#include "tools/campaign/campaign_error.h"

namespace fs = std::filesystem;

namespace criticality::campaign {
namespace {

std::string ShellQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// Output (stdout and stderr) and exit status of a shell command.
std::pair<int, std::string> Capture(const std::string& cmd) {
  FILE* pipe = popen((cmd + " 2>&1").c_str(), "r");
  if (!pipe) return {-1, "cannot start: " + cmd};
  std::string text;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) text.append(buf.data(), n);
  const int status = pclose(pipe);
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text};
}

std::string JobName(const std::string& name) {
  std::string s = "crit-";
  for (char c : name)
    s += (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_') ? c : '_';
  return s;
}

}  // namespace

double SlurmTimeSeconds(const std::string& text) {
  std::string rest = text;
  double days = 0.0;
  const auto dash = rest.find('-');
  std::vector<long> parts;
  auto numbers = [](const std::string& t, std::vector<long>* out) {
    std::string cur;
    for (std::size_t k = 0; k <= t.size(); ++k) {
      if (k == t.size() || t[k] == ':') {
        if (cur.empty()) return false;
        out->push_back(std::stol(cur));
        cur.clear();
      } else if (std::isdigit(static_cast<unsigned char>(t[k])) && cur.size() < 9) {
        cur += t[k];
      } else {
        return false;
      }
    }
    return true;
  };
  if (dash != std::string::npos) {
    std::vector<long> d;
    if (!numbers(rest.substr(0, dash), &d) || d.size() != 1) return -1.0;
    days = static_cast<double>(d[0]);
    rest = rest.substr(dash + 1);
    if (!numbers(rest, &parts) || parts.size() > 3) return -1.0;
    while (parts.size() < 3) parts.push_back(0);  // D-H, D-H:M
    return days * 86400.0 + parts[0] * 3600.0 + parts[1] * 60.0 + parts[2];
  }
  if (!numbers(rest, &parts) || parts.size() > 3) return -1.0;
  if (parts.size() == 1) return parts[0] * 60.0;             // M
  if (parts.size() == 2) return parts[0] * 60.0 + parts[1];  // M:S
  return parts[0] * 3600.0 + parts[1] * 60.0 + parts[2];     // H:M:S
}

SlurmJob MakeSlurmJob(const Plan& plan, const CampaignFolder& folder, const std::string& self,
                      const std::string& driver, double time_limit_s) {
  const SlurmSettings& st = plan.spec().slurm;
  SlurmJob job;
  const std::size_t n = plan.size();
  std::size_t k = st.runs_per_task > 0 ? static_cast<std::size_t>(st.runs_per_task) : 1;
  const std::size_t max_tasks = static_cast<std::size_t>(st.max_array_size);
  if ((n + k - 1) / k > max_tasks) k = (n + max_tasks - 1) / max_tasks;
  job.runs_per_task = k;
  job.tasks = (n + k - 1) / k;
  const fs::path logs = folder.dir() / "slurm" / "logs";
  std::ostringstream s;
  s << "#!/bin/bash\n"
    << "# Written by criticality-campaign slurm for " << plan.spec().file.string() << "\n"
    << "# " << n << " runs, " << k << " per array task; resubmitting redoes only what is missing.\n"
    << "#SBATCH --job-name=" << JobName(plan.spec().name) << "\n"
    << "#SBATCH --array=0-" << (job.tasks - 1);
  if (st.throttle > 0) s << "%" << st.throttle;
  s << "\n#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=" << st.cpus_per_task << "\n";
  if (!st.time.empty()) s << "#SBATCH --time=" << st.time << "\n";
  if (!st.mem.empty()) s << "#SBATCH --mem=" << st.mem << "\n";
  if (!st.partition.empty()) s << "#SBATCH --partition=" << st.partition << "\n";
  s << "#SBATCH --output=" << (logs / "task_%A_%a.out").string() << "\n";
  for (const std::string& e : st.extra) s << "#SBATCH " << e << "\n";
  s << "set -u\n"
    << "first=$(( SLURM_ARRAY_TASK_ID * " << k << " ))\n"
    << "last=$(( first + " << (k - 1) << " ))\n"
    << "if [ \"$last\" -gt " << (n - 1) << " ]; then last=" << (n - 1) << "; fi\n"
    << "exec " << ShellQuote(self) << " run " << ShellQuote(plan.spec().file.string())
    << " --output " << ShellQuote(folder.dir().string()) << " --driver " << ShellQuote(driver)
    << " --runs \"$first-$last\" -j " << st.cpus_per_task << " --no-check";
  if (time_limit_s > 0) s << " --time-limit " << time_limit_s;
  s << "\n";
  job.script = s.str();
  // A task runs its runs cpus_per_task at a time, each up to the time limit.
  const double slurm_s = SlurmTimeSeconds(st.time);
  const std::size_t waves = (k + st.cpus_per_task - 1) / st.cpus_per_task;
  const double need_s = static_cast<double>(waves) * time_limit_s;
  if (time_limit_s > 0 && slurm_s > 0 && need_s >= slurm_s) {
    std::ostringstream w;
    w << "each array task runs up to " << k << " run" << (k == 1 ? "" : "s") << ", "
      << st.cpus_per_task << " at a time, each up to " << time_limit_s
      << " s (limits.time_s): up to " << need_s << " s, not less than slurm.time " << st.time
      << " (" << slurm_s << " s); Slurm may end tasks before their runs (they are redone on "
      << "resubmission): raise slurm.time or cpus_per_task, or lower runs_per_task";
    job.time_warning = w.str();
  }
  return job;
}

std::string SubmitSlurmJob(const fs::path& script) {
  const auto [rc, out] = Capture("sbatch --parsable " + ShellQuote(script.string()));
  if (rc != 0) {
    throw CampaignError("sbatch failed" + (out.empty() ? std::string() : ": " + out) +
                        " (is Slurm reachable from here? tools/slurm_local.sh starts a local one)");
  }
  // --parsable prints "jobid" or "jobid;cluster".
  const std::string id = out.substr(out.find_last_of('\n') + 1);
  return id.substr(0, id.find(';'));
}

void WaitForSlurmJob(const std::string& job_id, double poll_s) {
  int failures = 0;
  while (true) {
    const auto [rc, out] = Capture("squeue -h -j " + ShellQuote(job_id) + " -o %i");
    if (rc != 0) {
      // squeue forgets a finished job after MinJobAge and then says "Invalid job id".
      if (out.find("Invalid job id") != std::string::npos) return;
      if (++failures >= 5) throw CampaignError("squeue failed: " + out);
    } else {
      failures = 0;
      if (out.empty()) return;
    }
    std::this_thread::sleep_for(std::chrono::duration<double>(poll_s));
  }
}

}  // namespace criticality::campaign
