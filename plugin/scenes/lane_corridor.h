#pragma once
// Scene extraction's geometry, independent of SUMO: a vehicle's lane corridor (the centre line
// of its lane from behind it to beyond where it can reach in the horizon, continued into the
// next lanes of its route, plus the widths of its lane and its neighbours) becomes the
// estimator's LaneSet: each divider sampled at its closest, middle and farthest point within
// the reach, in the vehicle's local frame. Neighbours on the same road are adjacent and
// parallel, so their dividers are the own lane's edges shifted by their widths.
#include <optional>
#include <vector>

#include "criticality/geometry.h"
#include "criticality/params.h"
#include "criticality/scene.h"
#include "plugin/network/polyline.h"

namespace criticality::plugin {

struct NeighbourLane {
  double width_m{3.2};
  bool counter_traffic{false};
};

struct LaneCorridor {
  std::vector<Point2> centre;  ///< the own lane's centre line, in driving direction (world)
  /** The vehicle's speed along it (LaneSampling::straight_by_fit: how soon it reaches a turn). */
  double speed_mps{0.0};
  double position_m{0.0};      ///< arc length along `centre` of the vehicle's centre of gravity
  double width_m{3.2};
  std::optional<NeighbourLane> left;
  std::optional<NeighbourLane> right;
};

/** How far into a turn the samples go: the paper's parabola y(x) in the vehicle's frame cannot
 *  follow a road that turns across the heading. Fitted through a sample beyond a junction's
 *  90 degree turn it bent the other way first and swept through the cars waiting beside the
 *  turn, so in the paper's frame the samples stop where the centre line has turned
 *  kPaperFrameMaxTurnRad from the vehicle's heading, and the parabola curves on beyond. In the
 *  estimator's turn frame (Params::turn_lane_frame: a lane fitted along its chord, continuing
 *  straight beyond its last sample) a turn of more than kPaperFrameMaxTurnRad ahead is sampled
 *  to its end instead (where the heading comes within kTurnEndToleranceRad of the heading at
 *  the full reach), so that the lane leaves the turn along the road that follows. */
struct LaneSampling {
  bool turn_lane_frame{true};
  /** The estimator's Params::turn_lane_frame_min_rad, so that the samples are checked in the
   *  frame it will fit them in. */
  double turn_lane_frame_min_rad{0.35};
  /** Params::straight_before_turn: where the centre line runs straight (within
   *  kStraightToleranceRad of its heading at the vehicle) for at least kMinStraightM and then
   *  turns by at least kStraightThenTurnMinRad within the reach, the middle samples go where
   *  the straight ends and every lane is marked Lane::straight_to_middle. */
  bool straight_before_turn{true};
  /** Params::straight_before_turn_by_fit: where a straight shorter than kMinStraightM (at least
   *  kMinChosenStraightM and kSteerLeadS of the vehicle's travel) leads into a turn, the set
   *  sampled as straight_before_turn does for long straights replaces the plain one where its
   *  own lane's fitted centre keeps closer to the corridor's centre line (LaneCentreDeviation),
   *  or where the plain one cannot be used. */
  bool straight_by_fit{true};
  /** Params::lane_fit_within_lane: a set whose own lane's fitted centre line lies farther than
   *  half the lane's width from the corridor's centre line (LaneCentreDeviation, checked every
   *  metre of the sampled reach) is not used at that reach (SampleLaneSet tries shorter). */
  bool centre_within_lane{true};
  /** Params::lane_corners: a centre line that turns by at least kStraightThenTurnMinRad
   *  between the first and the last sample is sampled as a corner (CornerOf), with the
   *  tangent length (CornerOf's own estimate or one of 12 from 1 m to the longer straight)
   *  whose fit keeps closest to it. */
  bool corners{false};
  /** Params::lane_corner_in_turn: where no reach gives an own lane that can be fitted within
   *  the lane (SampleLaneSet would send none, and the estimator would predict the vehicle on a
   *  virtual lane out of its turn), the lanes are sampled as a corner (CornerOf) from where
   *  the vehicle is, also when it is already in the turn; kept only where the corner's fitted
   *  centre stays within the lane. */
  bool corner_in_turn{false};
};
constexpr double kStraightToleranceRad = 0.05235987755982989;   // 3 degrees
constexpr double kStraightThenTurnMinRad = 0.2617993877991494;  // 15 degrees
/** A straight of 15 m or more: shorter straights lead into junction turns that the vehicle
 *  may already be steering into, where the parabola through three points of the whole turn
 *  follows it better (in the city run, 5 m straights fitted this way took turning cars wide). */
constexpr double kMinStraightM = 15.0;
/** ... and the turn keeps at least this much of the reach beyond the straight. */
constexpr double kMinTurnM = 5.0;
/** LaneSampling::straight_by_fit: straights from this long, and from this much of the
 *  vehicle's travel (the time to steer into a turn at the controller's 0.9 rad/s: a 10 m
 *  radius asks about 0.27 rad for a car), are sampled both ways and the closer fit is kept. */
constexpr double kMinChosenStraightM = 2.0;
constexpr double kSteerLeadS = 0.5;
constexpr double kPaperFrameMaxTurnRad = 1.0471975511965976;  // 60 degrees
constexpr double kTurnEndToleranceRad = 0.05235987755982989;  // 3 degrees
/** In the turn frame, the samples still stop where the centre line has turned this far
 *  (beyond it, e.g. in a U-turn, no chord makes the lane a function y(x)). */
constexpr double kTurnFrameMaxTurnRad = 2.0943951023931957;  // 120 degrees
/** ... but never closer than this (a vehicle standing across its lane keeps a usable reach). */
constexpr double kMinSampledReachM = 5.0;

/** The corridor's centre line every metre of the reach (from its position), in the frame of
 *  the vehicle at X_WV: what the lane-fit check and a corner's fit are measured against. */
std::vector<Point2> CentreLineAhead(const LaneCorridor& c, const Pose2& X_WV, double reach_m);

/** A turn of the centre line between arc lengths s0 and s2, as Lane::corner_tangent_m sends
 *  it: the corner where the straights along the line's direction at s0 and at s2 meet, how
 *  far along them (from the corner) the turn begins and ends, the straights' lengths. */
struct Corner {
  Point2 corner;
  double tangent_m{0.0};
  double in_m{0.0};   ///< from the point at s0 to the corner
  double out_m{0.0};  ///< from the corner to the point at s2
};

/** A corner needs the road to run straight (within kStraightToleranceRad) for this far ahead
 *  of the vehicle: one already in the turn keeps the parabola through the turn. */
constexpr double kMinCornerStraightM = 2.0;

/** The corner of the centre line between s0 and s2, when it runs straight from s0 for at least
 *  min_straight_m, turns by at least kStraightThenTurnMinRad (and less than 170 degrees)
 *  by s2, and both straights run forward to their meeting point. The turn's tangent length
 *  is the mean of the lengths, from the corner, at which the line leaves the first straight's
 *  heading and takes the second's (within kStraightToleranceRad; 0.5 m steps), at least 1 m
 *  and at most the shorter straight. */
std::optional<Corner> CornerOf(const std::vector<Point2>& centre, double s0, double s2,
                               double min_straight_m = kMinCornerStraightM);

/** The sampling for the estimator's parameters. */
LaneSampling LaneSamplingFor(const Params& params);

/** The reach the samples use: `reach_m`, or less where the centre line ahead of position turns
 *  away from `yaw`, as LaneSampling says (at least kMinSampledReachM). */
double SampledReach(const LaneCorridor& corridor, double reach_m, double yaw,
                    bool turn_lane_frame = false);

/** The yaw rate of a vehicle that follows the corridor's centre line at `speed`, as SUMO's
 *  vehicles follow their lanes: speed x the heading change from window_m behind its position
 *  to window_m ahead, over 2 window_m (0 on a straight, speed / radius in a turn; before the
 *  corridor's start the first segment's heading counts). */
double LaneYawRate(const LaneCorridor& corridor, double speed, double window_m);

/** Where the corridor's centre line stops running straight: the distance ahead of position
 *  at which it has turned more than kStraightToleranceRad from its heading at position, when
 *  that is at least kMinStraightM and at most reach - kMinTurnM and the line has turned at
 *  least kStraightThenTurnMinRad by the reach; otherwise 0 (no straight road before a turn). */
double StraightBeforeTurn(const LaneCorridor& corridor, double reach_m);

/** Samples the corridor at s = position, position + reach/2, position + reach (reach as
 *  SampledReach shortens it; the middle where StraightBeforeTurn says the straight ends, as
 *  LaneSampling::straight_before_turn asks) and returns the lanes in the vehicle's local frame
 *  X_WV. Where the own lane's samples cannot be fitted that far (they do not run forward along
 *  the frame the estimator fits them in: a junction turn ending across the heading whose chord
 *  turns less than turn_lane_frame_min_rad), the reach is shortened: to where the paper's frame
 *  stops (kPaperFrameMaxTurnRad), then halved, down to kMinSampledReachM. Returns an empty
 *  LaneSet (the estimator then uses a virtual lane) when the corridor has fewer than 2 points
 *  or no reach gives a usable own lane (e.g. the vehicle stands across its lane). */
LaneSet SampleLaneSet(const LaneCorridor& corridor, double reach_m, const Pose2& X_WV,
                      const LaneSampling& sampling = LaneSampling{});

}  // namespace criticality::plugin
