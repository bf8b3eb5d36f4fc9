#include "plugin/act/avoidance_policy.h"

#include <cmath>
#include <stdexcept>

namespace criticality::plugin {

AvoidancePolicy::AvoidancePolicy(const AvoidancePolicyConfig& c) : config_(c) {
  auto unit = [](double x) { return std::isfinite(x) && x >= 0.0 && x <= 1.0; };
  if (!unit(c.engage_threshold) || !unit(c.release_threshold))
    throw std::invalid_argument("the brake thresholds must lie in [0, 1]");
  if (c.release_threshold > c.engage_threshold)
    throw std::invalid_argument("--brake-release must not exceed --brake-threshold");
  if (!(c.min_hold_s >= 0.0) || !(c.release_after_s >= 0.0))
    throw std::invalid_argument("--act-hold and --act-release-after must be >= 0 s");
}

void AvoidancePolicy::Reset() {
  engaged_ = false;
  below_ = false;
}

AvoidanceDecision AvoidancePolicy::Step(double time_s, double p, bool may_release) {
  // Small tolerance on times so that 10 steps of 0.1 s make 1.0 s.
  constexpr double kEps = 1e-9;
  if (!engaged_) {
    if (p >= config_.engage_threshold) {
      engaged_ = true;
      engaged_since_s_ = time_s;
      below_ = false;
      return AvoidanceDecision::kEngage;
    }
    return AvoidanceDecision::kIdle;
  }
  if (p < config_.release_threshold) {
    if (!below_) {
      below_ = true;
      below_since_s_ = time_s;
    }
  } else {
    below_ = false;
  }
  const bool held = time_s - engaged_since_s_ + kEps >= config_.min_hold_s;
  if (may_release && held && below_ && time_s - below_since_s_ + kEps >= config_.release_after_s) {
    engaged_ = false;
    below_ = false;
    return AvoidanceDecision::kRelease;
  }
  return AvoidanceDecision::kHold;
}

}  // namespace criticality::plugin
