#pragma once
// Where on the network warnings and collisions happened (successful runs): counts per edge and
// per junction (an internal lane `:J_0_1`, crossing or walking area belongs to junction J), and
// the points for the map (x/y when the run file has them, else lane and position along it, which
// the figure script places on the lane's shape).
#include <map>
#include <string>
#include <vector>

#include "tools/campaign/sqlite_db.h"
#include "tools/campaign/table_writer.h"

namespace criticality::campaign {

struct Hotspots {
  Table counts;  ///< scenario, parameters, kind (edge | junction), id, warnings, collisions
  Table points;  ///< scenario, parameters, event, run_index, x_m, y_m, lane, pos_m
  std::vector<std::string> notes;
};

/** The network element of a lane or edge ID: {"edge", E} or {"junction", J}. */
std::pair<std::string, std::string> NetworkElement(const std::string& id, bool is_lane);

/** `setting`: each run's grouping parameters ("act=warn", "-" without a grid): counts and
 *  points are per scenario and setting, so that maps can show each parameter value apart. */
Hotspots ComputeHotspots(SqliteDb& db, const std::map<std::size_t, std::string>& setting);

}  // namespace criticality::campaign
