#include "plugin/script/scenario_event.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace criticality::plugin {
namespace {

double Number(const std::string& s, const std::string& line, const char* what) {
  try {
    size_t used = 0;
    const double v = std::stod(s, &used);
    if (used == s.size() && std::isfinite(v)) return v;
  } catch (const std::exception&) {
  }
  throw std::invalid_argument("event '" + line + "': " + what + " '" + s + "' is not a number");
}

}  // namespace

ScenarioEvent ParseEvent(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> w;
  for (std::string t; in >> t;) w.push_back(t);
  const std::string usage =
      "; expected 'TIME TARGET ACTION ARGS', ACTION one of speed-mode, lane-change-mode, speed, "
      "slow-down, lane-change, param, person-speed";
  if (w.size() < 4) throw std::invalid_argument("event '" + line + "': too few words" + usage);
  ScenarioEvent e;
  e.text = line;
  e.time_s = Number(w[0], line, "time");
  if (e.time_s < 0.0) throw std::invalid_argument("event '" + line + "': time must be >= 0");
  e.target = w[1];
  const std::string& a = w[2];
  auto need = [&](size_t n) {
    if (w.size() != n) {
      throw std::invalid_argument("event '" + line + "': " + a + " takes " + std::to_string(n - 3) +
                                  " argument(s)");
    }
  };
  if (a == "speed-mode" || a == "lane-change-mode" || a == "speed" || a == "person-speed") {
    need(4);
    e.action = a == "speed-mode"         ? EventAction::kSpeedMode
               : a == "lane-change-mode" ? EventAction::kLaneChangeMode
               : a == "speed"            ? EventAction::kSpeed
                                         : EventAction::kPersonSpeed;
    e.number = Number(w[3], line, "value");
  } else if (a == "slow-down" || a == "lane-change") {
    need(5);
    e.action = a == "slow-down" ? EventAction::kSlowDown : EventAction::kLaneChange;
    e.number = Number(w[3], line, "value");
    e.duration_s = Number(w[4], line, "duration");
  } else if (a == "param") {
    need(5);
    e.action = EventAction::kParam;
    e.key = w[3];
    e.value = w[4];
  } else {
    throw std::invalid_argument("event '" + line + "': unknown action '" + a + "'" + usage);
  }
  return e;
}

}  // namespace criticality::plugin
