#pragma once
// The report's exposure and rates (rates.h): per run, per scenario and setting, per value of
// each grid parameter and per vehicle class of the egos: vehicle-hours and vehicle-km of
// estimation, and warnings, false alarms and ego collisions per vehicle-hour and per million
// vehicle-km, each with its 95 % interval across the group's runs (seeds, repetitions).
#include <map>
#include <set>
#include <string>
#include <vector>

#include "tools/campaign/run_metrics.h"
#include "tools/campaign/sqlite_db.h"
#include "tools/campaign/table_writer.h"

namespace criticality::campaign {

struct RateAxis {
  std::string name;
  std::vector<std::string> values;
};

struct RateInputs {
  const RunMetricsSet& metrics;
  std::vector<RateAxis> axes;  ///< the grouping axes (not SUMO's seed), in file order
  std::map<std::string, std::size_t> scenario_order;
  /** act=brake runs: false alarms as counted against their act=warn twin, and the egos whose
   *  warnings are no false alarm because they collided in the twin. */
  std::map<std::size_t, long long> false_alarms;
  std::map<std::size_t, std::set<std::string>> twin_collided;
};

struct RateTables {
  Table per_run;   ///< exposure.csv: each run's exposure and counts
  Table rates;     ///< rates.csv: one row per group and measure
  Table by_class;  ///< by_vehicle_class.csv: exposure and counts per class
  std::vector<std::string> notes;
};

/** The event counts and exposure of one run (or of one vehicle class's share of it). */
struct RunEvents {
  double hours{0.0}, km{0.0};
  double warnings{0.0}, false_alarms{0.0}, ego_collisions{0.0};
  long long egos{0};
};

/** A run's events per vehicle class of its egos ("(unknown)" for an ego the egos table lacks). */
std::map<std::string, RunEvents> EventsByClass(const RunMetrics& m,
                                               const std::set<std::string>& not_false_alarms);

RateTables MakeRateTables(const RateInputs& in);

/** The table report_exposure(run_index, vehicle_class, egos, vehicle_hours, vehicle_km,
 *  warnings, false_alarms, ego_collisions) in the campaign database, made afresh. */
void WriteExposureTable(SqliteDb& db, const RateInputs& in);

}  // namespace criticality::campaign
