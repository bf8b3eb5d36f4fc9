#include "plugin/scenes/stop_lines.h"

#include <cmath>

namespace criticality::plugin {

std::optional<StopLine> StopLineOf(const VehicleOnLane& v, const std::string& id,
                                   const SceneConfig& config, RoadNetwork* network,
                                   TrafficView* traffic) {
  const double reach = ReachAhead(v.speed_mps, config);
  const std::optional<SignalReport> tls =
      v.observable_only ? std::nullopt : traffic->NextSignal(id);  // on its route
  if (tls) {
    if (tls->distance_m <= reach) {
      const double d = std::fmax(0.0, tls->distance_m);
      if (tls->state == 'r' || tls->state == 'u') return StopLine{StopLine::Reason::kRedLight, d};
      if (tls->state == 'y' || tls->state == 'Y')
        return StopLine{StopLine::Reason::kYellowLight, d};
    }
  }
  const double to_end = network->Lane(v.lane).length_m - v.lane_position_m;
  if (to_end > reach) return std::nullopt;
  int index = v.route_index;
  const std::string next = NextLaneOf(v, v.lane, network, &index);
  if (next.empty()) return std::nullopt;
  for (const LaneLink& link : network->LinksNow(v.lane)) {
    if (link.lane != next && link.internal != next) continue;
    const std::string& st = link.state;
    // Seen, not read from the route: the signal of the link it is seen to take, at its lane's
    // end (a signal further on is not seen).
    if (v.observable_only && (st == "r" || st == "u"))
      return StopLine{StopLine::Reason::kRedLight, std::fmax(0.0, to_end)};
    if (v.observable_only && (st == "y" || st == "Y"))
      return StopLine{StopLine::Reason::kYellowLight, std::fmax(0.0, to_end)};
    const bool must_stop = st == "s" || st == "w";
    const bool must_yield =
        config.yield_stops && (st == "m" || st == "g" || st == "=") && link.has_foe;
    if (must_stop || must_yield) return StopLine{StopLine::Reason::kYield, std::fmax(0.0, to_end)};
    break;
  }
  return std::nullopt;
}

bool MayYieldAhead(const VehicleOnLane& v, const SceneConfig& config, RoadNetwork* network) {
  const double to_end = network->Lane(v.lane).length_m - v.lane_position_m;
  if (to_end > ReachAhead(v.speed_mps, config)) return false;
  int index = v.route_index;
  const std::string next = NextLaneOf(v, v.lane, network, &index);
  if (next.empty()) return false;
  for (const LaneLink& link : network->LinksNow(v.lane)) {
    if (link.lane != next && link.internal != next) continue;
    const std::string& st = link.state;
    return st == "m" || st == "=" || st == "g" || st == "s" || st == "w";
  }
  return false;
}

}  // namespace criticality::plugin
