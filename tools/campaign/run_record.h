#pragma once
// What the campaign knows about one run, kept as run.json in its folder: the plan's parameters,
// the command line, how it ended (status, exit code, signal, time limit), wall time, the tail of
// its stderr and the driver's JSON summary line. The only things read from the driver are its
// exit code, its last stdout line (a JSON object with at least "status") and its database.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "tools/campaign/plan.h"
#include "tools/campaign/process_pool.h"

namespace criticality::campaign {

/** The last non-empty line of a file, parsed as a JSON object; nullopt when it is not one. */
std::optional<nlohmann::json> LastJsonLine(const std::filesystem::path& file);

/** The last `max_lines` lines of a file, at most `max_bytes` bytes (from its end). */
std::string TailOfFile(const std::filesystem::path& file, std::size_t max_lines = 20,
                       std::size_t max_bytes = 4000);

/** ok (exit 0, summary status "completed"), timeout (stopped at the time limit), killed (ended
 *  by a signal the pool did not send), failed (anything else). */
std::string RunStatus(const ChildResult& child, const std::optional<nlohmann::json>& summary);

struct RunTimes {
  std::string started_utc;
  std::string ended_utc;
};

/** The record of a finished run whose files are in `work_dir` (stdout.txt, stderr.txt,
 *  run.sqlite). */
nlohmann::json MakeRunRecord(const Plan& plan, const PlanRun& run,
                             const std::vector<std::string>& command, const ChildResult& child,
                             const RunTimes& times, const std::filesystem::path& work_dir,
                             double time_limit_s);

std::string UtcNow();
std::string HostName();

}  // namespace criticality::campaign
