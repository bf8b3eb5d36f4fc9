#include "plugin/scenes/stop_lines.h"

#include <cmath>

namespace criticality::plugin {

namespace {

// Whether a link's internal lane leads on into another internal lane: SUMO's internal junction,
// where a vehicle that must yield waits inside the junction.
bool WaitsInTheJunction(const LaneLink& link, RoadNetwork* network) {
  if (!IsInternal(link.internal)) return false;
  for (const LaneLink& next : network->Links(link.internal)) {
    if (IsInternal(next.internal) || IsInternal(next.lane)) return true;
  }
  return false;
}

// The link from the vehicle's lane to its next lane (its route's, or the one it is seen to
// take), read now; nullopt when the lane's end lies beyond `reach` or there is no next lane.
std::optional<LaneLink> LinkAhead(const VehicleOnLane& v, double reach, RoadNetwork* network) {
  const double to_end = network->Lane(v.lane).length_m - v.lane_position_m;
  if (to_end > reach) return std::nullopt;
  int index = v.route_index;
  const std::string next = NextLaneOf(v, v.lane, network, &index);
  if (next.empty()) return std::nullopt;
  for (const LaneLink& link : network->LinksNow(v.lane)) {
    if (link.lane == next || link.internal == next) return link;
  }
  return std::nullopt;
}

}  // namespace

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
  const std::optional<LaneLink> link = LinkAhead(v, reach, network);
  if (!link) return std::nullopt;
  const double to_end = std::fmax(0.0, network->Lane(v.lane).length_m - v.lane_position_m);
  const std::string& st = link->state;
  // Seen, not read from the route: the signal of the link it is seen to take, at its lane's
  // end (a signal further on is not seen).
  if (v.observable_only && (st == "r" || st == "u"))
    return StopLine{StopLine::Reason::kRedLight, to_end};
  if (v.observable_only && (st == "y" || st == "Y"))
    return StopLine{StopLine::Reason::kYellowLight, to_end};
  const bool must_stop = st == "s" || st == "w";
  const bool must_yield =
      config.yield_stops && (st == "m" || st == "g" || st == "=") && link->has_foe;
  if (must_stop) return StopLine{StopLine::Reason::kYield, to_end};
  if (!must_yield) return std::nullopt;
  // SUMO lets a vehicle that yields (a left turn across oncoming traffic) enter the junction and
  // wait at its internal junction, where its internal lane continues into another one: the
  // line is there, at the end of the first internal lane.
  double d = to_end;
  if (config.internal_junction_yield && WaitsInTheJunction(*link, network)) {
    d += network->Lane(link->internal).length_m;
    if (d > reach) return std::nullopt;
  }
  return StopLine{StopLine::Reason::kYield, d};
}

bool MayYieldAhead(const VehicleOnLane& v, const SceneConfig& config, RoadNetwork* network) {
  const std::optional<LaneLink> link = LinkAhead(v, ReachAhead(v.speed_mps, config), network);
  if (!link) return false;
  const std::string& st = link->state;
  return st == "m" || st == "=" || st == "g" || st == "s" || st == "w";
}

}  // namespace criticality::plugin
