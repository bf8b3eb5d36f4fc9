#include "plugin/scenes/stop_lines.h"

#include <cmath>

namespace criticality::plugin {

std::optional<StopLine> StopLineOf(const VehicleOnLane& v, const std::string& id,
                                   const SceneConfig& config, RoadNetwork* network,
                                   TrafficView* traffic) {
  const double reach = ReachAhead(v.speed_mps, config);
  if (const std::optional<SignalReport> tls = traffic->NextSignal(id)) {
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
  const std::string next = NextLaneOnRoute(*network, v.lane, v.route, &index);
  if (next.empty()) return std::nullopt;
  for (const LaneLink& link : network->LinksNow(v.lane)) {
    if (link.lane != next && link.internal != next) continue;
    const std::string& st = link.state;
    const bool must_stop = st == "s" || st == "w";
    const bool must_yield = (st == "m" || st == "g" || st == "=") && link.has_foe;
    if (must_stop || must_yield) return StopLine{StopLine::Reason::kYield, std::fmax(0.0, to_end)};
    break;
  }
  return std::nullopt;
}

}  // namespace criticality::plugin
