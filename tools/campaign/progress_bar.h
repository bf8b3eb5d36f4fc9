#pragma once
// The progress of `run`: on a terminal one line redrawn in place (bar, runs done / total,
// failures, running, elapsed, ETA); in a log (Slurm, CI) one line every `log_every_s`.
#include <chrono>
#include <cstdio>
#include <string>

namespace criticality::campaign {

struct Progress {
  std::size_t total{0};        ///< runs in the range worked on
  std::size_t done_before{0};  ///< complete when this session began
  std::size_t done{0};         ///< completed in this session (ok + failed)
  std::size_t failed{0};
  std::size_t running{0};
  std::size_t elsewhere{0};  ///< held by another process
};

/** "[#####.....] 12/40 runs, 1 failed, 2 running, elapsed 0:01:23, ETA 0:03:10". */
std::string FormatProgress(const Progress& p, double elapsed_s, int bar_width);

/** h:mm:ss. */
std::string FormatDuration(double seconds);

class ProgressBar {
 public:
  ProgressBar(std::FILE* out, bool terminal, double log_every_s = 30.0);
  /** Redraws (terminal: at most 10 times a second) or logs (every log_every_s). */
  void Update(const Progress& p, bool force = false);
  /** Ends the line on a terminal. */
  void Finish(const Progress& p);
  /** A line of its own (a failure), without breaking the bar. */
  void Message(const std::string& line);

 private:
  using Clock = std::chrono::steady_clock;
  std::FILE* out_;
  bool terminal_;
  double log_every_s_;
  Clock::time_point start_;
  Clock::time_point last_{};
  bool drawn_{false};
};

}  // namespace criticality::campaign
