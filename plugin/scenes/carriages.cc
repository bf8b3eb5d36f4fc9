#include "plugin/scenes/carriages.h"

#include <algorithm>
#include <cmath>

#include "plugin/network/polyline.h"
#include "plugin/network/way_behind.h"

namespace criticality::plugin {
namespace {

constexpr double kMinBoxM = 0.5;

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

bool IsBent(double length_m, double box_length_m) {
  return length_m - box_length_m >= kBentBodyToleranceM;
}

BodyPlan PlanBentBody(double length_m) {
  BodyPlan plan;
  plan.gap_m = 0.0;
  const int n = std::max(2, static_cast<int>(std::ceil(length_m / kBentBoxLengthM)));
  const double box = length_m / n;
  plan.head_length_m = box;
  plan.carriage_lengths_m.assign(n - 1, box);
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
  const WayLine way = LineBehind(*network, v.lane, v.lane_position_m, body, v.route, v.route_index);
  c.centre = way.line;
  c.width_m = network->Lane(v.lane).width_m;
  const double front = way.front_m;  // arc length of the front along c.centre
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
