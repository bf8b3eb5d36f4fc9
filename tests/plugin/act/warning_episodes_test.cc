// Warning episodes: one approach is one episode (hysteresis and the release wait), peaks, and an
// ego that leaves while warning. Every series is stepped at 0.1 s as the driver does.
#include "plugin/act/warning_episodes.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace criticality::plugin {
namespace {

using State = WarningEpisodes::State;

// The changes of one ego's episode over a p series (one value per 0.1 s step from t = 0), as
// "t:open", "t:peak", "t:close" (t in tenths of a second).
std::string Replay(WarningEpisodes& w, const std::vector<double>& p) {
  std::string out;
  for (size_t k = 0; k < p.size(); ++k) {
    const auto change = w.Update("ego", 0.1 * k, p[k]);
    if (!change) continue;
    const char* name = *change == WarningChange::kOpen ? "open"
                       : *change == WarningChange::kPeak ? "peak"
                                                         : "close";
    out += (out.empty() ? "" : " ") + std::to_string(k) + ":" + name;
  }
  return out;
}

WarningConfig Config(double release_after_s = 0.3) {
  WarningConfig c;
  c.threshold = 0.9;
  c.release = 0.72;
  c.release_after_s = release_after_s;
  return c;
}

TEST(WarningEpisodes, OpensAtTheThresholdAndRecordsHigherPeaks) {
  WarningEpisodes w(Config());
  EXPECT_EQ(Replay(w, {0.5, 0.89, 0.9, 0.95, 0.93, 0.97}), "2:open 3:peak 5:peak");
  EXPECT_EQ(w.StateOf("ego"), State::kOpen);
}

TEST(WarningEpisodes, ADipBelowTheThresholdButAboveTheReleaseDoesNotEndIt) {
  WarningEpisodes w(Config());
  EXPECT_EQ(Replay(w, {0.95, 0.8, 0.75, 0.73, 0.92, 0.8}), "0:open");
  EXPECT_TRUE(w.Warning("ego"));
}

TEST(WarningEpisodes, ItEndsOnlyOnceBelowTheReleaseForTheWholeWait) {
  WarningEpisodes w(Config(0.3));
  // Below 0.72 at steps 1-2 (0.1 s), back above at 3, then below from 4: 4 + 3 steps = 7.
  EXPECT_EQ(Replay(w, {0.95, 0.5, 0.5, 0.8, 0.5, 0.5, 0.5, 0.5, 0.5}), "0:open 7:close");
  EXPECT_EQ(w.StateOf("ego"), State::kQuiet);
  // Releasing in between: below the release, not yet ended.
  WarningEpisodes r(Config(0.3));
  Replay(r, {0.95, 0.5});
  EXPECT_EQ(r.StateOf("ego"), State::kReleasing);
  EXPECT_EQ(r.Open(), std::vector<std::string>{"ego"});
}

TEST(WarningEpisodes, WithoutAWaitTheFirstStepBelowTheReleaseEndsIt) {
  WarningEpisodes w(Config(0.0));
  EXPECT_EQ(Replay(w, {0.95, 0.71, 0.95}), "0:open 1:close 2:open");
}

TEST(WarningEpisodes, AnEgoThatLeavesWhileWarningEndsItsEpisode) {
  WarningEpisodes w(Config());
  Replay(w, {0.95});
  EXPECT_TRUE(w.Leave("ego"));
  EXPECT_FALSE(w.Warning("ego"));
  EXPECT_FALSE(w.Leave("ego"));  // nothing open any more
  // A quiet ego that leaves ends nothing.
  w.Update("other", 0.0, 0.1);
  EXPECT_FALSE(w.Leave("other"));
}

}  // namespace
}  // namespace criticality::plugin
