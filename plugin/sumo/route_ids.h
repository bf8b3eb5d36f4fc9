#pragma once
// Which IDs SUMO's route and additional files define, read without SUMO, so that an --ego that
// no file defines (a typo) or that names a person is reported before the first step instead of
// after the whole simulation ran. Vehicles come from <vehicle>, <trip> and <flow> (a flow's
// vehicles are FLOW.N), persons from <person> and <personFlow> (PERSONFLOW.N). A file that
// cannot be scanned (compressed, unreadable, using XML includes) makes the answer "cannot tell".
#include <set>
#include <string>
#include <vector>

namespace criticality::plugin {

struct RouteIds {
  std::set<std::string> vehicles, vehicle_flows, persons, person_flows;
  /** Files that could not be scanned; when any, an absent ID proves nothing. */
  std::vector<std::string> unscanned;
};

/** Scans the files (comma-separated lists as SUMO's route-files/additional-files options give
 *  them are accepted too). */
RouteIds ScanRouteIds(const std::vector<std::string>& files);

enum class RouteIdKind { kVehicle, kPerson, kAbsent, kCannotTell };
RouteIdKind Classify(const RouteIds& ids, const std::string& id);

}  // namespace criticality::plugin
