#pragma once
// A SUMO world in memory for the plugin's stage tests: a small network (straight lanes built
// edge by edge, links between them), vehicles and persons placed by the test, what SUMO would
// report after each step (queued by the test), and a log of every command the driver sent.
// Step() moves every vehicle along its heading at its speed (a commanded speed replaces it),
// the way SUMO's Euler update does: x += v_new dt.
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "plugin/observe/observation.h"
#include "plugin/sumo/sumo_world.h"

namespace criticality::plugin::testing {

class FakeSumoWorld final : public SumoWorld {
 public:
  explicit FakeSumoWorld(double step_s = 0.1) : dt_(step_s) {}

  // ---- Building the network -------------------------------------------------------------
  /** An edge of `lanes` parallel straight lanes from (x0, y0) to (x1, y1), lane 0 rightmost,
   *  each `width` wide; `allowed` classes for every lane (empty: all). */
  void AddEdge(const std::string& edge, double x0, double y0, double x1, double y1, int lanes,
               double width = 3.2, std::vector<std::string> allowed = {}) {
    const double len = std::hypot(x1 - x0, y1 - y0);
    const double nx = -(y1 - y0) / len, ny = (x1 - x0) / len;  // left normal
    for (int k = 0; k < lanes; ++k) {
      // Lane k's centre: (k - (lanes - 1) / 2) widths left of the edge's axis.
      const double off = (k - 0.5 * (lanes - 1)) * width;
      LaneInfo l;
      l.shape = {Point2{x0 + nx * off, y0 + ny * off}, Point2{x1 + nx * off, y1 + ny * off}};
      l.width_m = width;
      l.length_m = len;
      l.edge = edge;
      l.index = k;
      const std::string id = edge + "_" + std::to_string(k);
      lanes_[id] = l;
      allowed_[id] = allowed;
    }
    lane_count_[edge] = lanes;
    edges_.push_back(edge);
  }
  /** Renumbers `edge`'s lanes from its other side, as netconvert --lefthand numbers them: lane 0
   *  becomes the leftmost (each lane's shape swapped with its mirror's). */
  void MirrorLanes(const std::string& edge) {
    const int n = lane_count_.at(edge);
    for (int k = 0; k < n / 2; ++k) {
      std::swap(lanes_.at(edge + "_" + std::to_string(k)).shape,
                lanes_.at(edge + "_" + std::to_string(n - 1 - k)).shape);
    }
  }
  void AddLink(const std::string& from_lane, const std::string& to_lane, std::string state = "M",
               bool has_foe = false, std::string direction = "s") {
    links_[from_lane].push_back(LaneLink{to_lane, "", state, has_foe, direction});
  }
  /** A single-lane edge (`edge`_0) along `shape`, e.g. a junction's curved internal lane. */
  void AddLaneShape(const std::string& edge, std::vector<Point2> shape, double width = 3.2) {
    LaneInfo l;
    for (size_t k = 1; k < shape.size(); ++k)
      l.length_m += std::hypot(shape[k].x - shape[k - 1].x, shape[k].y - shape[k - 1].y);
    l.shape = std::move(shape);
    l.width_m = width;
    l.edge = edge;
    lanes_[edge + "_0"] = l;
    lane_count_[edge] = 1;
    edges_.push_back(edge);
  }
  /** A link from `from_lane` to `to_lane` through a junction's internal lane `via` (SUMO's
   *  TraCIConnection: its approached lane and its via lane). */
  void AddLinkVia(const std::string& from_lane, const std::string& to_lane, const std::string& via,
                  std::string direction = "s", std::string state = "M", bool has_foe = false) {
    links_[from_lane].push_back(
        LaneLink{to_lane, via, std::move(state), has_foe, std::move(direction)});
  }
  /** SUMO's length of `lane`, where netconvert's shape is longer or shorter than it (lane
   *  positions run along this length, scaled onto the shape). */
  void SetLaneLength(const std::string& lane, double length_m) {
    lanes_.at(lane).length_m = length_m;
  }
  void SetAllowed(const std::string& lane, std::vector<std::string> classes) {
    allowed_[lane] = std::move(classes);
  }

  // ---- Objects ----------------------------------------------------------------------------
  /** A vehicle whose front bumper is at (x, y), heading along `angle_deg` (navigation). */
  SumoObject& AddVehicle(const std::string& id, double x, double y, double angle_deg, double speed,
                         const std::string& lane = "", double lane_pos = 0.0,
                         std::vector<std::string> route = {}) {
    SumoObject o;
    o.id = id;
    o.x_m = x;
    o.y_m = y;
    o.angle_deg = angle_deg;
    o.speed_mps = speed;
    o.length_m = 5.0;
    o.width_m = 1.8;
    o.decel_mps2 = 4.5;
    o.vehicle_class = "passenger";
    o.lane = lane;
    o.lane_position_m = lane_pos;
    o.lane_index = lane.empty() ? 0 : lanes_.at(lane).index;
    o.route = std::move(route);
    objects_.push_back(o);
    known_[id] = Known::kVehicle;
    return objects_.back();
  }
  SumoObject& AddPerson(const std::string& id, double x, double y, double angle_deg, double speed,
                        const std::string& lane = "", const std::string& next_edge = "") {
    SumoObject o;
    o.id = id;
    o.person = true;
    o.x_m = x;
    o.y_m = y;
    o.angle_deg = angle_deg;
    o.speed_mps = speed;
    o.lane = lane;
    o.next_edge = next_edge;
    objects_.push_back(o);
    known_[id] = Known::kPerson;
    return objects_.back();
  }
  SumoObject* Find(const std::string& id) {
    for (SumoObject& o : objects_) {
      if (o.id == id) return &o;
    }
    return nullptr;
  }
  void Remove(const std::string& id) {
    objects_.erase(std::remove_if(objects_.begin(), objects_.end(),
                                  [&](const SumoObject& o) { return o.id == id; }),
                   objects_.end());
  }
  /** What SUMO reports after the next Step() (then cleared). */
  StepReport next_report;
  std::map<std::string, LeaderReport> leaders;
  std::map<std::string, SignalReport> signals;
  std::map<std::string, VehicleTypeReport> types;  ///< by vType ID
  std::map<std::string, std::string> options;
  /** ReadControl's answer per vehicle; unset: the vehicle's speed as SUMO's own choice. */
  std::map<std::string, VehicleControl> control;
  LaneChanging lane_changing;
  /** What BallisticUpdate answers (a test switches it as SUMO would mid-run). */
  bool ballistic{false};
  double end_time_s{-1.0};
  /** Every command, one line each: "speed ego 12.30", "release ego", "lane ego 1 2.0", ... */
  std::vector<std::string> commands;
  std::vector<std::string> forgotten;
  /** Publish calls: ego -> (last p, warning). */
  std::map<std::string, std::pair<double, bool>> published;
  /** Every Publish call in order: "<Time()> <ego> <p> <warning>", Time() being SUMO's clock
   *  when it came (the stamp of the last step made + one step). */
  std::shared_ptr<std::vector<std::string>> publish_log =
      std::make_shared<std::vector<std::string>>();
  /** Step() fails (as SUMO does when it cannot go on) when it would take the clock here. */
  double fail_at_s{-1.0};
  /** Vehicles that arrive (leave the network, reported in `arrived`) at the Step() that takes
   *  the clock to this time. */
  std::map<std::string, double> arrive_at;

  // ---- SumoWorld --------------------------------------------------------------------------
  std::string Version() override { return "fake SUMO"; }
  void Step() override {
    if (fail_at_s >= 0.0 && now_ + dt_ >= fail_at_s - 1e-9)
      throw SumoError("simulation step: the fake SUMO fails here");
    report_ = next_report;
    next_report = StepReport{};
    for (SumoObject& o : objects_) {
      auto it = commanded_.find(o.id);
      if (it != commanded_.end()) o.speed_mps = it->second;
      const double yaw = (90.0 - o.angle_deg) * M_PI / 180.0;
      o.x_m += o.speed_mps * dt_ * std::cos(yaw);
      o.y_m += o.speed_mps * dt_ * std::sin(yaw);
      if (!o.lane.empty()) o.lane_position_m += o.speed_mps * dt_;
    }
    now_ += dt_;
    for (const auto& [id, t] : arrive_at) {
      if (Find(id) && now_ >= t - 1e-9) {
        Remove(id);
        report_.arrived.push_back(id);
      }
    }
  }
  double Time() override { return now_; }
  double StepLength() override { return dt_; }
  double EndTime() override { return end_time_s; }
  std::string Option(const std::string& name) override {
    auto it = options.find(name);
    return it == options.end() ? "" : it->second;
  }
  int ExpectedObjects() override { return static_cast<int>(objects_.size()); }
  StepReport Report() override { return report_; }
  std::vector<std::string> VehicleIds() override {
    std::vector<std::string> ids;
    for (const SumoObject& o : objects_) {
      if (!o.person) ids.push_back(o.id);
    }
    return ids;
  }
  Known Lookup(const std::string& id) override {
    auto it = known_.find(id);
    return it == known_.end() ? Known::kUnknown : it->second;
  }
  SumoSurroundings Observe(const std::vector<std::string>& egos, const ReadScope& scope) override {
    SumoSurroundings out;
    out.whole_network = scope.whole_network;
    out.objects = objects_;
    for (const std::string& ego : egos) {
      const int self = IndexOf(ego, out.objects);
      if (self < 0) continue;  // it left
      SumoSurroundings::Ego e;
      e.self = self;
      if (!scope.whole_network) {
        for (int k = 0; k < static_cast<int>(out.objects.size()); ++k) {
          const SumoObject& o = out.objects[k];
          // As SUMO's context: what it cannot place (NaN) is delivered too.
          if (k != self && !(std::hypot(o.x_m - out.objects[self].x_m,
                                        o.y_m - out.objects[self].y_m) > scope.context_range_m))
            e.nearby.push_back(k);
        }
      }
      out.egos.push_back(e);
    }
    return out;
  }
  void Forget(const std::string& id) override { forgotten.push_back(id); }
  void Publish(const std::string& ego, double p, bool warning) override {
    // As SUMO: a vehicle no longer in the simulation cannot be written to.
    if (!Find(ego)) throw SumoError("publish criticality: Vehicle '" + ego + "' is not known");
    published[ego] = {p, warning};
    publish_log->push_back(Fixed(now_) + " " + ego + " " + std::to_string(p) + " " +
                          (warning ? "1" : "0"));
  }
  std::optional<LeaderReport> Leader(const std::string& vehicle, double) override {
    auto it = leaders.find(vehicle);
    if (it == leaders.end()) return std::nullopt;
    return it->second;
  }
  std::optional<SignalReport> NextSignal(const std::string& vehicle) override {
    auto it = signals.find(vehicle);
    if (it == signals.end()) return std::nullopt;
    return it->second;
  }
  const VehicleTypeReport& TypeOf(const std::string& type_id) override {
    return types[type_id];  // unknown: SUMO's passenger defaults
  }
  const LaneInfo& Lane(const std::string& id) override { return lanes_.at(id); }
  const std::vector<LaneLink>& Links(const std::string& lane) override { return links_[lane]; }
  std::vector<LaneLink> LinksNow(const std::string& lane) override { return links_[lane]; }
  const std::vector<std::string>& AllowedClasses(const std::string& lane) override {
    return allowed_[lane];
  }
  int LaneCount(const std::string& edge) override { return lane_count_.at(edge); }
  std::vector<std::string> Edges() override { return edges_; }
  VehicleControl ReadControl(const std::string& v) override {
    auto it = control.find(v);
    if (it != control.end()) return it->second;
    VehicleControl c;
    const SumoObject* o = Find(v);
    c.own_speed_mps = o ? o->speed_mps : 0.0;
    c.resume_speed_mps = c.own_speed_mps;
    c.lane = o ? o->lane : "";
    c.lane_index = o ? o->lane_index : 0;
    c.lanes = (o && !o->lane.empty()) ? lane_count_.at(lanes_.at(o->lane).edge) : 1;
    return c;
  }
  void CommandSpeed(const std::string& ego, double speed) override {
    commanded_[ego] = speed;
    commands.push_back("speed " + ego + " " + Fixed(speed));
  }
  void ReleaseSpeed(const std::string& ego) override {
    commanded_.erase(ego);
    commands.push_back("release " + ego);
  }
  void ChangeLane(const std::string& ego, int lane_index, double hold_s) override {
    commands.push_back("lane " + ego + " " + std::to_string(lane_index) + " " + Fixed(hold_s));
  }
  void ChangeSublane(const std::string& ego, double lateral_m) override {
    commands.push_back("sublane " + ego + " " + Fixed(lateral_m));
  }
  LaneChanging LaneChangingModel() override { return lane_changing; }
  bool BallisticUpdate() override { return ballistic; }
  bool Apply(const ScenarioEvent& e) override {
    if (!Find(e.target)) return false;
    commands.push_back("event " + e.text);
    return true;
  }
  void Close() override { closed = true; }
  bool closed{false};

  static std::string Fixed(double v) {
    std::ostringstream o;
    o.setf(std::ios::fixed);
    o.precision(2);
    o << v;
    return o.str();
  }

 private:
  static int IndexOf(const std::string& id, const std::vector<SumoObject>& objects) {
    for (int k = 0; k < static_cast<int>(objects.size()); ++k) {
      if (objects[k].id == id && !objects[k].person) return k;
    }
    return -1;
  }

  double dt_;
  double now_{0.0};
  std::map<std::string, LaneInfo> lanes_;
  std::map<std::string, std::vector<LaneLink>> links_;
  std::map<std::string, std::vector<std::string>> allowed_;
  std::map<std::string, int> lane_count_;
  std::vector<std::string> edges_;
  std::vector<SumoObject> objects_;
  std::map<std::string, Known> known_;
  std::map<std::string, double> commanded_;
  StepReport report_;
};

/** A square right turn: N runs north to (0, 0), the junction's internal lane :J_0_0 goes
 *  (0, 0) -> (0, 5) -> (5, 5), E runs east from (5, 5); one lane each. */
inline void AddSquareRightTurn(FakeSumoWorld& w) {
  w.AddEdge("N", 0, -100, 0, 0, 1);
  w.AddLaneShape(":J_0", {Point2{0, 0}, Point2{0, 5}, Point2{5, 5}});
  w.AddEdge("E", 5, 5, 105, 5, 1);
  w.AddLinkVia("N_0", "E_0", ":J_0_0", "r");
  w.AddLink(":J_0_0", "E_0", "M", false, "r");
}

/** Half a circle of radius 2 around (-2, 0) from angle a0 to a1 (radians), counter-clockwise,
 *  in 9 points. */
inline std::vector<Point2> UTurnArc(double a0, double a1) {
  std::vector<Point2> p;
  for (int k = 0; k <= 8; ++k) {
    const double a = a0 + (a1 - a0) * k / 8.0;
    p.push_back(Point2{-2.0 + 2.0 * std::cos(a), 2.0 * std::sin(a)});
  }
  return p;
}

/** SUMO's U-turn at a junction that an internal junction splits (the grid's :B2_14_0 then
 *  :B2_28_0): N runs north to (0, 0), the turn bends left around (-2, 0) in two internal lanes
 *  (:J_14_0 to the apex (-2, 2), :J_28_0 on to (-4, 0)), S runs south from (-4, 0). TraCI's
 *  links: N_0 to S_0 via the first part, the first part to S_0 via the second. */
inline FakeSumoWorld SplitUTurn() {
  constexpr double kHalfPi = 1.5707963267948966;
  FakeSumoWorld w;
  w.AddEdge("N", 0, -100, 0, 0, 1);
  w.AddLaneShape(":J_14", UTurnArc(0.0, kHalfPi));
  w.AddLaneShape(":J_28", UTurnArc(kHalfPi, 2.0 * kHalfPi));
  w.AddEdge("S", -4, 0, -4, -100, 1);
  w.AddLinkVia("N_0", "S_0", ":J_14_0", "t");
  w.AddLinkVia(":J_14_0", "S_0", ":J_28_0", "t");
  w.AddLink(":J_28_0", "S_0", "M", false, "t");
  return w;
}

/** An observation of every object of the world, each vehicle in `egos` an ego with every other
 *  object near it, read at the world's time (what the observe stage hands the scene stage). */
inline Observation ObserveAll(FakeSumoWorld& w, const std::vector<std::string>& egos) {
  Observation obs;
  obs.time_s = w.StampOfLastStep();
  obs.sumo_time_s = w.Time();
  ReadScope scope;
  scope.context_range_m = 1e9;
  obs.surroundings = w.Observe(egos, scope);
  return obs;
}

}  // namespace criticality::plugin::testing
