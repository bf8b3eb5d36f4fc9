#pragma once
// Is p calibrated? Every estimate of a successful run, binned by its predicted p, against how
// often a collision of its ego followed within the prediction horizon. Steps at or after the
// ego's first collision are left out (the crash has happened; SUMO keeps overlapping vehicles).
// Consecutive steps are strongly correlated: counts are estimates, not independent trials.
#include <string>

#include "tools/campaign/sqlite_db.h"
#include "tools/campaign/table_writer.h"

namespace criticality::campaign {

struct Reliability {
  bool available{false};
  std::string reason;  ///< why not, when not available
  Table bins;          ///< p_low, p_high, steps, mean_p, observed_frequency
  long long steps{0};
  long long followed{0};        ///< steps followed by a collision of their ego within the horizon
  long long ego_collisions{0};  ///< egos that collided: (run, ego) pairs
  double brier{0.0};
};

/** `default_horizon_s` for runs whose grid does not set `horizon` and whose command line
 *  (runs.options) has no --horizon. */
Reliability ComputeReliability(SqliteDb& db, double default_horizon_s, int min_collisions,
                               int bins = 10);

}  // namespace criticality::campaign
