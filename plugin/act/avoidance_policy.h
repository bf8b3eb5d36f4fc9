#pragma once
// When the closed loop (--act brake) takes control of an ego and when it hands it back: one
// decision per ego and step, from one probability (the one --warn-on names: p_collision by
// default) and the step's time. SUMO-independent (unit-tested in avoidance_policy_test.cc).
//
//   engage:  p >= engage_threshold (--brake-threshold)
//   hold:    while engaged, for at least min_hold_s (--act-hold) after engaging, whatever p
//   release: after that, once p < release_threshold (--brake-release; hysteresis) has held
//            for release_after_s (--act-release-after) without a break, and the caller
//            allows it (closed_loop.cc: the escape route followed no longer brakes, and an ego
//            held at a standstill is not handed to a speed a scenario forces)
//
// So one approach is one engagement: the probability may dip below the engage threshold (the
// braking itself lowers it) without the control flipping back and forth every step.
namespace criticality::plugin {

struct AvoidancePolicyConfig {
  double engage_threshold{0.9};
  /** Below this the release may start; must not exceed engage_threshold. */
  double release_threshold{0.45};
  double min_hold_s{1.0};
  double release_after_s{0.5};
};

enum class AvoidanceDecision { kIdle, kEngage, kHold, kRelease };

class AvoidancePolicy {
 public:
  /** Throws std::invalid_argument for a config that cannot work (thresholds outside [0, 1],
   *  release above engage, negative times). */
  explicit AvoidancePolicy(const AvoidancePolicyConfig& config);
  /** The decision at time_s (strictly increasing between calls) for probability p.
   *  may_release = false defers a release that would otherwise come (the caller's veto, e.g.
   *  the escape route still brakes); the countdown below the release threshold goes on. */
  AvoidanceDecision Step(double time_s, double p, bool may_release = true);
  /** Forget the state (the ego left or is teleported): the next Step starts idle. */
  void Reset();
  bool engaged() const { return engaged_; }
  /** The time of the engagement in progress (meaningless when idle). */
  double engaged_since_s() const { return engaged_since_s_; }

 private:
  AvoidancePolicyConfig config_;
  bool engaged_{false};
  double engaged_since_s_{0.0};
  bool below_{false};  ///< p has been below release_threshold since below_since_s_
  double below_since_s_{0.0};
};

}  // namespace criticality::plugin
