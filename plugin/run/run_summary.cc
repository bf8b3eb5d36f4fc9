#include "plugin/run/run_summary.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace criticality::plugin {
namespace {

std::string Str(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string StrOrNull(const std::string& s) { return s.empty() ? "null" : Str(s); }

std::string Num(double v) {
  if (!std::isfinite(v)) return "null";
  std::ostringstream o;
  o.precision(10);
  o << v;
  return o.str();
}

}  // namespace

std::string SummaryJson(const RunSummary& s) {
  std::ostringstream o;
  const double rate = s.wall_s > 0.0 ? s.estimates / s.wall_s : 0.0;
  o << "{\"status\":" << Str(s.status) << ",\"exit_code\":" << s.exit_code
    << ",\"error\":" << StrOrNull(s.error) << ",\"end_reason\":" << StrOrNull(s.end_reason)
    << ",\"sim_time_s\":" << Num(s.sim_time_s) << ",\"steps\":" << s.steps << ",\"egos\":" << s.egos
    << ",\"estimates\":" << s.estimates << ",\"vehicle_hours\":" << Num(s.vehicle_hours)
    << ",\"vehicle_km\":" << Num(s.vehicle_km) << ",\"shortcut_estimates\":" << s.shortcut_estimates
    << ",\"objects_out_of_reach\":" << s.objects_out_of_reach
    << ",\"invalid_objects\":" << s.invalid_objects
    << ",\"conditioned_states\":" << s.conditioned_states
    << ",\"parked_objects\":" << s.parked_objects
    << ",\"other_class_objects\":" << s.other_class_objects
    << ",\"parked_egos\":" << s.parked_egos << ",\"warnings\":" << s.warnings
    << ",\"actions\":" << s.actions << ",\"collisions\":" << s.collisions
    << ",\"ego_collisions\":" << s.ego_collisions << ",\"ego_events\":" << s.ego_events
    << ",\"time_s\":{\"sumo\":" << Num(s.times.sumo_s) << ",\"observe\":" << Num(s.times.observe_s)
    << ",\"scenes\":" << Num(s.times.scenes_s) << ",\"estimate\":" << Num(s.times.estimate_s)
    << ",\"act\":" << Num(s.times.act_s) << ",\"record\":" << Num(s.times.record_s)
    << ",\"estimate_wait\":" << Num(s.times.estimate_wait_s) << "}"
    << ",\"pipelined\":" << (s.pipelined ? "true" : "false")
    << ",\"wall_s\":" << Num(s.wall_s) << ",\"cpu_s\":" << Num(s.cpu_s)
    << ",\"estimates_per_s\":" << Num(rate)
    << ",\"estimator_ms_mean\":" << Num(s.estimates ? s.estimator_ms_sum / s.estimates : 0.0)
    << ",\"estimator_ms_max\":" << Num(s.estimator_ms_max)
    << ",\"max_rss_mb\":" << Num(s.max_rss_mb) << ",\"expectation_met\":"
    << (s.expectation_met ? (*s.expectation_met ? "true" : "false") : "null")
    << ",\"category\":" << StrOrNull(s.category) << ",\"output\":" << StrOrNull(s.output) << "}";
  return o.str();
}

namespace {

// 0:42, 12:05, 1:02:03.
std::string Clock(double seconds) {
  const long long t = static_cast<long long>(std::llround(std::max(0.0, seconds)));
  char b[32];
  if (t >= 3600)
    std::snprintf(b, sizeof b, "%lld:%02lld:%02lld", t / 3600, t / 60 % 60, t % 60);
  else
    std::snprintf(b, sizeof b, "%lld:%02lld", t / 60, t % 60);
  return b;
}

}  // namespace

std::string ProgressText(const ProgressState& p) {
  char b[256];
  std::string out;
  const double done_s = p.time_s - p.begin_s;
  if (p.end_s > p.begin_s) {
    const double share = std::clamp(done_s / (p.end_s - p.begin_s), 0.0, 1.0);
    std::snprintf(b, sizeof b, "t %.1f / %.6g s  %3.0f %%", p.time_s, p.end_s, 100.0 * share);
    out = b;
    // The time left at the pace so far: wall time per simulated second, times those left.
    if (done_s > 0.0 && 100.0 * share < 99.5)  // not at a shown 100 %
      out += "  ETA " + Clock(p.wall_s / done_s * (p.end_s - p.time_s));
  } else {
    std::snprintf(b, sizeof b, "t %.1f s (ends when SUMO does)", p.time_s);
    out = b;
  }
  out += "  elapsed " + Clock(p.wall_s);
  std::snprintf(b, sizeof b, "  %.0f steps/s  egos %lld  warnings %lld  collisions %lld",
                p.wall_s > 0.0 ? p.steps / p.wall_s : 0.0, p.egos, p.warnings, p.collisions);
  return out + b;
}

ProgressLine::ProgressLine(bool on) {
  if (!on) return;
  held_ = std::tmpfile();
  terminal_ = held_ ? ::dup(2) : -1;
  if (terminal_ < 0 && held_) {  // cannot hold what SUMO writes: no line rather than a mess
    std::fclose(held_);
    held_ = nullptr;
    return;
  }
  on_ = held_ != nullptr;
}

ProgressLine::~ProgressLine() {
  Release();
  if (held_) std::fclose(held_);
  if (terminal_ >= 0) ::close(terminal_);
}

void ProgressLine::Hold() {
  if (!held_ || holding_) return;
  std::fflush(stderr);
  holding_ = ::dup2(fileno(held_), 2) >= 0;
}

bool ProgressLine::Release() {
  if (!holding_) return false;
  std::fflush(stderr);
  ::dup2(terminal_, 2);
  holding_ = false;
  const int fd = fileno(held_);
  const off_t size = ::lseek(fd, 0, SEEK_CUR);
  if (size <= 0) return false;
  std::string text(static_cast<size_t>(size), '\0');
  const ssize_t n = ::pread(fd, text.data(), text.size(), 0);
  text.resize(n > 0 ? static_cast<size_t>(n) : 0);
  if (::ftruncate(fd, 0) != 0 || ::lseek(fd, 0, SEEK_SET) != 0) {
    // The file cannot be reused: stop holding rather than lose or repeat messages.
    std::fclose(held_);
    held_ = nullptr;
  }
  if (shown_) std::fputs("\r\033[K", stderr);
  if (!text.empty() && text.back() != '\n') text += '\n';
  std::fputs(text.c_str(), stderr);
  std::fflush(stderr);
  shown_ = false;
  return true;
}

void ProgressLine::Show(const std::string& text) {
  if (!on_) return;
  std::fprintf(stderr, "\r  %s\033[K", text.c_str());
  std::fflush(stderr);
  shown_ = true;
}

void ProgressLine::End() {
  if (on_ && shown_) std::fputs("\n", stderr);
  shown_ = false;
}

}  // namespace criticality::plugin
