#include "src/street_data.h"

#include <array>
#include <cmath>
#include <sstream>

#include "criticality/errors.h"

namespace criticality::internal {
namespace {

constexpr double kMinPointSpacing = 0.01;  // m, along x in the local frame
constexpr double kMaxLaneFrameRad = 1.3089969389957472;  // 75 degrees: the chord of a 150 degree turn

// x of a divider's middle point in the frame turned by frame_rad.
double MiddleX(const LaneDivider& d, double frame_rad) {
  return std::cos(frame_rad) * d.points[1].x + std::sin(frame_rad) * d.points[1].y;
}

// Where a corner lane's (Lane::corner_tangent_m) turn begins and ends along x in the frame
// turned by frame_rad: tangent_m before the divider's corner along its first straight and after
// it along its second.
void CornerSpan(const LaneDivider& d, double frame_rad, double tangent_m, double* x_start,
                double* x_end) {
  const double c = std::cos(frame_rad), s = std::sin(frame_rad);
  double x[3], y[3];
  for (int i = 0; i < 3; ++i) {
    x[i] = c * d.points[i].x + s * d.points[i].y;
    y[i] = -s * d.points[i].x + c * d.points[i].y;
  }
  const double l1 = std::hypot(x[1] - x[0], y[1] - y[0]);
  const double l2 = std::hypot(x[2] - x[1], y[2] - y[1]);
  *x_start = x[1] - (l1 > 0.0 ? tangent_m * (x[1] - x[0]) / l1 : 0.0);
  *x_end = x[1] + (l2 > 0.0 ? tangent_m * (x[2] - x[1]) / l2 : 0.0);
}

// straight_until: NaN for the paper's parabola, else the x (fit frame) where the straight road
// before a turn ends (FitStraightThenParabola). corner_start < corner_end: a corner lane's turn
// (FitCorner); NaN otherwise.
core::Parabola FitDivider(const LaneDivider& d, const std::string& where, double frame_rad,
                          bool straight_beyond, double straight_until,
                          double corner_start = std::nan(""), double corner_end = std::nan("")) {
  double x[3], y[3];
  const double c = std::cos(frame_rad), s = std::sin(frame_rad);
  for (int i = 0; i < 3; ++i) {
    x[i] = d.points[i].x;
    y[i] = d.points[i].y;
    if (!std::isfinite(x[i]) || !std::isfinite(y[i])) {
      std::ostringstream msg;
      msg << where << ".points[" << i << "] = (" << x[i] << ", " << y[i]
          << "): coordinates must be finite";
      throw InputError(msg.str());
    }
    if (frame_rad != 0.0) {  // into the lane's turn frame
      const double xr = c * x[i] + s * y[i], yr = -s * x[i] + c * y[i];
      x[i] = xr;
      y[i] = yr;
    }
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = i + 1; j < 3; ++j) {
      if (std::fabs(x[i] - x[j]) < kMinPointSpacing) {
        std::ostringstream msg;
        msg << where << ": points " << i << " and " << j << " have forward distances x = " << x[i]
            << " and " << x[j] << " m; the three points need distinct x (at least "
            << kMinPointSpacing << " m apart) in the observer's frame";
        if (frame_rad != 0.0) msg << " turned by " << frame_rad * 180.0 / core::kPi << " deg";
        throw InputError(msg.str());
      }
    }
  }
  core::Parabola p;
  if (!std::isnan(corner_start)) {
    if (!core::FitCorner(x, y, corner_start, corner_end, &p)) {
      std::ostringstream msg;
      msg << where << ": a corner needs increasing forward distances and a turn of positive "
          << "length, got x = " << x[0] << ", " << x[1] << ", " << x[2] << " m, turn from "
          << corner_start << " to " << corner_end << " m";
      throw InputError(msg.str());
    }
    if (frame_rad != 0.0) p.SetFrame(frame_rad);
    return p;  // straight beyond its turn already
  }
  if (!std::isnan(straight_until)) {
    if (!core::FitStraightThenParabola(x, y, straight_until, &p)) {
      std::ostringstream msg;
      msg << where << ": straight to the middle point needs increasing forward distances, got x = "
          << x[0] << ", " << x[1] << ", " << x[2] << " m";
      throw InputError(msg.str());
    }
  } else if (!core::FitParabola(x, y, &p)) {
    throw InputError(where + ": the three points do not define a lane divider y(x)");
  }
  if (frame_rad != 0.0) p.SetFrame(frame_rad);
  if (straight_beyond) p.x_end = std::fmax(x[0], std::fmax(x[1], x[2]));
  return p;
}

std::optional<FittedLane> FitLane(const std::optional<Lane>& lane, const std::string& where,
                                  double frame_rad, bool straight_beyond,
                                  bool straight_to_middle) {
  if (!lane) return std::nullopt;
  FittedLane f;
  // Both dividers turn from the same x (the mean of their middle points').
  const double straight_until =
      straight_to_middle && lane->straight_to_middle
          ? 0.5 * (MiddleX(lane->left, frame_rad) + MiddleX(lane->right, frame_rad))
          : std::nan("");
  // A corner lane's dividers turn over the same span of x (the means of theirs).
  double corner_start = std::nan(""), corner_end = std::nan("");
  if (lane->corner_tangent_m > 0.0) {
    double s_left, e_left, s_right, e_right;
    CornerSpan(lane->left, frame_rad, lane->corner_tangent_m, &s_left, &e_left);
    CornerSpan(lane->right, frame_rad, lane->corner_tangent_m, &s_right, &e_right);
    corner_start = 0.5 * (s_left + s_right);
    corner_end = 0.5 * (e_left + e_right);
  }
  f.left = FitDivider(lane->left, where + ".left", frame_rad, straight_beyond, straight_until,
                      corner_start, corner_end);
  f.right = FitDivider(lane->right, where + ".right", frame_rad, straight_beyond, straight_until,
                       corner_start, corner_end);
  f.counter_traffic = lane->counter_traffic;
  // Both dividers continue straight from the same distance along the turn frame.
  f.left.x_end = f.right.x_end = 0.5 * (f.left.x_end + f.right.x_end);
  const double width = f.left.Eval(0.0) - f.right.Eval(0.0);
  if (!(width > 0.0)) {
    std::ostringstream msg;
    msg << where << ": width at the observer = " << width
        << " m; the left divider must lie left of (greater y than) the right divider";
    throw InputError(msg.str());
  }
  return f;
}

LaneDivider DividerFrom(const core::Parabola& p, const std::array<double, 3>& xs) {
  LaneDivider d;
  for (int i = 0; i < 3; ++i) d.points[i] = Point2{xs[i], p.Eval(xs[i])};
  return d;
}

bool Contains(const FittedLane& lane, double x, double y) {
  return lane.right.OffsetFrom(x, y) <= 0.0 && lane.left.OffsetFrom(x, y) >= 0.0;
}

LaneDivider ToFrame(const LaneDivider& d, const core::Pose2& X_EV) {
  LaneDivider out;
  for (int i = 0; i < 3; ++i) {
    core::WorldToLocal(X_EV, d.points[i].x, d.points[i].y, &out.points[i].x, &out.points[i].y);
  }
  return out;
}

// A lane re-expressed in another frame; nullopt when it is not a function y(x) there.
std::optional<Lane> LaneInFrame(const Lane& lane, const core::Pose2& X_EV, bool reversed,
                                bool counter) {
  Lane out;
  out.left = ToFrame(reversed ? lane.right : lane.left, X_EV);
  out.right = ToFrame(reversed ? lane.left : lane.right, X_EV);
  out.counter_traffic = counter;
  out.straight_to_middle = lane.straight_to_middle;
  out.corner_tangent_m = lane.corner_tangent_m;
  try {
    const FittedLanes probe =
        FitLanes(LaneSet{out, std::nullopt, std::nullopt}, "lane", 0.0, false, true);
    (void)probe;
  } catch (const InputError&) {
    return std::nullopt;
  }
  return out;
}

}  // namespace

Lane VirtualLane(const ObjectState& state, double width) {
  double curvature = state.speed_mps > 0.5 ? state.yaw_rate_radps / state.speed_mps : 0.0;
  curvature = std::fmax(-0.2, std::fmin(0.2, curvature));
  const std::array<double, 3> xs{0.0, 25.0, 50.0};
  Lane lane;
  lane.left = DividerFrom(core::Parabola{0.5 * curvature, 0.0, 0.5 * width}, xs);
  lane.right = DividerFrom(core::Parabola{0.5 * curvature, 0.0, -0.5 * width}, xs);
  return lane;
}

LaneSet VirtualLaneSet(const ObjectState& state, double width) {
  LaneSet set;
  set.own = VirtualLane(state, width);
  auto shifted = [&](const Lane& lane, double dy) {
    Lane out = lane;
    for (LaneDivider* d : {&out.left, &out.right}) {
      for (Point2& p : d->points) p.y += dy;
    }
    return out;
  };
  set.left = shifted(*set.own, width);
  set.right = shifted(*set.own, -width);
  return set;
}

double LaneFrameAngle(const LaneSet& lanes, const Params& params) {
  if (!params.turn_lane_frame || !lanes.own) return 0.0;
  const Lane& own = *lanes.own;
  const double x0 = 0.5 * (own.left.points[0].x + own.right.points[0].x);
  const double y0 = 0.5 * (own.left.points[0].y + own.right.points[0].y);
  const double x2 = 0.5 * (own.left.points[2].x + own.right.points[2].x);
  const double y2 = 0.5 * (own.left.points[2].y + own.right.points[2].y);
  double chord = std::atan2(y2 - y0, x2 - x0);
  if (own.corner_tangent_m > 0.0) {
    // A corner: the frame across its bisector, in which both straights have slopes of the
    // same size (a turn of 90 degrees: +-1), so that the parabola between them is symmetric.
    const double x1 = 0.5 * (own.left.points[1].x + own.right.points[1].x);
    const double y1 = 0.5 * (own.left.points[1].y + own.right.points[1].y);
    const double in = std::atan2(y1 - y0, x1 - x0), out = std::atan2(y2 - y1, x2 - x1);
    chord = in + 0.5 * std::remainder(out - in, 2.0 * core::kPi);
  }
  if (!std::isfinite(chord) || std::fabs(chord) < params.turn_lane_frame_min_rad) return 0.0;
  // A chord further off than this does not belong to a lane the observer drives along (a lane
  // sampled against its direction of travel, or a U-turn): the paper's frame, which rejects it.
  if (std::fabs(chord) > kMaxLaneFrameRad) return 0.0;
  return chord;
}

FittedLanes FitLanes(const LaneSet& lanes, const std::string& where, double frame_rad,
                     bool straight_beyond, bool straight_to_middle) {
  FittedLanes f;
  f.own = FitLane(lanes.own, where + ".own", frame_rad, straight_beyond, straight_to_middle);
  f.left = FitLane(lanes.left, where + ".left", frame_rad, straight_beyond, straight_to_middle);
  f.right = FitLane(lanes.right, where + ".right", frame_rad, straight_beyond, straight_to_middle);
  return f;
}

FittedLanes FitLanes(const LaneSet& lanes, const std::string& where, const Params& params) {
  return FitLanes(lanes, where, LaneFrameAngle(lanes, params), params.turn_lane_frame,
                  params.straight_before_turn);
}

LaneSet CompleteEgoLanes(const Ego& ego, const Params& params) {
  LaneSet lanes = ego.lanes;
  if (!lanes.own) lanes.own = VirtualLane(ego.state, params.virtual_lane_width_m);
  return lanes;
}

LaneIndex AssociateLane(const FittedLanes& ego_lanes, double x_E, double y_E) {
  if (ego_lanes.own && Contains(*ego_lanes.own, x_E, y_E)) return LaneIndex::kOwn;
  if (ego_lanes.left && Contains(*ego_lanes.left, x_E, y_E)) return LaneIndex::kLeft;
  if (ego_lanes.right && Contains(*ego_lanes.right, x_E, y_E)) return LaneIndex::kRight;
  return LaneIndex::kNone;
}

LaneSet EgoLanesSeenBy(const LaneSet& ego_lanes, const core::Pose2& X_EV, LaneIndex own) {
  LaneSet out;
  auto lane_at = [&](int index) -> const std::optional<Lane>& {
    static const std::optional<Lane> kNoLane;
    if (index == -1) return ego_lanes.right;
    if (index == 0) return ego_lanes.own;
    if (index == 1) return ego_lanes.left;
    return kNoLane;
  };
  const int m = static_cast<int>(own);
  const std::optional<Lane>& own_lane = lane_at(m);
  if (own == LaneIndex::kNone || !own_lane) return out;
  // Driving against the ego's direction: the ego's left is this vehicle's right.
  const bool reversed = std::cos(X_EV.yaw) < 0.0;
  const bool own_counter = own_lane->counter_traffic;
  out.own = LaneInFrame(*own_lane, X_EV, reversed, false);
  if (!out.own) return LaneSet{};
  for (int side : {-1, 1}) {
    const std::optional<Lane>& lane = lane_at(m + side);
    if (!lane) continue;
    auto seen = LaneInFrame(*lane, X_EV, reversed, lane->counter_traffic != own_counter);
    const bool is_left = (side == 1) != reversed;
    (is_left ? out.left : out.right) = seen;
  }
  return out;
}

}  // namespace criticality::internal
