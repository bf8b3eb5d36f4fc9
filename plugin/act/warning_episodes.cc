#include "plugin/act/warning_episodes.h"

namespace criticality::plugin {

WarningEpisodes::WarningEpisodes(const WarningConfig& config) : config_(config) {}

std::optional<WarningChange> WarningEpisodes::Update(const std::string& ego, double t, double p) {
  Episode& e = egos_[ego];
  switch (e.state) {
    case State::kQuiet:
      if (p < config_.threshold) return std::nullopt;
      e.state = State::kOpen;
      e.peak = p;
      return WarningChange::kOpen;
    case State::kOpen:
    case State::kReleasing:
      if (p > e.peak) {  // p > peak >= threshold >= release: open again
        e.peak = p;
        e.state = State::kOpen;
        return WarningChange::kPeak;
      }
      if (p >= config_.release) {
        e.state = State::kOpen;
        return std::nullopt;
      }
      if (e.state == State::kOpen) {
        e.state = State::kReleasing;
        e.below_since_s = t;
      }
      // Small tolerance on times so that 3 steps of 0.1 s make 0.3 s.
      if (t - e.below_since_s >= config_.release_after_s - 1e-9) {
        e.state = State::kQuiet;
        return WarningChange::kClose;
      }
      return std::nullopt;
  }
  return std::nullopt;
}

bool WarningEpisodes::Leave(const std::string& ego) {
  auto it = egos_.find(ego);
  if (it == egos_.end()) return false;
  const bool open = it->second.state != State::kQuiet;
  egos_.erase(it);
  return open;
}

WarningEpisodes::State WarningEpisodes::StateOf(const std::string& ego) const {
  auto it = egos_.find(ego);
  return it == egos_.end() ? State::kQuiet : it->second.state;
}

bool WarningEpisodes::Warning(const std::string& ego) const {
  return StateOf(ego) != State::kQuiet;
}

std::vector<std::string> WarningEpisodes::Open() const {
  std::vector<std::string> open;
  for (const auto& [ego, e] : egos_) {
    if (e.state != State::kQuiet) open.push_back(ego);
  }
  return open;
}

}  // namespace criticality::plugin
