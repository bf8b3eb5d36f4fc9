#include "plugin/scenes/lane_corridor.h"

#include <cmath>

#include "criticality/errors.h"
#include "criticality/estimator.h"

namespace criticality::plugin {

LaneSampling LaneSamplingFor(const Params& params) {
  LaneSampling s;
  s.turn_lane_frame = params.turn_lane_frame && params.road_model;
  s.turn_lane_frame_min_rad = params.turn_lane_frame_min_rad;
  s.straight_before_turn = params.straight_before_turn && params.road_model;
  s.straight_by_fit = params.straight_before_turn_by_fit && s.straight_before_turn;
  s.centre_within_lane = params.lane_fit_within_lane && params.road_model;
  s.corners = params.lane_corners && params.road_model;
  s.corner_in_turn = params.lane_corner_in_turn && params.road_model;
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

namespace {

constexpr double kHeadingStep = 0.5;  // m, where headings along a line are read

// How far from s0 (up to max_m, in kHeadingStep steps) the line keeps within
// kStraightToleranceRad of `heading`; step < 0 reads backwards from s0.
double StraightFrom(const std::vector<Point2>& line, double s0, double heading, double max_m,
                    double step = kHeadingStep) {
  double straight = 0.0;
  for (double d = kHeadingStep; d <= max_m; d += kHeadingStep) {
    double h = 0.0;
    PointAlong(line, s0 + (step < 0.0 ? -d : d), &h);
    if (std::fabs(WrapAngle(h - heading)) > kStraightToleranceRad) break;
    straight = d;
  }
  return straight;
}

// How far the centre line runs straight from the vehicle where it turns by at least
// kStraightThenTurnMinRad within the reach and leaves kMinTurnM of it to the turn; 0 elsewhere.
double StraightIntoTurn(const LaneCorridor& c, double reach_m) {
  double start_heading = 0.0, end_heading = 0.0;
  PointAlong(c.centre, c.position_m, &start_heading);
  PointAlong(c.centre, c.position_m + reach_m, &end_heading);
  if (std::fabs(WrapAngle(end_heading - start_heading)) < kStraightThenTurnMinRad) return 0.0;
  const double straight = StraightFrom(c.centre, c.position_m, start_heading, reach_m);
  return straight <= reach_m - kMinTurnM ? straight : 0.0;
}

}  // namespace

double StraightBeforeTurn(const LaneCorridor& c, double reach_m) {
  const double straight = StraightIntoTurn(c, reach_m);
  return straight >= kMinStraightM ? straight : 0.0;
}

std::vector<Point2> CentreLineAhead(const LaneCorridor& c, const Pose2& X_WV, double reach_m) {
  std::vector<Point2> centre;
  for (double d = 0.0; d <= reach_m; d += 1.0) {
    double heading = 0.0;
    const Point2 p = PointAlong(c.centre, c.position_m + d, &heading);
    Point2 local;
    WorldToLocal(X_WV, p.x, p.y, &local.x, &local.y);
    centre.push_back(local);
  }
  return centre;
}

namespace {

// How far along heading h0 from a the straight through a with heading h0 meets the straight
// through b with heading h2 (*out: how far along h2 from there to b): a + in u0 = b - out u2.
double MeetingDistance(const Point2& a, double h0, const Point2& b, double h2,
                       double* out = nullptr) {
  const double u0x = std::cos(h0), u0y = std::sin(h0), u2x = std::cos(h2), u2y = std::sin(h2);
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double det = u0x * u2y - u0y * u2x;
  if (out) *out = (u0x * dy - u0y * dx) / det;
  return (dx * u2y - dy * u2x) / det;
}

}  // namespace

std::optional<Corner> CornerOf(const std::vector<Point2>& centre, double s0, double s2,
                               double min_straight_m) {
  constexpr double kMaxCornerTurnRad = 2.9670597283903604;  // 170 degrees
  if (centre.size() < 2 || !(s2 > s0)) return std::nullopt;
  double h0 = 0.0, h2 = 0.0;
  const Point2 p0 = PointAlong(centre, s0, &h0), p2 = PointAlong(centre, s2, &h2);
  const double turn = WrapAngle(h2 - h0);
  if (std::fabs(turn) < kStraightThenTurnMinRad || std::fabs(turn) > kMaxCornerTurnRad)
    return std::nullopt;
  double out = 0.0;
  const double in = MeetingDistance(p0, h0, p2, h2, &out);
  if (!(in > kHeadingStep) || !(out > kHeadingStep)) return std::nullopt;
  // Where the line leaves the first straight's heading and takes the second's.
  const double inside = std::nextafter(s2 - s0, 0.0);  // strictly between s0 and s2
  const double begin = s0 + StraightFrom(centre, s0, h0, inside);
  const double end = s2 - StraightFrom(centre, s2, h2, inside, -kHeadingStep);
  // A vehicle already in the turn keeps the parabola through the turn: the corner is for a
  // straight road that leads into it.
  if (begin - s0 < min_straight_m) return std::nullopt;
  Corner c;
  c.corner = Point2{p0.x + in * std::cos(h0), p0.y + in * std::sin(h0)};
  c.in_m = in;
  c.out_m = out;
  const double tangent = 0.5 * ((in - (begin - s0)) + (out - (s2 - end)));
  c.tangent_m = std::fmin(std::fmax(tangent, 1.0), std::fmin(in, out));
  return c;
}

namespace {

// The lanes sampled over exactly `reach_m` (see SampleLaneSet); nullopt when the own lane's
// samples cannot be fitted in the frame the estimator will fit them in. *within_lane: false
// when LaneSampling::centre_within_lane finds the own lane's fitted centre out of the lane.
// `straight` > 0: the middle samples at that distance (a straight of that length, as
// StraightBeforeTurn's) instead of StraightBeforeTurn's choice. *deviation (where given): the
// own lane's fitted centre's LaneCentreDeviation where the check above measured it, else NaN.
// `turn_corner`: sampled as a corner (CornerOf) also where the vehicle is already in the turn
// (LaneSampling::corner_in_turn); nullopt where the centre line makes no corner.
std::optional<LaneSet> SampleOver(const LaneCorridor& c, double reach_m, const Pose2& X_WV,
                                  const LaneSampling& sampling, bool* within_lane,
                                  double straight_m = 0.0, double* deviation = nullptr,
                                  bool turn_corner = false) {
  *within_lane = true;
  if (deviation) *deviation = std::nan("");
  const std::optional<Corner> corner =
      turn_corner        ? CornerOf(c.centre, c.position_m, c.position_m + reach_m, 0.0)
      : sampling.corners ? CornerOf(c.centre, c.position_m, c.position_m + reach_m)
                         : std::nullopt;
  if (turn_corner && !corner) return std::nullopt;
  const double straight = straight_m > 0.0 ? straight_m
                          : sampling.straight_before_turn && !corner
                              ? StraightBeforeTurn(c, reach_m)
                              : 0.0;
  const double middle = straight > 0.0 ? straight : 0.5 * reach_m;
  const double s[3] = {c.position_m, c.position_m + middle, c.position_m + reach_m};
  // Each divider is the centre line shifted left by `offset` (negative: right); a corner's
  // middle point is where its shifted straights meet.
  auto divider = [&](double offset) {
    LaneDivider d;
    Point2 world[3];
    double heading[3];
    for (int i = 0; i < 3; ++i) {
      const Point2 p = PointAlong(c.centre, s[i], &heading[i]);
      world[i] = Point2{p.x - std::sin(heading[i]) * offset, p.y + std::cos(heading[i]) * offset};
    }
    if (corner) {
      const double in = MeetingDistance(world[0], heading[0], world[2], heading[2]);
      world[1] =
          Point2{world[0].x + in * std::cos(heading[0]), world[0].y + in * std::sin(heading[0])};
    }
    for (int i = 0; i < 3; ++i)
      WorldToLocal(X_WV, world[i].x, world[i].y, &d.points[i].x, &d.points[i].y);
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
    if (!*lane) continue;
    (*lane)->straight_to_middle = straight > 0.0;
    if (corner) (*lane)->corner_tangent_m = corner->tangent_m;
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
  const std::vector<Point2> centre = sampling.centre_within_lane || corner
                                         ? CentreLineAhead(c, X_WV, reach_m)
                                         : std::vector<Point2>{};
  // A corner turns over the tangent length whose fit keeps closest to the road (the
  // estimator's own fit, LaneCentreDeviation): CornerOf's estimate or one of 12 from 1 m to the
  // longer straight (a turn that begins before the vehicle or ends beyond the reach may fit the
  // road best).
  if (corner) {
    constexpr int kTangents = 12;
    const double longest = std::fmax(corner->in_m, corner->out_m);
    Lane probe = *set.own;
    double best = HUGE_VAL, best_tangent = corner->tangent_m;
    for (int k = 0; k <= kTangents; ++k) {  // CornerOf's estimate, then the grid
      probe.corner_tangent_m =
          k == 0 ? corner->tangent_m : 1.0 + (longest - 1.0) * (k - 1) / (kTangents - 1);
      if (!(probe.corner_tangent_m > 0.0)) continue;
      double deviation = HUGE_VAL;
      try {  // one fit: LaneCentreDeviation throws where LaneProblem would name a problem
        deviation = LaneCentreDeviation(probe, frame, centre);
      } catch (const InputError&) {
        continue;
      }
      if (deviation < best) {
        best = deviation;
        best_tangent = probe.corner_tangent_m;
      }
    }
    for (std::optional<Lane>* lane : {&set.own, &set.left, &set.right}) {
      if (*lane) (*lane)->corner_tangent_m = best_tangent;
    }
  }
  // The parabola through three samples can leave the lane between them (a short straight and
  // a sharp turn: it swings out to the other side first); then the lane is fitted over a
  // shorter reach, which follows the road where the vehicle is.
  if (sampling.centre_within_lane) {
    const double d = LaneCentreDeviation(*set.own, frame, centre);
    *within_lane = d <= 0.5 * c.width_m;
    if (deviation) *deviation = d;
  }
  if (set.left && !usable(set.left)) set.left.reset();
  if (set.right && !usable(set.right)) set.right.reset();
  return set;
}

// LaneSampling::straight_by_fit: the straight ahead where it is too short for
// StraightBeforeTurn (kMinChosenStraightM to kMinStraightM, and kSteerLeadS of travel) and leads
// into a turn within the reach; 0 where none.
double ShortStraightBeforeTurn(const LaneCorridor& c, double reach_m) {
  const double straight = StraightIntoTurn(c, reach_m);
  const double least = std::fmax(kMinChosenStraightM, kSteerLeadS * c.speed_mps);
  return straight >= least && straight < kMinStraightM ? straight : 0.0;
}

// The own lane's fitted centre's largest distance from `centre` (LaneCentreDeviation, in the
// frame the estimator fits the set in); HUGE_VAL where it cannot be fitted.
double OwnCentreDeviation(const LaneSet& set, const LaneSampling& sampling,
                          const std::vector<Point2>& centre) {
  Params frame_params;
  frame_params.turn_lane_frame = sampling.turn_lane_frame;
  frame_params.turn_lane_frame_min_rad = sampling.turn_lane_frame_min_rad;
  try {
    return LaneCentreDeviation(*set.own, LaneFrameAngle(set, frame_params), centre);
  } catch (const InputError&) {
    return HUGE_VAL;
  }
}

// LaneSampling::straight_by_fit over `reach_m`: *set (and *within_lane) become the set sampled
// with the middle samples at a short straight's end where that set is usable and either *set
// is not (none, or out of its lane) or that set's own centre keeps closer to the road.
// `deviation`: *set's, as SampleOver measured it (NaN: not measured).
void ChooseStraightByFit(const LaneCorridor& c, double reach_m, const Pose2& X_WV,
                         const LaneSampling& sampling, double deviation,
                         std::optional<LaneSet>* set, bool* within_lane) {
  const double straight = ShortStraightBeforeTurn(c, reach_m);
  if (straight <= 0.0) return;
  bool alt_within = true;
  double alt_deviation = std::nan("");
  std::optional<LaneSet> alt =
      SampleOver(c, reach_m, X_WV, sampling, &alt_within, straight, &alt_deviation);
  if (!alt) return;
  if (!*set || !*within_lane) {
    *set = std::move(alt);
    *within_lane = alt_within;
    return;
  }
  if (!alt_within) return;
  if (std::isnan(deviation) || std::isnan(alt_deviation)) {  // the lane-fit check is off
    const std::vector<Point2> centre = CentreLineAhead(c, X_WV, reach_m);
    deviation = OwnCentreDeviation(**set, sampling, centre);
    alt_deviation = OwnCentreDeviation(*alt, sampling, centre);
  }
  if (alt_deviation < deviation) *set = std::move(alt);
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
    double deviation = std::nan("");
    std::optional<LaneSet> set =
        SampleOver(c, reach, X_WV, sampling, &within_lane, 0.0, &deviation);
    const bool long_straight = set && set->own && set->own->straight_to_middle;
    if (sampling.straight_by_fit && !sampling.corners && !long_straight)
      ChooseStraightByFit(c, reach, X_WV, sampling, deviation, &set, &within_lane);
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
  // No parabola through the turn fits (a tight junction turn whose inner divider, offset from
  // its centre line, folds back): the turn as a corner, from where the vehicle is.
  if (sampling.corner_in_turn && !sampling.corners) {
    bool within_lane = true;
    if (auto set = SampleOver(c, first, X_WV, sampling, &within_lane, 0.0, nullptr, true);
        set && within_lane)
      return *set;
  }
  return fallback ? *fallback : LaneSet{};
}

}  // namespace criticality::plugin
