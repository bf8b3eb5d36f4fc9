#pragma once
// Street data processing (paper Sec. IV-A), host side: lane sets -> fitted dividers in an
// object's local frame, the virtual own lane, association of vehicles to the ego's lanes, and
// the ego's lanes re-expressed in another vehicle's frame.
#include <optional>
#include <string>

#include "core/geometry.h"
#include "core/lane_fit.h"
#include "criticality/params.h"
#include "criticality/scene.h"

namespace criticality::internal {

/** A lane with both dividers fitted, in the local frame of the object that sees it. */
struct FittedLane {
  core::Parabola left;
  core::Parabola right;
  bool counter_traffic{false};
  /** Lateral position at fraction f across the lane (0 = right divider, 1 = left divider). */
  core::Parabola At(double f) const { return core::Blend(right, left, f); }
  core::Parabola Centre() const { return At(0.5); }
};

struct FittedLanes {
  std::optional<FittedLane> own;
  std::optional<FittedLane> left;
  std::optional<FittedLane> right;
};

/** Which of the ego's lanes an object is associated with. */
enum class LaneIndex : int { kRight = -1, kOwn = 0, kLeft = 1, kNone = 2 };

/** Three divider points of a lane whose own lane is missing: a virtual lane of `width` centred
 *  on the object, curving with its current path curvature yaw_rate / v (paper Sec. IV-A, RAA
 *  lane width). */
Lane VirtualLane(const ObjectState& state, double width);

/** The "no road model" ablation (Params::road_model false): a virtual own lane with a virtual
 *  lane of the same width on each side, no counter traffic. */
LaneSet VirtualLaneSet(const ObjectState& state, double width);

/** The frame an observer's lanes are fitted in, as an angle in its local frame: 0 (the
 *  paper's: x along the observer's heading), or, with Params::turn_lane_frame, the direction of
 *  its own lane's centre from the closest to the farthest sample (the chord) when that differs
 *  from its heading by at least Params::turn_lane_frame_min_rad (and at most 75 degrees: a
 *  chord further off, e.g. of a lane sampled against the observer's direction of travel, keeps
 *  the paper's frame, which rejects it): a lane through a junction turn is then a function
 *  y(x) along its chord, which the local frame cannot give it. */
double LaneFrameAngle(const LaneSet& lanes, const Params& params);

/** Fits every divider in the frame turned by frame_rad from the observer's (LaneFrameAngle),
 *  with straight_beyond each lane continuing straight along its tangent beyond its farthest
 *  sample (instead of the parabola curving on), with straight_to_middle a lane marked
 *  Lane::straight_to_middle fitted straight up to its middle sample; throws InputError naming
 *  `where` (e.g. "scene.ego.lanes.left") when a divider's points do not define y(x) there or
 *  the lane has no positive width at the observer. */
FittedLanes FitLanes(const LaneSet& lanes, const std::string& where, double frame_rad = 0.0,
                     bool straight_beyond = false, bool straight_to_middle = false);

/** The same in the frame and with the continuation and the straight road the parameters ask
 *  for (Params::turn_lane_frame, Params::straight_before_turn). */
FittedLanes FitLanes(const LaneSet& lanes, const std::string& where, const Params& params);

/** The ego's lanes, with a virtual own lane when the scene gives none. */
LaneSet CompleteEgoLanes(const Ego& ego, const Params& params);

/** Associates a point given in the ego's frame with the ego lane that contains it. */
LaneIndex AssociateLane(const FittedLanes& ego_lanes, double x_E, double y_E);

/** The ego's lanes (points in the ego frame) seen from another vehicle with pose X_EV in the
 *  ego frame, which was associated with lane `own`. Its own lane is that lane, its neighbours
 *  the ego lanes next to it (left and right swap when it drives against the ego), the
 *  counter-traffic flags are relative to it. Returns no own lane when the lane cannot be
 *  expressed as y(x) in its frame (e.g. a crossing vehicle). */
LaneSet EgoLanesSeenBy(const LaneSet& ego_lanes, const core::Pose2& X_EV, LaneIndex own);

}  // namespace criticality::internal
