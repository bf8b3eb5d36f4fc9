#include "plugin/scenes/road_users.h"

#include <map>
#include <sstream>
#include <stdexcept>

namespace criticality::plugin {
namespace {

// SUMO 1.15's vClasses (SUMOVehicleClass.cpp) and what they are here.
const std::map<std::string, std::optional<RoadUser>>& Classes() {
  static const std::map<std::string, std::optional<RoadUser>> classes{
      {"ignoring", RoadUser::kCar},        {"private", RoadUser::kCar},
      {"emergency", RoadUser::kCar},       {"authority", RoadUser::kCar},
      {"army", RoadUser::kCar},            {"vip", RoadUser::kCar},
      {"passenger", RoadUser::kCar},       {"hov", RoadUser::kCar},
      {"taxi", RoadUser::kCar},            {"delivery", RoadUser::kCar},
      {"evehicle", RoadUser::kCar},        {"custom1", RoadUser::kCar},
      {"custom2", RoadUser::kCar},         {"bus", RoadUser::kHeavy},
      {"coach", RoadUser::kHeavy},         {"truck", RoadUser::kHeavy},
      {"trailer", RoadUser::kHeavy},       {"motorcycle", RoadUser::kMotorcycle},
      {"moped", RoadUser::kMotorcycle},    {"bicycle", RoadUser::kBicycle},
      {"scooter", RoadUser::kBicycle},     {"pedestrian", RoadUser::kBicycle},
      {"tram", RoadUser::kRail},           {"rail_urban", RoadUser::kRail},
      {"rail", RoadUser::kRail},           {"rail_electric", RoadUser::kRail},
      {"rail_fast", RoadUser::kRail},      {"subway", RoadUser::kRail},
      {"cable_car", RoadUser::kRail},      {"ship", std::nullopt},
      {"aircraft", std::nullopt},          {"drone", std::nullopt},
      {"container", std::nullopt}};
  return classes;
}

}  // namespace

std::optional<RoadUser> RoadUserOf(const std::string& vehicle_class) {
  auto it = Classes().find(vehicle_class);
  return it == Classes().end() ? std::optional<RoadUser>(RoadUser::kCar) : it->second;
}

VehicleType TypeFrom(const VehicleTypeReport& sumo, RoadUser road_user) {
  VehicleType t;
  t.road_user = road_user;
  t.mass_kg = sumo.mass_kg;
  auto positive = [](double v) { return v > 0.0 ? std::optional<double>(v) : std::nullopt; };
  t.accel_mps2 = positive(sumo.accel_mps2);
  t.decel_mps2 = positive(sumo.decel_mps2);
  t.emergency_decel_mps2 = positive(sumo.emergency_decel_mps2);
  t.max_speed_mps = positive(sumo.max_speed_mps);
  return t;
}

bool EgoClasses::Includes(const std::string& vehicle_class) const {
  const std::optional<RoadUser> user = RoadUserOf(vehicle_class);
  if (!user) return false;  // no road user is ever an ego
  if (all) return true;
  if (!classes.empty()) return classes.count(vehicle_class) > 0;
  return *user != RoadUser::kRail;
}

EgoClasses ParseEgoClasses(const std::string& text) {
  EgoClasses out;
  if (text == "all") {
    out.all = true;
    return out;
  }
  std::istringstream in(text);
  std::string name;
  while (std::getline(in, name, ',')) {
    if (name.empty()) continue;
    const auto it = Classes().find(name);
    if (it == Classes().end() || !it->second) {
      std::string known;
      for (const auto& [c, user] : Classes()) {
        if (user) known += (known.empty() ? "" : ", ") + c;
      }
      throw std::invalid_argument("--ego-classes: " +
                                  (it == Classes().end()
                                       ? "unknown vClass '" + name + "'"
                                       : "vClass '" + name + "' is no road user and never an ego") +
                                  "; use all or " + known);
    }
    out.classes.insert(name);
  }
  if (out.classes.empty())
    throw std::invalid_argument("--ego-classes '" + text + "': name at least one vClass, or all");
  return out;
}

}  // namespace criticality::plugin
