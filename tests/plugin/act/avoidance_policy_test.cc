// The closed loop's decision policy: engage at the threshold, hold for the minimum time,
// release only after the estimate stayed below the release threshold long enough, and no
// chatter when the estimate oscillates around the engage threshold.
#include "plugin/act/avoidance_policy.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace criticality::plugin {
namespace {

using D = AvoidanceDecision;

AvoidancePolicyConfig Config() {
  AvoidancePolicyConfig c;
  c.engage_threshold = 0.9;
  c.release_threshold = 0.45;
  c.min_hold_s = 1.0;
  c.release_after_s = 0.5;
  return c;
}

// Runs p[k] at time 0.1 k; returns the decisions.
std::vector<D> Feed(AvoidancePolicy* policy, const std::vector<double>& p) {
  std::vector<D> out;
  for (size_t k = 0; k < p.size(); ++k) out.push_back(policy->Step(0.1 * k, p[k]));
  return out;
}

int Count(const std::vector<D>& d, D what) {
  int n = 0;
  for (D x : d) n += x == what;
  return n;
}

TEST(AvoidancePolicy, EngagesAtTheThresholdNotBelow) {
  AvoidancePolicy policy(Config());
  EXPECT_EQ(policy.Step(0.0, 0.8999), D::kIdle);
  EXPECT_FALSE(policy.engaged());
  EXPECT_EQ(policy.Step(0.1, 0.9), D::kEngage);
  EXPECT_TRUE(policy.engaged());
  EXPECT_DOUBLE_EQ(policy.engaged_since_s(), 0.1);
}

TEST(AvoidancePolicy, HoldsForTheMinimumTimeWhateverTheEstimate) {
  AvoidancePolicy policy(Config());
  ASSERT_EQ(policy.Step(0.0, 1.0), D::kEngage);
  // p drops to 0 at once: still held until 1.0 s after engaging.
  for (int k = 1; k < 10; ++k) EXPECT_EQ(policy.Step(0.1 * k, 0.0), D::kHold) << k;
  EXPECT_EQ(policy.Step(1.0, 0.0), D::kRelease);
  EXPECT_FALSE(policy.engaged());
}

TEST(AvoidancePolicy, ReleasesOnlyAfterTheEstimateStayedBelowTheReleaseThreshold) {
  AvoidancePolicy policy(Config());
  ASSERT_EQ(policy.Step(0.0, 1.0), D::kEngage);
  for (int k = 1; k <= 20; ++k) ASSERT_EQ(policy.Step(0.1 * k, 0.6), D::kHold);  // hysteresis
  // Below 0.45 from 2.1 s: released at 2.6 s (0.5 s later), not before.
  for (int k = 21; k < 26; ++k) EXPECT_EQ(policy.Step(0.1 * k, 0.2), D::kHold) << k;
  EXPECT_EQ(policy.Step(2.6, 0.2), D::kRelease);
}

TEST(AvoidancePolicy, ABriefRiseRestartsTheReleaseCountdown) {
  AvoidancePolicy policy(Config());
  ASSERT_EQ(policy.Step(0.0, 1.0), D::kEngage);
  for (int k = 1; k <= 4; ++k) policy.Step(0.1 * k, 0.1);  // below since 0.1 s
  EXPECT_EQ(policy.Step(0.5, 0.5), D::kHold);              // back above the release threshold
  // Below again from 0.6 s: without the restart it would be released at 1.0 s (held and
  // below since 0.1 s); with it, at 1.1 s.
  for (int k = 6; k <= 10; ++k) EXPECT_EQ(policy.Step(0.1 * k, 0.1), D::kHold) << k;
  EXPECT_EQ(policy.Step(1.1, 0.1), D::kRelease);
}

TEST(AvoidancePolicy, NoChatterWhenTheEstimateOscillatesAroundTheThreshold) {
  // The crossing scenario's pattern before this policy: p above and below the threshold on
  // alternate steps. Once engaged it stays engaged: one engagement, no release.
  AvoidancePolicy policy(Config());
  std::vector<double> p;
  for (int k = 0; k < 50; ++k) p.push_back(k % 2 ? 0.95 : 0.85);
  const std::vector<D> d = Feed(&policy, p);
  EXPECT_EQ(Count(d, D::kEngage), 1);
  EXPECT_EQ(Count(d, D::kRelease), 0);
}

TEST(AvoidancePolicy, OscillationAcrossTheWholeBandReleasesAtMostOncePerHoldPeriod) {
  // Even p jumping between 1 and 0 every step cannot make it switch every step: every
  // engagement lasts at least min_hold_s.
  AvoidancePolicy policy(Config());
  std::vector<double> p;
  for (int k = 0; k < 100; ++k) p.push_back(k % 2 ? 0.0 : 1.0);
  const std::vector<D> d = Feed(&policy, p);
  // Every 0 breaks the 1s: below never lasts 0.5 s, so no release at all.
  EXPECT_EQ(Count(d, D::kRelease), 0);
  // Long runs: 1.0 for a step, then 0 for 0.6 s, repeated: releases are >= 1 s apart.
  AvoidancePolicy second(Config());
  std::vector<double> q;
  for (int k = 0; k < 100; ++k) q.push_back(k % 7 == 0 ? 1.0 : 0.0);
  const std::vector<D> e = Feed(&second, q);
  double last_change = -10.0;
  for (size_t k = 0; k < e.size(); ++k) {
    if (e[k] == D::kEngage || e[k] == D::kRelease) {
      if (e[k] == D::kRelease) {
        EXPECT_GE(0.1 * k - last_change, 1.0 - 1e-9) << k;
      }
      last_change = 0.1 * k;
    }
  }
  EXPECT_GE(Count(e, D::kRelease), 1);
}

TEST(AvoidancePolicy, TheCallersVetoDefersTheRelease) {
  AvoidancePolicy policy(Config());
  ASSERT_EQ(policy.Step(0.0, 1.0), D::kEngage);
  for (int k = 1; k <= 30; ++k) EXPECT_EQ(policy.Step(0.1 * k, 0.0, false), D::kHold) << k;
  EXPECT_TRUE(policy.engaged());
  // Once allowed, released at once: the estimate has been low long enough.
  EXPECT_EQ(policy.Step(3.1, 0.0, true), D::kRelease);
}

TEST(AvoidancePolicy, ResetForgetsAnEngagement) {
  AvoidancePolicy policy(Config());
  ASSERT_EQ(policy.Step(0.0, 1.0), D::kEngage);
  policy.Reset();
  EXPECT_FALSE(policy.engaged());
  EXPECT_EQ(policy.Step(0.1, 0.5), D::kIdle);
}

TEST(AvoidancePolicy, RefusesConfigsThatCannotWork) {
  AvoidancePolicyConfig c = Config();
  c.release_threshold = 0.95;
  EXPECT_THROW(AvoidancePolicy{c}, std::invalid_argument);
  c = Config();
  c.engage_threshold = 1.5;
  EXPECT_THROW(AvoidancePolicy{c}, std::invalid_argument);
  c = Config();
  c.min_hold_s = -1.0;
  EXPECT_THROW(AvoidancePolicy{c}, std::invalid_argument);
}

}  // namespace
}  // namespace criticality::plugin
