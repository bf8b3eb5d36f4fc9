#include "plugin/scenes/carriages.h"

#include <algorithm>
#include <cmath>

#include "plugin/network/polyline.h"

namespace criticality::plugin {
namespace {

constexpr double kMinBoxM = 0.5;

// Appends `shape` before `line`, dropping a repeated joint point.
void Prepend(const std::vector<Point2>& shape, std::vector<Point2>* line) {
  std::vector<Point2> joined = shape;
  for (const Point2& p : *line) {
    if (joined.empty() || std::hypot(p.x - joined.back().x, p.y - joined.back().y) > 1e-3)
      joined.push_back(p);
  }
  line->swap(joined);
}

// The lane before `lane` on the vehicle's way and the internal lane between them ("" when
// none); "" when it cannot be found (the route starts here).
std::string PreviousLane(const std::string& lane, const std::vector<std::string>& route,
                         int* route_index, RoadNetwork* network, std::string* via) {
  via->clear();
  std::string edge;
  if (IsInternal(lane)) {
    if (*route_index < 0 || *route_index >= static_cast<int>(route.size())) return "";
    edge = route[*route_index];  // on a junction the route index is the edge before it
  } else {
    if (*route_index <= 0 || *route_index > static_cast<int>(route.size())) return "";
    edge = route[--*route_index];
  }
  for (int k = 0; k < network->LaneCount(edge); ++k) {
    const std::string candidate = edge + "_" + std::to_string(k);
    for (const LaneLink& link : network->Links(candidate)) {
      if (IsInternal(lane) ? link.internal == lane : link.lane == lane) {
        if (!IsInternal(lane)) *via = link.internal;
        return candidate;
      }
    }
  }
  return "";
}

}  // namespace

BodyPlan PlanBody(double length_m, double /*width_m*/, const VehicleTypeReport& type) {
  BodyPlan plan;
  const bool given = type.carriage_length_m || type.locomotive_length_m;
  if (!given && length_m <= kMaxBoxLengthM) {
    plan.head_length_m = length_m;
    return plan;
  }
  double carriage = kMaxBoxLengthM;
  if (given) {
    carriage = type.carriage_length_m.value_or(type.locomotive_length_m.value_or(kMaxBoxLengthM));
    plan.gap_m = type.carriage_gap_m.value_or(kDefaultCarriageGapM);
  } else {
    // Equal carriages: n boxes and n - 1 gaps make the length.
    const int n = static_cast<int>(std::ceil((length_m + plan.gap_m) / (kMaxBoxLengthM + plan.gap_m)));
    carriage = (length_m - (n - 1) * plan.gap_m) / n;
  }
  plan.head_length_m = std::min(length_m, type.locomotive_length_m.value_or(carriage));
  double left = length_m - plan.head_length_m;
  if (left > kMaxCarriages * (carriage + plan.gap_m)) {
    carriage = left / kMaxCarriages - plan.gap_m;  // fewer, longer carriages
  }
  while (left - plan.gap_m >= kMinBoxM) {
    const double box = std::min(carriage, left - plan.gap_m);
    plan.carriage_lengths_m.push_back(box);
    left -= plan.gap_m + box;
  }
  return plan;
}

std::vector<Carriage> PlaceCarriages(const BodyPlan& plan, const VehicleOnLane& v, double width_m,
                                     const SceneConfig& config, double step_s,
                                     RoadNetwork* network) {
  std::vector<Carriage> out;
  if (plan.carriage_lengths_m.empty()) return out;
  double body = plan.head_length_m;
  for (double l : plan.carriage_lengths_m) body += plan.gap_m + l;
  // The centre line from far enough behind the front to the front and on along the route.
  LaneCorridor c;
  c.centre = network->Lane(v.lane).shape;
  c.width_m = network->Lane(v.lane).width_m;
  double front = v.lane_position_m;  // arc length of the front along c.centre
  std::string lane = v.lane;
  int route_index = v.route_index;
  for (int hop = 0; hop < 64 && front < body; ++hop) {
    std::string via;
    const std::string previous = PreviousLane(lane, v.route, &route_index, network, &via);
    if (previous.empty()) break;
    for (const std::string& l : {via, previous}) {
      if (l.empty()) continue;
      Prepend(network->Lane(l).shape, &c.centre);
      front += PolylineLength(network->Lane(l).shape);
    }
    lane = previous;
  }
  c.position_m = front - 0.5 * v.length_m;
  std::string beyond;
  std::optional<double> route_end;
  const double reach = ReachAhead(v.speed_mps, config);
  FollowRoute(v, reach, network, &c, &beyond, &route_end);
  // Each carriage's centre, its heading there, its lane ahead of it.
  double s = front - plan.head_length_m;
  for (double length : plan.carriage_lengths_m) {
    s -= plan.gap_m + 0.5 * length;
    double heading = 0.0;
    const Point2 p = PointAlong(c.centre, s, &heading);
    Carriage k;
    k.x_m = p.x;
    k.y_m = p.y;
    k.yaw_rad = heading;
    k.length_m = length;
    k.width_m = width_m;
    LaneCorridor own = c;
    own.position_m = s;
    k.yaw_rate_radps =
        LaneYawRate(own, v.speed_mps, std::fmax(1.0, 0.5 * v.speed_mps * step_s));
    const LaneSet lanes = SampleLaneSet(own, reach, Pose2{p.x, p.y, heading}, config.lane_sampling);
    if (lanes.own) k.lanes = lanes;
    out.push_back(std::move(k));
    s -= 0.5 * length;
  }
  return out;
}

}  // namespace criticality::plugin
