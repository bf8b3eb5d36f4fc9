#include "plugin/scenes/object_lanes.h"

#include <cmath>

#include "criticality/geometry.h"
#include "plugin/network/polyline.h"
#include "plugin/scenes/junction_way.h"

namespace criticality::plugin {

std::string NextLaneOf(const VehicleOnLane& v, const std::string& lane, RoadNetwork* network,
                       int* route_index) {
  if (v.observable_only) return NextLaneSeen(*network, lane, v.vehicle_class, v.blinker);
  return NextLaneOnRoute(*network, lane, v.route, route_index);
}

void FollowRoute(const VehicleOnLane& v, double reach, RoadNetwork* network, LaneCorridor* c,
                 std::string* beyond_junction, std::optional<double>* route_end) {
  std::string current = v.lane;
  int route_index = v.route_index;
  double length = PolylineLength(c->centre);
  bool current_in_centre = true;  // the corridor's centre line ends with `current`
  for (int hop = 0; hop < 8 && (length < c->position_m + reach ||
                                (IsInternal(v.lane) && beyond_junction->empty()));
       ++hop) {
    const std::string next = NextLaneOf(v, current, network, &route_index);
    if (next.empty()) {
      if (!v.observable_only && current_in_centre && !v.route.empty() &&
          network->Lane(current).edge == v.route.back())
        *route_end = std::fmax(0.0, length - v.lane_position_m);
      break;
    }
    if (beyond_junction->empty() && !IsInternal(next)) *beyond_junction = next;
    current_in_centre = length < c->position_m + reach;
    if (current_in_centre) {
      // getLinks names the lane after the junction. With junction_shapes the way there runs
      // through the junction's internal lanes (their shape: the turn); without, the centre
      // line jumps along the chord between the two lanes.
      auto append = [&](const std::string& lane) {
        for (const Point2& p : network->Lane(lane).shape) {
          const Point2& last = c->centre.back();
          if (std::hypot(p.x - last.x, p.y - last.y) > 1e-3) c->centre.push_back(p);
        }
      };
      if (v.junction_shapes) {
        for (const std::string& lane : InternalLanesBetween(*network, current, next)) append(lane);
      }
      append(next);
      length = PolylineLength(c->centre);
    }
    current = next;
  }
}

namespace {

// The neighbours as the vehicle sees them, from `reference` (its lane, or inside a junction
// the lane it drives onto). SUMO numbers lanes from the kerb: the next higher index is on the
// offside (left in right-hand traffic, right in a left-hand network), and beyond the highest
// the opposite direction's lane (CounterLanes::Offside).
void Neighbours(const VehicleOnLane& v, const std::string& reference, RoadNetwork* network,
                CounterLanes* counter_lanes, LaneCorridor* c) {
  const LaneInfo& ref = network->Lane(reference);
  const int index = IsInternal(v.lane) ? ref.index : v.lane_index;
  const int n = network->LaneCount(ref.edge);
  const bool left_hand = counter_lanes->LeftHand();
  std::optional<NeighbourLane>& offside = left_hand ? c->right : c->left;
  std::optional<NeighbourLane>& nearside = left_hand ? c->left : c->right;
  const std::string beyond = ref.edge + "_" + std::to_string(index + 1);
  const std::string within = ref.edge + "_" + std::to_string(index - 1);
  if (index + 1 < n) {
    if (Allows(*network, beyond, v.vehicle_class))
      offside = NeighbourLane{network->Lane(beyond).width_m, false};
  } else if (const auto counter = counter_lanes->Offside(reference)) {
    if (Allows(*network, *counter, v.vehicle_class))
      offside = NeighbourLane{network->Lane(*counter).width_m, true};
  }
  if (index > 0 && Allows(*network, within, v.vehicle_class))
    nearside = NeighbourLane{network->Lane(within).width_m, false};
}

}  // namespace

std::string LaneChangeTarget(const VehicleOnLane& v, RoadNetwork* network, bool left_hand) {
  if (v.blinker == Blinker::kNone || v.lane.empty() || IsInternal(v.lane)) return "";
  const LaneInfo& own = network->Lane(v.lane);
  const int side = v.blinker == Blinker::kLeft ? 1 : -1;  // +1: to the left
  const int index = v.lane_index + (left_hand ? -side : side);
  if (index < 0 || index >= network->LaneCount(own.edge)) return "";
  const std::string target = own.edge + "_" + std::to_string(index);
  if (!Allows(*network, target, v.vehicle_class)) return "";
  // The front's place on the shape (SUMO's lane position scaled, OnShape, measured once), the
  // centre half the body's length behind it.
  double at_front = 0.0, at_centre = 0.0;
  const double front_on_shape = OnShape(own, v.lane_position_m);
  const Point2 on = PointAlong(own.shape, front_on_shape, &at_front);
  PointAlong(own.shape, std::fmax(0.0, front_on_shape - 0.5 * v.length_m), &at_centre);
  const double left_offset =
      std::cos(at_front) * (v.front.y - on.y) - std::sin(at_front) * (v.front.x - on.x);
  const double left_turn = WrapAngle(v.centre.yaw - at_centre);
  if (side * left_offset < kLaneChangeMinOffsetM || side * left_turn < kLaneChangeMinAngleRad)
    return "";
  return target;
}

ObjectLanes LanesOf(const VehicleOnLane& seen, const SceneConfig& config, double step_s,
                    RoadNetwork* network, CounterLanes* counter_lanes) {
  ObjectLanes out;
  if (config.lane_change_yaw_rate && !config.instant_lane_changes && !seen.lane.empty() &&
      !IsInternal(seen.lane) && seen.lane_position_m < seen.length_m) {
    const LaneInfo& own = network->Lane(seen.lane);
    double yaw = 0.0;
    PointAlong(own.shape, OnShape(own, 0.5 * seen.lane_position_m), &yaw);
    out.lane_start_yaw_rad = yaw;
  }
  VehicleOnLane v = seen;
  if (config.lane_change_target) {
    const std::string target = LaneChangeTarget(seen, network, counter_lanes->LeftHand());
    if (!target.empty()) {
      const LaneInfo& lane = network->Lane(target);
      v.lane = target;
      v.lane_index = lane.index;
      v.lane_position_m = std::fmin(seen.lane_position_m, lane.length_m);
    }
  }
  LaneCorridor c;
  c.centre = network->Lane(v.lane).shape;
  c.position_m = v.lane_position_m - 0.5 * v.length_m;
  c.width_m = network->Lane(v.lane).width_m;
  c.speed_mps = v.speed_mps;
  const double reach = ReachAhead(v.speed_mps, config);
  std::string beyond_junction;  // the first normal lane after an internal one
  FollowRoute(v, reach, network, &c, &beyond_junction, &out.route_end_m);
  out.lane_yaw_rate_radps =
      LaneYawRate(c, v.speed_mps, std::fmax(1.0, 0.5 * v.speed_mps * step_s));
  out.smooth_lane_yaw_rate_radps =
      LaneYawRate(c, v.speed_mps, std::fmax(kCornerWindowM, 0.5 * v.speed_mps * step_s));
  if (config.lane_heading_yaw_rate && step_s <= kLongStepS) {
    const double window = std::fmax(1.0, kLaneHeadingWindowS * v.speed_mps);
    const WayLine way = LineThrough(*network, v.lane, v.lane_position_m,
                                    v.length_m + window + 1.0, v.route, v.route_index, c.centre);
    out.lane_heading = HeadingAlong(way, v.length_m, v.speed_mps, window, window);
  }
  if (config.junction_ways && BodyInJunction(*network, v.lane, v.lane_position_m, v.way_length_m,
                                             v.route, v.route_index))
    out.way = WayOf(*network, v.lane, v.lane_position_m, v.way_length_m, v.route, v.route_index,
                    c.centre, v.centre);
  const std::string reference = IsInternal(v.lane) ? beyond_junction : v.lane;
  if (!reference.empty()) Neighbours(v, reference, network, counter_lanes, &c);
  out.lanes = SampleLaneSet(c, reach, v.centre, config.lane_sampling);
  return out;
}

}  // namespace criticality::plugin
