#include "plugin/run/run_summary.h"

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
    << ",\"estimates\":" << s.estimates << ",\"shortcut_estimates\":" << s.shortcut_estimates
    << ",\"objects_out_of_reach\":" << s.objects_out_of_reach
    << ",\"invalid_objects\":" << s.invalid_objects << ",\"warnings\":" << s.warnings
    << ",\"actions\":" << s.actions << ",\"collisions\":" << s.collisions
    << ",\"ego_collisions\":" << s.ego_collisions << ",\"ego_events\":" << s.ego_events
    << ",\"time_s\":{\"sumo\":" << Num(s.times.sumo_s) << ",\"observe\":" << Num(s.times.observe_s)
    << ",\"scenes\":" << Num(s.times.scenes_s) << ",\"estimate\":" << Num(s.times.estimate_s)
    << ",\"act\":" << Num(s.times.act_s) << ",\"record\":" << Num(s.times.record_s) << "}"
    << ",\"wall_s\":" << Num(s.wall_s) << ",\"cpu_s\":" << Num(s.cpu_s)
    << ",\"estimates_per_s\":" << Num(rate)
    << ",\"estimator_ms_mean\":" << Num(s.estimates ? s.estimator_ms_sum / s.estimates : 0.0)
    << ",\"estimator_ms_max\":" << Num(s.estimator_ms_max)
    << ",\"max_rss_mb\":" << Num(s.max_rss_mb) << ",\"expectation_met\":"
    << (s.expectation_met ? (*s.expectation_met ? "true" : "false") : "null")
    << ",\"category\":" << StrOrNull(s.category) << ",\"output\":" << StrOrNull(s.output) << "}";
  return o.str();
}

}  // namespace criticality::plugin
