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

/** Samples the corridor at s = position, position + reach/2, position + reach and returns the
 *  lanes in the vehicle's local frame X_WV. Returns an empty LaneSet (the estimator then uses a
 *  virtual lane) when the corridor has fewer than 2 points or its samples do not run forward
 *  in the vehicle's frame (e.g. the vehicle stands across its lane). */
LaneSet SampleLaneSet(const LaneCorridor& corridor, double reach_m, const core::Pose2& X_WV);

}  // namespace criticality::plugin
