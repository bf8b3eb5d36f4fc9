#pragma once
// Warning episodes, one state machine per ego, on the estimate --warn-on names:
//
//   quiet --p >= threshold--> open --p < release--> releasing --p >= release--> open
//   releasing --p stayed below release for release_after_s--> quiet   (the episode ends)
//   open | releasing --the ego leaves (arrives, vanishes, starts a teleport)--> gone
//
// With hysteresis (release <= threshold) and the wait, one approach is one episode: a dip below
// the threshold, or a one-step dip below the release, does not split it. While open or
// releasing a new highest p is the episode's peak. SUMO-independent.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "plugin/act/act_config.h"
#include "plugin/act/act_outcome.h"

namespace criticality::plugin {

class WarningEpisodes {
 public:
  enum class State { kQuiet, kOpen, kReleasing };

  explicit WarningEpisodes(const WarningConfig& config);
  /** The ego's estimate `p` at time t: the change of its episode, if any (kOpen and kPeak carry
   *  p; the caller adds where the ego is). At most one change per call. */
  std::optional<WarningChange> Update(const std::string& ego, double t, double p);
  /** The ego left: its episode, if one is open, ends now (returns true then). */
  bool Leave(const std::string& ego);
  /** Whether the ego's episode is open (or releasing). */
  bool Warning(const std::string& ego) const;
  State StateOf(const std::string& ego) const;
  /** Egos whose episode is open (to close them when the run ends), in ID order. */
  std::vector<std::string> Open() const;

 private:
  struct Episode {
    State state{State::kQuiet};
    double peak{0.0};
    double below_since_s{0.0};  ///< kReleasing: when p fell below the release level
  };
  WarningConfig config_;
  std::map<std::string, Episode> egos_;
};

}  // namespace criticality::plugin
