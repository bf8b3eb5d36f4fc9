#include "plugin/scenes/lane_corridor.h"

#include <cmath>

#include "criticality/estimator.h"

namespace criticality::plugin {

LaneSampling LaneSamplingFor(const Params& params) {
  LaneSampling s;
  s.turn_lane_frame = params.turn_lane_frame && params.road_model;
  s.turn_lane_frame_min_rad = params.turn_lane_frame_min_rad;
  s.straight_before_turn = params.straight_before_turn && params.road_model;
  s.centre_within_lane = params.lane_fit_within_lane && params.road_model;
  return s;
}

double SampledReach(const LaneCorridor& c, double reach_m, double yaw, bool turn_lane_frame) {
  constexpr double kStep = 0.5;  // m
  double final_heading = 0.0;
  PointAlong(c.centre, c.position_m + reach_m, &final_heading);
  const bool to_turn_end =
      turn_lane_frame && std::fabs(WrapAngle(final_heading - yaw)) > kPaperFrameMaxTurnRad;
  const double max_turn = turn_lane_frame ? kTurnFrameMaxTurnRad : kPaperFrameMaxTurnRad;
  for (double d = kStep; d < reach_m; d += kStep) {
    double heading = 0.0;
    PointAlong(c.centre, c.position_m + d, &heading);
    if (std::fabs(WrapAngle(heading - yaw)) > max_turn) {
      return std::fmax(d - kStep, kMinSampledReachM);
    }
    if (to_turn_end && std::fabs(WrapAngle(heading - final_heading)) < kTurnEndToleranceRad)
      return std::fmin(std::fmax(d, kMinSampledReachM), reach_m);
  }
  return reach_m;
}

double LaneYawRate(const LaneCorridor& c, double speed, double window_m) {
  if (c.centre.size() < 2 || !(window_m > 0.0)) return 0.0;
  double behind = 0.0, ahead = 0.0;
  PointAlong(c.centre, c.position_m - window_m, &behind);
  PointAlong(c.centre, c.position_m + window_m, &ahead);
  return speed * WrapAngle(ahead - behind) / (2.0 * window_m);
}

double StraightBeforeTurn(const LaneCorridor& c, double reach_m) {
  constexpr double kStep = 0.5;  // m
  double start_heading = 0.0, end_heading = 0.0;
  PointAlong(c.centre, c.position_m, &start_heading);
  PointAlong(c.centre, c.position_m + reach_m, &end_heading);
  if (std::fabs(WrapAngle(end_heading - start_heading)) < kStraightThenTurnMinRad) return 0.0;
  double straight = 0.0;
  for (double d = kStep; d <= reach_m; d += kStep) {
    double heading = 0.0;
    PointAlong(c.centre, c.position_m + d, &heading);
    if (std::fabs(WrapAngle(heading - start_heading)) > kStraightToleranceRad) break;
    straight = d;
  }
  return straight >= kMinStraightM && straight <= reach_m - kMinTurnM ? straight : 0.0;
}

namespace {

// The lanes sampled over exactly `reach_m` (see SampleLaneSet); nullopt when the own lane's
// samples cannot be fitted in the frame the estimator will fit them in. *within_lane: false
// when LaneSampling::centre_within_lane finds the own lane's fitted centre out of the lane.
std::optional<LaneSet> SampleOver(const LaneCorridor& c, double reach_m, const Pose2& X_WV,
                                  const LaneSampling& sampling, bool* within_lane) {
  *within_lane = true;
  const double straight = sampling.straight_before_turn ? StraightBeforeTurn(c, reach_m) : 0.0;
  const double middle = straight > 0.0 ? straight : 0.5 * reach_m;
  const double s[3] = {c.position_m, c.position_m + middle, c.position_m + reach_m};
  // Each divider is the centre line shifted left by `offset` (negative: right).
  auto divider = [&](double offset) {
    LaneDivider d;
    for (int i = 0; i < 3; ++i) {
      double heading = 0.0;
      const Point2 p = PointAlong(c.centre, s[i], &heading);
      const double wx = p.x - std::sin(heading) * offset, wy = p.y + std::cos(heading) * offset;
      WorldToLocal(X_WV, wx, wy, &d.points[i].x, &d.points[i].y);
    }
    return d;
  };
  const double half = 0.5 * c.width_m;
  LaneSet set;
  set.own = Lane{divider(half), divider(-half), false};
  if (c.left)
    set.left = Lane{divider(half + c.left->width_m), divider(half), c.left->counter_traffic};
  if (c.right)
    set.right = Lane{divider(-half), divider(-half - c.right->width_m), c.right->counter_traffic};
  for (std::optional<Lane>* lane : {&set.own, &set.left, &set.right}) {
    if (*lane) (*lane)->straight_to_middle = straight > 0.0;
  }
  // The estimator needs every lane's samples to run forward in the vehicle's frame with the
  // left divider left of the right one. Offsetting a tight turn's centre line can break that
  // (the dividers cross), and a parabola y(x) cannot end across the heading: such a neighbour
  // is left out; such an own lane makes the whole set unusable at this reach.
  // Checked in the frame the estimator will fit them in (turned along a junction turn's chord).
  Params frame_params;
  frame_params.turn_lane_frame = sampling.turn_lane_frame;
  frame_params.turn_lane_frame_min_rad = sampling.turn_lane_frame_min_rad;
  const double frame = LaneFrameAngle(set, frame_params);
  const double cf = std::cos(frame), sf = std::sin(frame);
  auto usable = [&](const std::optional<Lane>& lane) {
    auto xr = [&](const Point2& p) { return cf * p.x + sf * p.y; };
    auto yr = [&](const Point2& p) { return -sf * p.x + cf * p.y; };
    for (const LaneDivider* d : {&lane->left, &lane->right}) {
      if (!(xr(d->points[1]) > xr(d->points[0]) + 0.5 &&
            xr(d->points[2]) > xr(d->points[1]) + 0.5)) {
        return false;
      }
    }
    for (int i = 0; i < 3; ++i) {
      if (!(yr(lane->left.points[i]) > yr(lane->right.points[i]) + 0.1)) return false;
    }
    // The estimator's own test (fit, width at the observer).
    return LaneProblem(*lane, frame).empty();
  };
  if (!usable(set.own)) return std::nullopt;
  // The parabola through three samples can leave the lane between them (a short straight and
  // a sharp turn: it swings out to the other side first); then the lane is fitted over a
  // shorter reach, which follows the road where the vehicle is.
  if (sampling.centre_within_lane) {
    std::vector<Point2> centre;
    for (double d = 0.0; d <= reach_m; d += 1.0) {
      double heading = 0.0;
      const Point2 p = PointAlong(c.centre, c.position_m + d, &heading);
      Point2 local;
      WorldToLocal(X_WV, p.x, p.y, &local.x, &local.y);
      centre.push_back(local);
    }
    *within_lane = LaneCentreDeviation(*set.own, frame, centre) <= 0.5 * c.width_m;
  }
  if (set.left && !usable(set.left)) set.left.reset();
  if (set.right && !usable(set.right)) set.right.reset();
  return set;
}

}  // namespace

LaneSet SampleLaneSet(const LaneCorridor& c, double reach_m, const Pose2& X_WV,
                      const LaneSampling& sampling) {
  if (c.centre.size() < 2 || !(reach_m > 0.0)) return LaneSet{};
  // As far as LaneSampling says; where the own lane cannot be fitted that far (a junction turn
  // ending across the heading whose chord the estimator does not turn its frame for), as far
  // as the paper's frame can follow the turn, then shorter: a lane that follows the road part
  // of the way is better than none (without lanes a vehicle is predicted straight on, through
  // the junction it is turning in).
  // The same where the fitted centre leaves the lane (LaneSampling::centre_within_lane); if no
  // reach keeps it within, the first that can be fitted.
  std::optional<LaneSet> fallback;
  auto sample = [&](double reach) -> std::optional<LaneSet> {
    bool within_lane = true;
    std::optional<LaneSet> set = SampleOver(c, reach, X_WV, sampling, &within_lane);
    if (set && !within_lane) {
      if (!fallback) fallback = set;
      return std::nullopt;
    }
    return set;
  };
  const double first = SampledReach(c, reach_m, X_WV.yaw, sampling.turn_lane_frame);
  if (const auto set = sample(first)) return *set;
  double reach = SampledReach(c, reach_m, X_WV.yaw, false);
  if (reach >= first) reach = 0.5 * first;
  for (; reach >= kMinSampledReachM; reach *= 0.5) {
    if (const auto set = sample(reach)) return *set;
  }
  return fallback ? *fallback : LaneSet{};
}

}  // namespace criticality::plugin
