#pragma once
// `report`: what a campaign found, as tables (CSV and Markdown, written here) and figures with
// one HTML page (made by tools/campaign/campaign_report.py with matplotlib, when available).
// Metrics are computed from the merged database, tolerating older run files: a metric whose
// columns are missing is reported as not computable, with the reason, never guessed.
#include <filesystem>
#include <string>
#include <vector>

#include "tools/campaign/campaign_folder.h"

namespace criticality::campaign {

struct ReportOptions {
  /** A warning episode is a false alarm when no collision, overlap, pass-through or hard
   *  braking of its ego follows from its start until `grace_s` after its end (the view
   *  warning_outcomes of plugin/record/result_views.sql). */
  double grace_s{1.0};
  /** Reliability diagram: a step counts as followed by a collision when one involving its ego
   *  happens within the run's prediction horizon (--horizon; this when the plan does not set
   *  it: the driver's default). */
  double default_horizon_s{2.0};
  /** Fewest egos that collided (run, ego pairs) for a reliability diagram. */
  int reliability_min_collisions{5};
  bool plots{true};
  /** Warnings drawn as a picture of their scene (warning_scenes), at most this many. */
  int scene_pictures{40};
  /** criticality-bench for the pictures' hypotheses; empty: $CRIT_BENCH, next to this program
   *  in the build tree (estimator/bench/), or PATH. */
  std::string bench;
  std::string python;            ///< interpreter; empty: $CRIT_PYTHON, /usr/bin/python3, python3
  std::filesystem::path script;  ///< campaign_report.py; empty: the built-in default
};

struct ReportResult {
  std::filesystem::path dir;
  std::vector<std::string> files;  ///< written, relative to dir
  std::vector<std::string> notes;  ///< what could not be computed, and why
  bool figures{false};
  std::string figures_missing;  ///< why there are no figures (one line), when so
};

ReportResult MakeReport(const CampaignFolder& folder, const ReportOptions& options);

}  // namespace criticality::campaign
