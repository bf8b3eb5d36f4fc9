#pragma once
// Per-run figures from the merged campaign database, tolerant of run files from older or newer
// drivers: each figure says whether it could be computed, and a note says why not.
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "tools/campaign/sqlite_db.h"

namespace criticality::campaign {

struct RunMetrics {
  std::size_t run_index{0};
  std::string scenario;
  std::string label;
  std::string status;
  std::map<std::string, std::string> params;  ///< grid values
  bool ok{false};
  double wall_s{0.0};
  long long steps{0};
  double estimator_ms_sum{0.0};
  std::optional<double> estimator_ms_max;
  long long collisions{0};         ///< every collision SUMO reported
  long long ego_collisions{0};     ///< those involving an ego
  long long warned_collisions{0};  ///< ego collisions preceded by a warning (anticipation known)
  std::vector<double> anticipation_s;
  long long warnings{0};
  long long false_alarms{0};  ///< warnings that nothing followed (view warning_outcomes)
  std::vector<std::string> false_alarm_egos;  ///< the ego of each of those warnings
  std::vector<std::string> collided_egos;     ///< egos with a collision (when egos are known)
  // Exposure: how long and how far the egos were estimated (MetricsAvailability says whether
  // the run files allow it).
  double vehicle_hours{0.0};  ///< ego estimates x the run's step length
  double vehicle_km{0.0};     ///< sum of the egos' speed x step length
  struct EgoExposure {
    double hours{0.0}, km{0.0};
  };
  std::map<std::string, EgoExposure> ego_exposure;
  std::map<std::string, std::string> ego_class;  ///< SUMO's vClass of each ego (table egos)
  std::vector<std::string> warning_egos;         ///< the ego of each warning
  std::vector<std::string> collision_egos;       ///< the ego(s) in each ego collision
};

/** Which figures the database allows. */
struct MetricsAvailability {
  bool steps{false};
  bool estimator_ms{false};
  bool collisions{false};
  bool ego_collisions{false};
  bool anticipation{false};
  bool warnings{false};
  bool false_alarms{false};
  bool vehicle_hours{false};  ///< runs.step_length_s and steps
  bool vehicle_km{false};     ///< and steps.speed_mps
  bool vehicle_class{false};  ///< the egos table
};

struct RunMetricsSet {
  std::vector<RunMetrics> runs;  ///< every merged run, by run index
  MetricsAvailability available;
  std::vector<std::string> notes;  ///< what could not be computed, and why
};

/** Reads campaign_runs, plan_params and the run tables of a merged campaign database. A
 *  collision involves an ego when collisions.involves_ego says so or, for run files without
 *  that column, when its collider or victim was estimated as an ego in that run. False alarms
 *  come from the TEMP view warning_outcomes (plugin/record/result_views.sql, grace_s as its
 *  grace), which this creates on `db`; anticipation from collisions.anticipation_s. */
RunMetricsSet LoadRunMetrics(SqliteDb& db, double grace_s);

/** Ego IDs per run (distinct steps.ego), as the temporary table _run_egos(run_index, ego);
 *  false when the steps table lacks the columns. */
bool MakeRunEgosTable(SqliteDb& db);

/** The SQL condition "collision c involves an ego of its run" for this database. */
std::string EgoCollisionCondition(SqliteDb& db);

}  // namespace criticality::campaign
