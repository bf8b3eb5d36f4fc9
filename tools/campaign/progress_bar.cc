#include "tools/campaign/progress_bar.h"

#include <cmath>

namespace criticality::campaign {

std::string FormatDuration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  const long s = std::lround(seconds);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  return buf;
}

std::string FormatProgress(const Progress& p, double elapsed_s, int bar_width) {
  const std::size_t complete = p.done_before + p.done;
  std::string line;
  if (bar_width > 0) {
    const int filled =
        p.total ? static_cast<int>(static_cast<double>(complete) / p.total * bar_width) : bar_width;
    line = "[" + std::string(filled, '#') + std::string(bar_width - filled, '.') + "] ";
  }
  line += std::to_string(complete) + "/" + std::to_string(p.total) + " runs";
  if (p.failed) line += ", " + std::to_string(p.failed) + " failed";
  line += ", " + std::to_string(p.running) + " running";
  if (p.elsewhere) line += ", " + std::to_string(p.elsewhere) + " held by another process";
  line += ", elapsed " + FormatDuration(elapsed_s);
  const std::size_t left = p.total - std::min(p.total, complete + p.elsewhere);
  if (p.done > 0 && left > 0) {
    line += ", ETA " + FormatDuration(elapsed_s / static_cast<double>(p.done) * left);
  }
  return line;
}

ProgressBar::ProgressBar(std::FILE* out, bool terminal, double log_every_s)
    : out_(out), terminal_(terminal), log_every_s_(log_every_s), start_(Clock::now()) {}

void ProgressBar::Update(const Progress& p, bool force) {
  if (!out_) return;
  const auto now = Clock::now();
  const double since = std::chrono::duration<double>(now - last_).count();
  if (!force && since < (terminal_ ? 0.1 : log_every_s_)) return;
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  if (terminal_) {
    std::fprintf(out_, "\r%s\033[K", FormatProgress(p, elapsed, 30).c_str());
    drawn_ = true;
  } else {
    std::fprintf(out_, "criticality-campaign: %s\n", FormatProgress(p, elapsed, 0).c_str());
  }
  std::fflush(out_);
}

void ProgressBar::Finish(const Progress& p) {
  Update(p, true);
  if (out_ && terminal_ && drawn_) std::fprintf(out_, "\n");
  drawn_ = false;
}

void ProgressBar::Message(const std::string& line) {
  if (!out_) return;
  if (terminal_ && drawn_) std::fprintf(out_, "\r\033[K");
  std::fprintf(out_, "%s\n", line.c_str());
  if (terminal_) last_ = {};  // redraw the bar at once
  drawn_ = false;
  std::fflush(out_);
}

}  // namespace criticality::campaign
