#include "criticality/scene_io.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <vector>

#include "criticality/errors.h"

namespace criticality {
namespace {

void WriteState(std::ostream& out, const ObjectState& s) {
  out << ' ' << s.x_m << ' ' << s.y_m << ' ' << s.yaw_rad << ' ' << s.speed_mps << ' '
      << s.accel_mps2 << ' ' << s.yaw_rate_radps << ' ' << s.sideslip_rad;
}

void WriteHeight(std::ostream& out, const std::optional<double>& h) {
  if (h)
    out << ' ' << *h;
  else
    out << " -";
}

void WriteStateLines(std::ostream& out, const ObjectState& s) {
  if (s.expected_accel_mps2) out << "expected-accel " << *s.expected_accel_mps2 << '\n';
  if (s.route_end_m) out << "route-end " << *s.route_end_m << '\n';
  if (s.braking_causes_known) out << "braking-causes-known\n";
}

void WriteLanes(std::ostream& out, const LaneSet& lanes) {
  auto one = [&](const char* name, const std::optional<Lane>& lane) {
    if (!lane) return;
    out << "lane " << name << ' ' << (lane->counter_traffic ? 1 : 0);
    for (const LaneDivider* d : {&lane->left, &lane->right}) {
      for (const Point2& p : d->points) out << ' ' << p.x << ' ' << p.y;
    }
    if (lane->straight_to_middle) out << " straight-to-middle";
    if (lane->corner_tangent_m > 0.0) out << " corner " << lane->corner_tangent_m;
    out << '\n';
  };
  one("own", lanes.own);
  one("left", lanes.left);
  one("right", lanes.right);
}

const char* RoadUserName(RoadUser r) {
  switch (r) {
    case RoadUser::kCar:
      return "car";
    case RoadUser::kMotorcycle:
      return "motorcycle";
    case RoadUser::kBicycle:
      return "bicycle";
    case RoadUser::kHeavy:
      return "heavy";
    case RoadUser::kRail:
      return "rail";
  }
  return "?";
}

// A 'type' line when the type is not a plain car without values (files without types stay as
// they were).
void WriteType(std::ostream& out, const VehicleType& t) {
  if (t.road_user == RoadUser::kCar && !t.mass_kg && !t.accel_mps2 && !t.decel_mps2 &&
      !t.emergency_decel_mps2 && !t.max_speed_mps)
    return;
  out << "type " << RoadUserName(t.road_user);
  auto value = [&](const char* key, const std::optional<double>& v) {
    if (v) out << ' ' << key << ' ' << *v;
  };
  value("mass", t.mass_kg);
  value("accel", t.accel_mps2);
  value("decel", t.decel_mps2);
  value("emergency-decel", t.emergency_decel_mps2);
  value("max-speed", t.max_speed_mps);
  out << '\n';
}

const char* StopReasonName(StopLine::Reason r) {
  switch (r) {
    case StopLine::Reason::kRedLight:
      return "red";
    case StopLine::Reason::kYellowLight:
      return "yellow";
    case StopLine::Reason::kYield:
      return "yield";
  }
  return "?";
}

struct LineReader {
  std::vector<std::string> words;
  size_t next{0};
  std::string where;
  double Num() {
    if (next >= words.size()) throw InputError(where + ": too few values");
    const std::string& w = words[next++];
    try {
      size_t used = 0;
      const double v = std::stod(w, &used);
      if (used == w.size()) return v;
    } catch (const std::exception&) {
    }
    throw InputError(where + ": '" + w + "' is not a number");
  }
  std::string Word() {
    if (next >= words.size()) throw InputError(where + ": too few values");
    return words[next++];
  }
  ObjectState State() {
    ObjectState s;
    s.x_m = Num();
    s.y_m = Num();
    s.yaw_rad = Num();
    s.speed_mps = Num();
    s.accel_mps2 = Num();
    s.yaw_rate_radps = Num();
    s.sideslip_rad = Num();
    return s;
  }
  std::optional<double> Height() {
    if (next < words.size() && words[next] == "-") {
      ++next;
      return std::nullopt;
    }
    return Num();
  }
};

void WriteStop(std::ostream& out, const std::optional<StopLine>& stop) {
  if (stop) out << "stop " << StopReasonName(stop->reason) << ' ' << stop->distance_m << '\n';
}

void WriteWay(std::ostream& out, const std::optional<Way>& way) {
  if (!way) return;
  out << "way " << way->front_m << ' ' << way->back_m << ' ' << way->points.size();
  for (const Point2& q : way->points) out << ' ' << q.x << ' ' << q.y;
  out << '\n';
}

}  // namespace

void WriteScene(std::ostream& out, const Scene& scene) {
  out << std::setprecision(17);
  out << "criticality-scene 1\n";
  if (scene.euler_update_step_s > 0.0)
    out << "euler-update-step " << scene.euler_update_step_s << '\n';
  if (scene.bodies_on_path) out << "bodies-on-path\n";
  out << "ego " << scene.ego.id;
  WriteState(out, scene.ego.state);
  out << ' ' << scene.ego.length_m << ' ' << scene.ego.width_m;
  WriteHeight(out, scene.ego.height_m);
  out << '\n';
  WriteStateLines(out, scene.ego.state);
  WriteType(out, scene.ego.type);
  WriteLanes(out, scene.ego.lanes);
  WriteStop(out, scene.ego.stop_line);
  WriteWay(out, scene.ego.way);
  for (const Vehicle& v : scene.vehicles) {
    out << "vehicle " << v.id;
    WriteState(out, v.state);
    out << ' ' << v.length_m << ' ' << v.width_m;
    WriteHeight(out, v.height_m);
    out << ' ' << (v.lanes ? 1 : 0) << '\n';
    WriteStateLines(out, v.state);
    if (v.lanes) WriteLanes(out, *v.lanes);
    WriteStop(out, v.stop_line);
    WriteType(out, v.type);
    WriteWay(out, v.way);
    for (const Carriage& c : v.carriages) {
      out << "carriage " << c.x_m << ' ' << c.y_m << ' ' << c.yaw_rad << ' ' << c.yaw_rate_radps
          << ' ' << c.length_m << ' ' << c.width_m << ' ' << (c.lanes ? 1 : 0) << '\n';
      if (c.lanes) WriteLanes(out, *c.lanes);
    }
  }
  for (const Pedestrian& p : scene.pedestrians) {
    out << "pedestrian " << p.id;
    WriteState(out, p.state);
    out << ' ' << p.length_m << ' ' << p.width_m << '\n';
    if (p.state.expected_accel_mps2)
      out << "expected-accel " << *p.state.expected_accel_mps2 << '\n';
    if (p.stays_on_footway) out << "footway\n";
  }
}

Scene ReadScene(std::istream& in, const std::string& source) {
  Scene scene;
  LaneSet* lanes = nullptr;
  ObjectState* state = nullptr;  // of the last ego, vehicle or pedestrian: 'expected-accel', ...
  VehicleType* type = nullptr;   // of the last ego or vehicle, for 'type'
  Vehicle* vehicle = nullptr;    // the last vehicle read, for its 'stop' and 'carriage' lines
  Pedestrian* pedestrian = nullptr;  // the last pedestrian read, for its 'footway' line
  bool after_ego = false;  // the last object read is the ego (for its 'stop' line)
  bool header = false, ego = false;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    LineReader r;
    r.where = source + ":" + std::to_string(n);
    std::istringstream words(line);
    for (std::string w; words >> w;) r.words.push_back(w);
    if (r.words.empty()) continue;
    const std::string kind = r.Word();
    if (!header) {
      if (kind != "criticality-scene" || r.Word() != "1") {
        throw InputError(r.where + ": not a scene file (expected 'criticality-scene 1')");
      }
      header = true;
      continue;
    }
    if (kind == "euler-update-step") {
      scene.euler_update_step_s = r.Num();
    } else if (kind == "bodies-on-path") {
      scene.bodies_on_path = true;
    } else if (kind == "ego") {
      scene.ego.id = r.Word();
      scene.ego.state = r.State();
      scene.ego.length_m = r.Num();
      scene.ego.width_m = r.Num();
      scene.ego.height_m = r.Height();
      lanes = &scene.ego.lanes;
      state = &scene.ego.state;
      type = &scene.ego.type;
      vehicle = nullptr;
      pedestrian = nullptr;
      ego = true;
      after_ego = true;
    } else if (kind == "vehicle") {
      Vehicle v;
      v.id = r.Word();
      v.state = r.State();
      v.length_m = r.Num();
      v.width_m = r.Num();
      v.height_m = r.Height();
      const bool has_lanes = r.Num() != 0.0;
      if (has_lanes) v.lanes = LaneSet{};
      scene.vehicles.push_back(std::move(v));
      lanes = has_lanes ? &*scene.vehicles.back().lanes : nullptr;
      state = &scene.vehicles.back().state;
      type = &scene.vehicles.back().type;
      vehicle = &scene.vehicles.back();
      pedestrian = nullptr;
      after_ego = false;
    } else if (kind == "pedestrian") {
      Pedestrian p;
      p.id = r.Word();
      p.state = r.State();
      p.length_m = r.Num();
      p.width_m = r.Num();
      scene.pedestrians.push_back(std::move(p));
      lanes = nullptr;
      state = &scene.pedestrians.back().state;  // for 'expected-accel' (not 'route-end')
      type = nullptr;
      vehicle = nullptr;
      after_ego = false;
      pedestrian = &scene.pedestrians.back();
    } else if (kind == "type") {
      if (!type) throw InputError(r.where + ": 'type' must follow an ego or a vehicle");
      const std::string name = r.Word();
      VehicleType t;
      if (name == "car") {
        t.road_user = RoadUser::kCar;
      } else if (name == "motorcycle") {
        t.road_user = RoadUser::kMotorcycle;
      } else if (name == "bicycle") {
        t.road_user = RoadUser::kBicycle;
      } else if (name == "heavy") {
        t.road_user = RoadUser::kHeavy;
      } else if (name == "rail") {
        t.road_user = RoadUser::kRail;
      } else {
        throw InputError(r.where + ": road user '" + name +
                         "' must be car, motorcycle, bicycle, heavy or rail");
      }
      while (r.next < r.words.size()) {
        const std::string key = r.Word();
        std::optional<double>* field = key == "mass"              ? &t.mass_kg
                                       : key == "accel"           ? &t.accel_mps2
                                       : key == "decel"           ? &t.decel_mps2
                                       : key == "emergency-decel" ? &t.emergency_decel_mps2
                                       : key == "max-speed"       ? &t.max_speed_mps
                                                                  : nullptr;
        if (!field)
          throw InputError(r.where + ": type value '" + key +
                           "' must be mass, accel, decel, emergency-decel or max-speed");
        *field = r.Num();
      }
      *type = t;
    } else if (kind == "carriage") {
      if (!vehicle) throw InputError(r.where + ": 'carriage' must follow a vehicle");
      Carriage c;
      c.x_m = r.Num();
      c.y_m = r.Num();
      c.yaw_rad = r.Num();
      c.yaw_rate_radps = r.Num();
      c.length_m = r.Num();
      c.width_m = r.Num();
      const bool has_lanes = r.Num() != 0.0;
      if (has_lanes) c.lanes = LaneSet{};
      vehicle->carriages.push_back(std::move(c));
      lanes = has_lanes ? &*vehicle->carriages.back().lanes : nullptr;
    } else if (kind == "way") {
      if (!vehicle && !after_ego)
        throw InputError(r.where + ": 'way' must follow the ego or a vehicle");
      Way w;
      w.front_m = r.Num();
      w.back_m = r.Num();
      const double n = r.Num();
      if (!(n >= 0.0 && n <= kMaxWayPoints))
        throw InputError(r.where + ": a way has at most 48 points");
      for (int k = 0; k < static_cast<int>(n); ++k) {
        Point2 q;
        q.x = r.Num();
        q.y = r.Num();
        w.points.push_back(q);
      }
      (vehicle ? vehicle->way : scene.ego.way) = std::move(w);
    } else if (kind == "footway") {
      if (!pedestrian) throw InputError(r.where + ": 'footway' must follow a pedestrian");
      pedestrian->stays_on_footway = true;
    } else if (kind == "route-end") {
      if (!state || pedestrian)
        throw InputError(r.where + ": 'route-end' must follow an ego or a vehicle");
      state->route_end_m = r.Num();
    } else if (kind == "braking-causes-known") {
      if (!state || pedestrian)
        throw InputError(r.where + ": 'braking-causes-known' must follow an ego or a vehicle");
      state->braking_causes_known = true;
    } else if (kind == "expected-accel") {
      if (!state)
        throw InputError(r.where +
                         ": 'expected-accel' must follow an ego, a vehicle or a pedestrian");
      state->expected_accel_mps2 = r.Num();
    } else if (kind == "stop") {
      if (!vehicle && !after_ego)
        throw InputError(r.where + ": 'stop' must follow an ego or a vehicle");
      const std::string reason = r.Word();
      StopLine stop;
      if (reason == "red") {
        stop.reason = StopLine::Reason::kRedLight;
      } else if (reason == "yellow") {
        stop.reason = StopLine::Reason::kYellowLight;
      } else if (reason == "yield") {
        stop.reason = StopLine::Reason::kYield;
      } else {
        throw InputError(r.where + ": stop reason '" + reason + "' must be red, yellow or yield");
      }
      stop.distance_m = r.Num();
      (vehicle ? vehicle->stop_line : scene.ego.stop_line) = stop;
    } else if (kind == "lane") {
      if (!lanes)
        throw InputError(r.where +
                         ": 'lane' must follow an ego, or a vehicle or carriage with LANES 1");
      const std::string which = r.Word();
      Lane lane;
      lane.counter_traffic = r.Num() != 0.0;
      for (LaneDivider* d : {&lane.left, &lane.right}) {
        for (Point2& p : d->points) {
          p.x = r.Num();
          p.y = r.Num();
        }
      }
      while (r.next < r.words.size()) {
        const std::string shape = r.Word();
        if (shape == "straight-to-middle") {
          lane.straight_to_middle = true;
        } else if (shape == "corner") {
          lane.corner_tangent_m = r.Num();
          if (!(lane.corner_tangent_m > 0.0) || !std::isfinite(lane.corner_tangent_m))
            throw InputError(r.where + ": corner tangent length must be a positive number of m");
        } else {
          throw InputError(r.where + ": lane shape '" + shape +
                           "' must be straight-to-middle or corner T");
        }
      }
      if (which == "own")
        lanes->own = lane;
      else if (which == "left")
        lanes->left = lane;
      else if (which == "right")
        lanes->right = lane;
      else
        throw InputError(r.where + ": lane '" + which + "' must be own, left or right");
    } else {
      throw InputError(r.where + ": unknown record '" + kind +
                       "' (euler-update-step, ego, vehicle, pedestrian, lane, stop, footway, "
                       "expected-accel, route-end, braking-causes-known, type, carriage)");
    }
    if (r.next != r.words.size()) throw InputError(r.where + ": too many values");
  }
  if (!header) throw InputError(source + ": empty, not a scene file");
  if (!ego) throw InputError(source + ": no 'ego' line");
  return scene;
}

Scene ReadSceneFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError("scene file '" + path + "': cannot be read");
  return ReadScene(in, path);
}

}  // namespace criticality
