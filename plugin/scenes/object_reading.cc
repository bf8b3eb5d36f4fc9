#include "plugin/scenes/object_reading.h"

#include <algorithm>
#include <cmath>

#include "plugin/network/polyline.h"
#include "plugin/network/way_behind.h"
#include "plugin/scenes/carriages.h"
#include "plugin/scenes/footway.h"
#include "plugin/scenes/junction_way.h"
#include "plugin/scenes/road_users.h"
#include "plugin/scenes/stop_lines.h"
#include "plugin/sumo/sumo_conventions.h"

namespace criticality::plugin {
namespace {

// SUMO's stop state bits (getStopState).
constexpr int kStopped = 1;
constexpr int kParking = 2;
// SUMO's signal bits (getSignals).
constexpr int kBlinkerRight = 1;
constexpr int kBlinkerLeft = 2;

Blinker BlinkerOf(int signals) {
  const bool left = (signals & kBlinkerLeft) != 0, right = (signals & kBlinkerRight) != 0;
  if (left == right) return Blinker::kNone;  // off, or both (hazard lights)
  return left ? Blinker::kLeft : Blinker::kRight;
}

// SUMO's speed, never negative (NaN passed on).
double Speed(double v) { return std::isnan(v) ? v : std::max(0.0, v); }

bool Finite(const ObjectState& s) {
  return std::isfinite(s.x_m) && std::isfinite(s.y_m) && std::isfinite(s.yaw_rad) &&
         std::isfinite(s.speed_mps);
}

// The distance from the front to the point `metres` behind it along `way`: the chord of the
// way a body of that length lies along; `metres` where the way is not known that far.
double ChordOf(const WayLine& way, double metres) {
  const std::optional<Point2> back = PointOnWay(way, metres);
  const std::optional<Point2> front = PointOnWay(way, 0.0);
  if (!back || !front) return metres;
  return std::hypot(front->x - back->x, front->y - back->y);
}

// The centre pose of a body's first box, `length_m` long, with boxes behind it: along its own
// part of `way` (SUMO's angle points along the whole body), its front SUMO's front bumper;
// along SUMO's angle where the way is not known that far.
Pose2 HeadPose(const SumoObject& o, const WayLine& way, double length_m) {
  const std::optional<double> chord = ChordYaw(way, length_m);
  if (!chord) return FrontBumperToCentre(o.x_m, o.y_m, o.angle_deg, length_m);
  const double yaw = *chord;
  return Pose2{o.x_m - 0.5 * length_m * std::cos(yaw), o.y_m - 0.5 * length_m * std::sin(yaw), yaw};
}

// A lane change since the lanes behind: one of them moved sideways onto the next by more than
// netconvert's joints are apart (millimetres; lanes are 2 m apart or more).
constexpr double kLaneChangeShiftM = 0.5;

// The heading of a body `length_m` long along `way` (from its back to its front) where the way
// was moved sideways by a lane change (WayLine::shifted_m); nullopt otherwise, or where the way
// is not known that far back.
std::optional<double> ChangedLanesHeading(const WayLine& way, double length_m) {
  if (!(way.shifted_m > kLaneChangeShiftM)) return std::nullopt;
  return ChordYaw(way, length_m);
}

// A class can be seen, a vType's limits cannot: the class's own (estimator/ALGORITHM.md).
VehicleType SeenType(const VehicleType& type) {
  VehicleType seen;
  seen.road_user = type.road_user;
  return seen;
}

// Where the vehicle is on its lanes, as scene extraction's geometry reads it: its centre `c`
// and box length (the snapshot's), SUMO's lane position, route, class, blinker and length.
VehicleOnLane OnLane(const SumoObject& o, const Pose2& c, double speed_mps, double box_length_m,
                     const SceneConfig& config) {
  VehicleOnLane v;
  v.centre = c;
  v.front = Point2{o.x_m, o.y_m};
  v.speed_mps = speed_mps;
  v.length_m = box_length_m;
  v.lane = o.lane;
  v.lane_position_m = o.lane_position_m;
  v.lane_index = o.lane_index;
  v.route = o.route;
  v.route_index = o.route_index;
  v.vehicle_class = o.vehicle_class;
  v.observable_only = config.observable_only;
  v.blinker = BlinkerOf(o.signals);
  v.junction_shapes = config.junction_shapes;
  v.way_length_m = o.length_m;
  return v;
}

}  // namespace

ObjectReader::ObjectReader(const SceneConfig& config, double step_s, RoadNetwork* network,
                           TrafficView* traffic)
    : config_(config), step_s_(step_s), network_(network), traffic_(traffic),
      counter_lanes_(network), crossing_entries_(network) {}

std::vector<ObjectSnapshot> ObjectReader::Read(const std::vector<SumoObject>& objects,
                                               double sumo_time_s) {
  RememberAccels(objects, sumo_time_s);  // first: a leader's is read with its follower
  std::vector<ObjectSnapshot> out;
  out.reserve(objects.size());
  for (const SumoObject& o : objects) out.push_back(o.person ? Person(o) : Vehicle(o, sumo_time_s));
  return out;
}

void ObjectReader::RememberAccels(const std::vector<SumoObject>& objects, double sumo_time_s) {
  if (!(config_.accel_window_s > 0.0)) return;
  // A read belongs to the window while it is less than the window old: at 0.1 s steps and a
  // 0.4 s window, the reads of now and the 3 steps before (the speed change over 0.4 s).
  const double oldest = sumo_time_s - config_.accel_window_s + 1e-6;
  for (const SumoObject& o : objects) {
    if (o.person) continue;
    std::deque<AccelRead>& reads = accel_reads_[o.id];
    if (!reads.empty() && (sumo_time_s <= reads.back().time_s ||
                           sumo_time_s - reads.back().time_s > 1.5 * step_s_))
      reads.clear();  // not read at the step before (out of every ego's range, or the same step)
    reads.push_back(AccelRead{sumo_time_s, o.accel_mps2});
    while (reads.front().time_s < oldest) reads.pop_front();
  }
}

double ObjectReader::WindowAccel(const std::string& id, double sumo_accel,
                                 double sumo_time_s) const {
  if (!(config_.accel_window_s > 0.0)) return sumo_accel;  // off: no lookup per read
  const auto it = accel_reads_.find(id);
  if (it == accel_reads_.end() || it->second.empty() || it->second.back().time_s != sumo_time_s)
    return sumo_accel;
  double sum = 0.0;
  for (const AccelRead& r : it->second) sum += r.accel_mps2;
  return sum / static_cast<double>(it->second.size());
}

ObjectSnapshot ObjectReader::Person(const SumoObject& o) {
  ObjectSnapshot s;
  s.id = o.id;
  s.person = true;
  s.vehicle_class = "pedestrian";
  s.state.x_m = o.x_m;
  s.state.y_m = o.y_m;
  s.state.yaw_rad = NavigationDegToYaw(o.angle_deg);
  s.state.speed_mps = Speed(o.speed_mps);
  const Pedestrian footprint;  // the estimator's pedestrian (scene.h)
  s.length_m = footprint.length_m;
  s.width_m = footprint.width_m;
  s.lane = o.lane;
  if (s.lane.empty()) return s;
  s.edge = network_->Lane(s.lane).edge;
  const WalkingPlace here = WalkingPlaceOf(s.edge, PedestriansOnly(*network_, s.lane));
  if (config_.observable_only) {
    // Where it walks can be seen, where it will walk next cannot: on a sidewalk it keeps to it;
    // at a junction's corner (a walking area) it may be about to cross.
    s.stays_on_footway = here == WalkingPlace::kSidewalk;
    return s;
  }
  // The next edge's lane 0: a sidewalk, walking area or crossing when it has one. A walk that
  // ends on this edge goes on along it.
  const WalkingPlace next = o.next_edge.empty()
                                ? WalkingPlace::kSidewalk
                                : WalkingPlaceOf(o.next_edge,
                                                 PedestriansOnly(*network_, o.next_edge + "_0"));
  s.stays_on_footway = StaysOnFootway(here, next);
  // About to cross where it may not yet: it waits on the footway
  // (SceneConfig::crossing_obligations).
  if (!s.stays_on_footway && config_.crossing_obligations && here == WalkingPlace::kWalkingArea &&
      next == WalkingPlace::kCrossing) {
    const std::string crossing = o.next_edge + "_0";
    const std::optional<LaneLink> entry = crossing_entries_.EntryLink(s.lane, o.next_edge);
    s.stays_on_footway = entry && MustWaitAt(*entry);
    // It stops where the crossing begins, as SUMO's persons do: its reference hypothesis
    // decelerates to that point (SceneConfig::crossing_stops).
    if (s.stays_on_footway && config_.crossing_stops) {
      const double stop = CrossingStopDecel(
          s.state.speed_mps, DistanceToCrossing(network_->Lane(crossing), o.x_m, o.y_m));
      if (stop < 0.0) s.state.expected_accel_mps2 = stop;  // none for a person standing
    }
  }
  return s;
}

ObjectSnapshot ObjectReader::Vehicle(const SumoObject& o, double sumo_time_s) {
  ObjectSnapshot s;
  s.id = o.id;
  s.vehicle_class = o.vehicle_class;
  s.vehicle_type = o.vehicle_type;
  const std::optional<RoadUser> road_user = RoadUserOf(o.vehicle_class);
  s.not_a_road_user = !road_user;
  const VehicleTypeReport& type = traffic_->TypeOf(o.vehicle_type);
  s.type = TypeFrom(type, road_user.value_or(RoadUser::kCar));
  if (config_.observable_only) s.type = SeenType(s.type);
  s.stopped = (o.stop_state & kStopped) != 0;
  s.parked = (o.stop_state & kParking) != 0;
  // A long body: its first box is the vehicle, the rest carriages behind it (carriages.h).
  // With --bent-bodies so is a body bent by a turn (its way behind shorter from front to back
  // than the vehicle, vehicle_bodies.h): each of its boxes keeps to the lanes it stands on.
  BodyPlan body{o.length_m, {}, 0.0};
  WayLine way;
  bool bent = false;
  if (!o.lane.empty()) {
    body = PlanBody(o.length_m, o.width_m, type);
    // The way behind only where it is used (every vehicle, every step): a margin, since the
    // way is gathered by SUMO's lane lengths and measured along the shapes.
    if (config_.bent_bodies)
      way = LineBehind(*network_, o.lane, o.lane_position_m, 1.2 * o.length_m + 1.0, o.route,
                       o.route_index);
    bent = config_.bent_bodies && body.carriage_lengths_m.empty() &&
           IsBent(o.length_m, ChordOf(way, o.length_m));
    if (bent) body = PlanBentBody(o.length_m);
  }
  // One box is SUMO's box of the body (front to back, BodyLengthOf; shorter in a bend):
  // SceneConfig::sumo_box, always with --bent-bodies and --bodies-on-path.
  const bool one_box = body.carriage_lengths_m.empty();
  s.length_m = one_box && (config_.bent_bodies || config_.bodies_on_path || config_.sumo_box)
                   ? BodyLengthOf(o)
                   : body.head_length_m;
  s.width_m = o.width_m;
  if (o.height_m > 0.0) s.height_m = o.height_m;
  // Just past a junction, after a lane change within one step: the heading of the way its new
  // lane came by (SceneConfig::way_heading), not SUMO's angle from the back left on the old lane.
  double angle_deg = o.angle_deg;
  if (config_.way_heading && config_.instant_lane_changes && !o.lane.empty() && !s.parked &&
      o.lane_position_m < o.length_m && ChangedLanesSinceTheJunction(o)) {
    if (!config_.bent_bodies)
      way = LineBehind(*network_, o.lane, o.lane_position_m, o.length_m + 1.0, o.route,
                       o.route_index);
    if (const std::optional<double> yaw = ChangedLanesHeading(way, o.length_m))
      angle_deg = YawToNavigationDeg(*yaw);
  }
  // In a junction (SceneConfig::junction_chord_heading): the chord of its lanes from its back to
  // its front, as SUMO places the body; not held (it turns as the lanes do).
  std::optional<double> chord;
  if (config_.junction_chord_heading && !o.lane.empty() && !s.parked &&
      BodyInJunction(*network_, o.lane, o.lane_position_m, o.length_m, o.route, o.route_index)) {
    chord = ChordYaw(LineBehind(*network_, o.lane, o.lane_position_m, o.length_m + 1.0, o.route,
                                o.route_index),
                     o.length_m);
    if (chord) angle_deg = YawToNavigationDeg(*chord);
  }
  bool held = false;
  const double heading = chord ? *chord : HeadingOf(o, angle_deg, sumo_time_s, &held);
  const Pose2 c =
      one_box || !config_.bent_bodies
          ? FrontBumperToCentre(o.x_m, o.y_m, held ? YawToNavigationDeg(heading) : angle_deg,
                                s.length_m)
          : HeadPose(o, way, s.length_m);
  s.state.x_m = c.x;
  s.state.y_m = c.y;
  s.state.yaw_rad = c.yaw;
  s.state.speed_mps = Speed(o.speed_mps);
  s.state.accel_mps2 = WindowAccel(o.id, o.accel_mps2, sumo_time_s);
  s.normal_decel_mps2 = o.decel_mps2;
  // Yaw rate from the heading change since the previous step; 0 when the vehicle was not read
  // at the previous step. With long steps it is replaced below by its lane's. SUMO's angle (the
  // whole body's; held where it jumped, HeadingOf), so that a body whose first box changes
  // between one box and a chain's does not turn by that change.
  auto it = last_yaw_.find(o.id);
  const bool recent = it != last_yaw_.end() && sumo_time_s > it->second.time_s &&
                      sumo_time_s - it->second.time_s < 1.5 * step_s_;
  if (recent) {
    s.state.yaw_rate_radps =
        WrapAngle(heading - it->second.yaw_rad) / (sumo_time_s - it->second.time_s);
  }
  LastHeading& last = last_yaw_[o.id];
  last.time_s = sumo_time_s;
  last.yaw_rad = heading;
  // Within grip (Plausible below refines it to the lane's where it reads the lanes).
  const double r_max = GripYawRate(s.state.speed_mps);
  last.yaw_rate_radps = std::clamp(s.state.yaw_rate_radps, -r_max, r_max);
  if (!held) last.taken_s = sumo_time_s;
  last.in_junction = IsInternal(o.lane);
  if (held) ++conditioned_;  // Plausible below does not count this read again
  s.lane = o.lane;
  // SUMO takes a vehicle parked with parking="true" (or in a parking area) off its lane: it
  // reports no lane for it (libsumo 1.15), and it stands beside the road.
  if (s.parked) s.off_road = s.lane.empty() || OffItsLane(o);
  if (s.lane.empty()) return s;
  s.edge = network_->Lane(s.lane).edge;
  s.leader = LeaderOf(o.id, s.state.speed_mps, sumo_time_s);  // for ExpectCarFollowing
  // SUMO's leader is looked for along the route: seen, only the one ahead in its own lane.
  if (config_.observable_only && s.leader &&
      s.leader->gap_m > network_->Lane(o.lane).length_m - o.lane_position_m)
    s.leader.reset();
  if (!Finite(s.state)) return s;
  const VehicleOnLane v = OnLane(o, c, s.state.speed_mps, s.length_m, config_);
  const ObjectLanes lanes = LanesOf(v, config_, step_s_, network_, &counter_lanes_);
  s.lanes = lanes.lanes;
  s.way = lanes.way;
  s.state.route_end_m = lanes.route_end_m;
  s.state.yaw_rate_radps = LaneYawRateOr(s.state.yaw_rate_radps, lanes, heading, held);
  s.stop_line = StopLineOf(v, o.id, config_, network_, traffic_);
  // Its leader and its stop line are read: the reasons to brake this scene knows
  // (Params::release_unexplained_braking), unless it may be yielding ahead.
  if (config_.braking_causes) s.state.braking_causes_known = !MayYieldAhead(v, config_, network_);
  s.carriages = PlaceCarriages(body, v, o.width_m, config_, step_s_, network_);
  Plausible(lanes.smooth_lane_yaw_rate_radps, held, &s);
  last.yaw_rate_radps = s.state.yaw_rate_radps;
  return s;
}

double ObjectReader::HeadingOf(const SumoObject& o, double angle_deg, double sumo_time_s,
                               bool* held) const {
  // SUMO moves a vehicle along its lanes and turns it to their direction: at the corners of a
  // junction's internal lane its heading can jump by tens of degrees for a step or two and
  // back (35 degrees at 12 m/s for 0.4 s on a netgenerate rand net), a turn no vehicle
  // drives. The same after a lane change within one step (SUMO's default, lanechange.duration
  // 0): the front is in the new lane, SUMO's angle points from the back, still in the old one,
  // to it (32 degrees for 3.2 m over a 5 m car) until the back follows, two steps later.
  // Predicted from that heading the vehicle leaves its lane across the road. A change beyond
  // the grip-limited yaw rate (v r <= mu g, as Plausible) is held there: the previous heading,
  // on at the previous yaw rate. After kMaxHeadingHoldS SUMO's heading is taken whatever it is
  // (with steps longer than that, never held). Where SUMO moves lane-changing vehicles over time
  // (lanechange.duration > 0, the sublane model), a sudden heading change on a normal lane is
  // the start of a lane change (SUMO turns the vehicle by atan(lateral speed / speed) at once)
  // and is taken as it is; only the junctions' corners are held.
  const double angle = NavigationDegToYaw(angle_deg);
  *held = false;
  if (!config_.heading_hold) return angle;
  auto it = last_yaw_.find(o.id);
  if (it == last_yaw_.end()) return angle;
  const LastHeading& last = it->second;
  const double dt = sumo_time_s - last.time_s;
  if (!(dt > 0.0) || dt >= 1.5 * step_s_) return angle;
  if (sumo_time_s - last.taken_s > kMaxHeadingHoldS + 1e-9) return angle;
  if (!config_.instant_lane_changes && !last.in_junction && !IsInternal(o.lane)) return angle;
  const double r_max = GripYawRate(Speed(o.speed_mps));
  // Beyond grip both from the previous heading and from where it was turning to.
  if (!(std::fabs(WrapAngle(angle - last.yaw_rad)) > r_max * dt)) return angle;
  const double on = WrapAngle(last.yaw_rad + last.yaw_rate_radps * dt);
  if (!(std::fabs(WrapAngle(angle - on)) > r_max * dt)) return angle;
  *held = true;
  return on;
}

bool ObjectReader::ChangedLanesSinceTheJunction(const SumoObject& o) {
  if (IsInternal(o.lane) || o.route_index < 1 || o.route_index >= static_cast<int>(o.route.size()))
    return false;
  const std::string& before = o.route[o.route_index - 1];
  const std::string key = before + '\n' + o.lane;
  auto it = reached_from_.find(key);
  if (it == reached_from_.end()) {
    bool reached = false;
    for (int k = 0; k < network_->LaneCount(before) && !reached; ++k)
      for (const LaneLink& link : network_->Links(before + "_" + std::to_string(k)))
        reached = reached || link.lane == o.lane;
    it = reached_from_.emplace(key, reached).first;
  }
  return !it->second;
}

double ObjectReader::LaneYawRateOr(double measured, const ObjectLanes& lanes, double heading,
                                   bool held) const {
  if (step_s_ > kLongStepS) return lanes.lane_yaw_rate_radps;
  // SceneConfig::lane_heading_yaw_rate: SUMO's heading along its lanes, where it is that.
  if (lanes.lane_heading && !held &&
      std::fabs(WrapAngle(heading - lanes.lane_heading->yaw_rad)) < kFollowsLaneToleranceRad)
    return lanes.lane_heading->yaw_rate_radps;
  // SceneConfig::lane_change_yaw_rate: moved sideways with its back behind its lane's start,
  // where SUMO's heading jumps as the move begins or ends.
  if (config_.lane_change_yaw_rate && !config_.instant_lane_changes && !held &&
      lanes.lane_start_yaw_rad &&
      std::fabs(WrapAngle(heading - *lanes.lane_start_yaw_rad)) <= kSidewaysMaxAngleRad)
    return lanes.lane_yaw_rate_radps;
  return measured;
}

double ObjectReader::GripYawRate(double speed_mps) const {
  return config_.friction * 9.80665 / std::fmax(speed_mps, 0.1);
}

bool ObjectReader::OffItsLane(const SumoObject& o) {
  const LaneInfo& lane = network_->Lane(o.lane);
  const Point2 on = PointAlong(lane.shape, OnShape(lane, o.lane_position_m), nullptr);
  return std::hypot(o.x_m - on.x, o.y_m - on.y) > 0.5 * lane.width_m;
}

void ObjectReader::Plausible(double lane_yaw_rate, bool counted, ObjectSnapshot* s) {
  ObjectState& st = s->state;
  bool changed = false;
  // The yaw rate a vehicle can turn at: within the friction circle, v r <= mu g. SUMO's heading
  // jumps at the corners of a junction's internal lane (27 degrees in one 0.1 s step at
  // 5.8 m/s: 4.8 rad/s, 27 m/s^2 of lateral acceleration); the vehicle follows its lane there,
  // so the lane's yaw rate (over the corners around it) replaces a yaw rate beyond grip. A
  // tight turn a vehicle really drives (SUMO's right turns: 1.3 rad/s at 4.3 m/s) stays.
  const double r_max = GripYawRate(st.speed_mps);
  if (std::fabs(st.yaw_rate_radps) > r_max) {
    const double lane = s->lanes.own ? lane_yaw_rate : 0.0;
    st.yaw_rate_radps = std::clamp(lane, -r_max, r_max);
    changed = true;
  }
  // Accelerations its type can drive: SUMO reports a speed forced by a script (or a stop in a
  // collision) as the acceleration of one step.
  const double lo = -s->type.emergency_decel_mps2.value_or(9.0);
  const double hi = s->type.accel_mps2.value_or(9.7);
  if (st.accel_mps2 < lo || st.accel_mps2 > hi) {
    st.accel_mps2 = std::clamp(st.accel_mps2, lo, hi);
    changed = true;
  }
  conditioned_ += changed && !counted ? 1 : 0;
}

std::optional<Leader> ObjectReader::LeaderOf(const std::string& id, double speed,
                                             double sumo_time_s) {
  if (!(speed > 0.1)) return std::nullopt;
  const std::optional<LeaderReport> ahead = traffic_->Leader(id, LeaderLookAhead(speed));
  if (!ahead) return std::nullopt;
  Leader leader;
  leader.id = ahead->id;
  leader.gap_m = ahead->gap_m;
  leader.speed_mps = ahead->speed_mps;
  leader.accel_mps2 = WindowAccel(ahead->id, ahead->accel_mps2, sumo_time_s);
  if (!std::isfinite(leader.gap_m) || !std::isfinite(leader.speed_mps) ||
      !std::isfinite(leader.accel_mps2))
    return std::nullopt;
  return leader;
}

}  // namespace criticality::plugin
