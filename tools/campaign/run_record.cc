#include "tools/campaign/run_record.h"

#include <signal.h>
#include <string.h>
#include <unistd.h>

#include <chrono>
#include <ctime>
#include <fstream>

namespace fs = std::filesystem;
using nlohmann::json;

namespace criticality::campaign {

std::string UtcNow() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

std::string HostName() {
  char buf[256] = {};
  if (gethostname(buf, sizeof buf - 1) != 0) return "?";
  return buf;
}

std::string TailOfFile(const fs::path& file, std::size_t max_lines, std::size_t max_bytes) {
  std::ifstream in(file, std::ios::binary | std::ios::ate);
  if (!in) return "";
  const std::streamoff size = in.tellg();
  const std::streamoff from = size > static_cast<std::streamoff>(max_bytes)
                                  ? size - static_cast<std::streamoff>(max_bytes)
                                  : 0;
  in.seekg(from);
  std::string text(static_cast<std::size_t>(size - from), '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  std::size_t lines = 0, cut = std::string::npos;
  for (std::size_t i = text.size(); i-- > 0;) {
    if (text[i] == '\n' && ++lines == max_lines) {
      cut = i + 1;
      break;
    }
  }
  if (cut != std::string::npos) text.erase(0, cut);
  // Keep it valid UTF-8-ish for JSON: replace control bytes other than newline and tab.
  for (char& c : text) {
    if (static_cast<unsigned char>(c) < 0x20 && c != '\n' && c != '\t') c = ' ';
  }
  return text;
}

std::optional<json> LastJsonLine(const fs::path& file) {
  const std::string tail = TailOfFile(file, 1, 1 << 16);
  if (tail.empty() || tail.front() != '{') return std::nullopt;
  try {
    json j = json::parse(tail);
    if (j.is_object() && j.contains("status")) return j;
  } catch (const json::exception&) {
  }
  return std::nullopt;
}

std::string RunStatus(const ChildResult& child, const std::optional<json>& summary) {
  if (child.timed_out) return "timeout";
  if (child.signal != 0) return "killed";
  if (child.exit_code != 0 || !summary) return "failed";
  const json& st = (*summary)["status"];
  return st.is_string() && st.get<std::string>() == "completed" ? "ok" : "failed";
}

json MakeRunRecord(const Plan& plan, const PlanRun& run, const std::vector<std::string>& command,
                   const ChildResult& child, const RunTimes& times, const fs::path& work_dir,
                   double time_limit_s) {
  const std::optional<json> summary = LastJsonLine(work_dir / "stdout.txt");
  const std::string tail = TailOfFile(work_dir / "stderr.txt");
  const Scenario& s = plan.scenarios()[run.scenario];
  json r;
  r["index"] = run.index;
  r["fingerprint"] = plan.FingerprintHex();
  r["scenario"] = s.name;
  r["scenario_path"] = s.path.string();
  r["params"] = json::object();
  for (const auto& [name, value] : plan.GridValues(run)) r["params"][name] = value;
  r["label"] = plan.Label(run);
  r["repetition"] = run.repetition;
  r["identity"] = plan.Identity(run);  // finds the run again when the campaign file changes
  r["command"] = command;
  r["status"] = RunStatus(child, summary);
  r["exit_code"] = child.signal ? json() : json(child.exit_code);
  r["signal"] = child.signal ? json(child.signal) : json();
  std::string error;
  if (child.timed_out) {
    error = "time limit of " + std::to_string(static_cast<long>(time_limit_s)) + " s reached";
  } else if (child.signal) {
    error = std::string("killed by signal ") + std::to_string(child.signal) + " (" +
            strsignal(child.signal) + ")";
  } else if (summary && summary->contains("error") && (*summary)["error"].is_string()) {
    error = (*summary)["error"].get<std::string>();
  } else if (child.exit_code != 0 || !summary) {
    const auto nl = tail.find_last_of('\n');
    error = nl == std::string::npos ? tail : tail.substr(nl + 1);
    if (error.empty())
      error = child.exit_code != 0 ? "exit code " + std::to_string(child.exit_code)
                                   : "no JSON summary line on stdout";
    else if (child.exit_code == 0)
      error = "no JSON summary line on stdout; " + error;
  } else if (r["status"] != "ok") {
    error = "driver status '" + (*summary)["status"].get<std::string>() + "'";
  }
  r["error"] = error.empty() ? json() : json(error);
  r["driver_status"] = summary ? (*summary)["status"] : json();
  r["wall_s"] = child.wall_s;
  r["max_rss_kb"] = child.max_rss_kb;
  r["started_utc"] = times.started_utc;
  r["ended_utc"] = times.ended_utc;
  r["host"] = HostName();
  r["attempt"] = HostName() + ":" + std::to_string(::getpid()) + ":" +
                 std::to_string(std::chrono::system_clock::now().time_since_epoch().count());
  r["stderr_tail"] = tail;
  r["summary"] = summary ? *summary : json();
  r["results"] = fs::exists(work_dir / "run.sqlite") ? json("run.sqlite") : json();
  return r;
}

}  // namespace criticality::campaign
