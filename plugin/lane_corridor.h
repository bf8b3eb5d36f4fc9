#pragma once
// Scene extraction's geometry, independent of SUMO: a vehicle's lane corridor (the centre line
// of its lane from behind it to beyond where it can reach in the horizon, continued into the
// next lanes of its route, plus the widths of its lane and its neighbours) becomes the
// estimator's LaneSet: each divider sampled at its closest, middle and farthest point within
// the reach, in the vehicle's local frame. Neighbours on the same road are adjacent and
// parallel, so their dividers are the own lane's edges shifted by their widths.
#include <optional>
#include <vector>

#include "core/geometry.h"
#include "criticality/scene.h"

namespace criticality::plugin {

struct NeighbourLane {
  double width_m{3.2};
  bool counter_traffic{false};
};

struct LaneCorridor {
  std::vector<Point2> centre;  ///< the own lane's centre line, in driving direction (world)
  double position_m{0.0};      ///< arc length along `centre` of the vehicle's centre of gravity
  double width_m{3.2};
  std::optional<NeighbourLane> left;
  std::optional<NeighbourLane> right;
};

/** Polyline length. */
double PolylineLength(const std::vector<Point2>& line);

/** The point at arc length s (extrapolated along the end segments beyond the ends) and the
 *  direction of travel there (math yaw). */
Point2 PointAlong(const std::vector<Point2>& line, double s, double* heading);

/** The paper's lane model is a parabola y(x) in the vehicle's frame, fitted to three samples:
 *  it cannot follow a road that turns across the vehicle's heading. Fitted through a sample
 *  beyond a junction's 90 degree turn, it bent the other way first and swept through the cars
 *  waiting beside the turn (one-step false alarms of p ~ 1 in the city run). The samples stop
 *  where the centre line has turned more than this from the vehicle's heading: the parabola
 *  then follows the turn as far as it goes, and curves on with it beyond. */
constexpr double kMaxSampledTurnRad = 1.0471975511965976;  // 60 degrees
/** ... but never closer than this (a vehicle standing across its lane keeps a usable reach). */
constexpr double kMinSampledReachM = 5.0;

/** The reach the samples use: `reach_m`, or less where the centre line ahead of position turns
 *  more than kMaxSampledTurnRad away from `yaw` (at least kMinSampledReachM). */
double SampledReach(const LaneCorridor& corridor, double reach_m, double yaw);

/** Samples the corridor at s = position, position + reach/2, position + reach (reach as
 *  SampledReach shortens it) and returns the
 *  lanes in the vehicle's local frame X_WV. Returns an empty LaneSet (the estimator then uses a
 *  virtual lane) when the corridor has fewer than 2 points or its samples do not run forward
 *  in the vehicle's frame (e.g. the vehicle stands across its lane). */
LaneSet SampleLaneSet(const LaneCorridor& corridor, double reach_m, const core::Pose2& X_WV);

}  // namespace criticality::plugin
