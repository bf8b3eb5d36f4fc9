#include "plugin/sumo/route_ids.h"

#include <cctype>
#include <fstream>
#include <sstream>

namespace criticality::plugin {
namespace {

std::vector<std::string> SplitList(const std::string& list) {
  std::vector<std::string> out;
  std::string item;
  std::istringstream in(list);
  while (std::getline(in, item, ',')) {
    const auto b = item.find_first_not_of(" \t");
    const auto e = item.find_last_not_of(" \t");
    if (b != std::string::npos) out.push_back(item.substr(b, e - b + 1));
  }
  return out;
}

// The value of attribute `name` inside the tag text `tag` ("" when absent).
std::string Attribute(const std::string& tag, const std::string& name) {
  size_t at = 0;
  while ((at = tag.find(name, at)) != std::string::npos) {
    const bool starts = at > 0 && std::isspace(static_cast<unsigned char>(tag[at - 1]));
    size_t k = at + name.size();
    while (k < tag.size() && std::isspace(static_cast<unsigned char>(tag[k]))) ++k;
    if (starts && k < tag.size() && tag[k] == '=') {
      ++k;
      while (k < tag.size() && std::isspace(static_cast<unsigned char>(tag[k]))) ++k;
      if (k < tag.size() && (tag[k] == '"' || tag[k] == '\'')) {
        const size_t end = tag.find(tag[k], k + 1);
        if (end != std::string::npos) return tag.substr(k + 1, end - k - 1);
      }
    }
    at += name.size();
  }
  return "";
}

// Scans one file; false when it cannot be scanned.
bool ScanFile(const std::string& path, RouteIds* ids) {
  if (path.size() > 3 && path.compare(path.size() - 3, 3, ".gz") == 0) return false;
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream buf;
  buf << in.rdbuf();
  const std::string text = buf.str();
  size_t at = 0;
  while ((at = text.find('<', at)) != std::string::npos) {
    if (text.compare(at, 4, "<!--") == 0) {
      const size_t end = text.find("-->", at + 4);
      if (end == std::string::npos) break;
      at = end + 3;
      continue;
    }
    size_t k = at + 1;
    while (k < text.size() &&
           (std::isalnum(static_cast<unsigned char>(text[k])) || text[k] == ':' || text[k] == '_'))
      ++k;
    const std::string name = text.substr(at + 1, k - at - 1);
    const size_t end = text.find('>', k);
    if (end == std::string::npos) break;
    if (name == "include" || name == "xi:include") return false;
    std::set<std::string>* into = nullptr;
    if (name == "vehicle" || name == "trip") into = &ids->vehicles;
    if (name == "flow") into = &ids->vehicle_flows;
    if (name == "person" || name == "container") into = &ids->persons;
    if (name == "personFlow" || name == "containerFlow") into = &ids->person_flows;
    if (into) {
      const std::string id = Attribute(text.substr(k, end - k), "id");
      if (!id.empty()) into->insert(id);
    }
    at = end + 1;
  }
  return true;
}

// FLOW.N of one of the flows?
bool FromFlow(const std::set<std::string>& flows, const std::string& id) {
  const auto dot = id.rfind('.');
  if (dot == std::string::npos || dot + 1 == id.size()) return false;
  for (size_t k = dot + 1; k < id.size(); ++k) {
    if (!std::isdigit(static_cast<unsigned char>(id[k]))) return false;
  }
  return flows.count(id.substr(0, dot)) > 0;
}

}  // namespace

RouteIds ScanRouteIds(const std::vector<std::string>& files) {
  RouteIds ids;
  for (const std::string& entry : files) {
    for (const std::string& file : SplitList(entry)) {
      if (!ScanFile(file, &ids)) ids.unscanned.push_back(file);
    }
  }
  return ids;
}

RouteIdKind Classify(const RouteIds& ids, const std::string& id) {
  if (ids.vehicles.count(id) || FromFlow(ids.vehicle_flows, id)) return RouteIdKind::kVehicle;
  if (ids.persons.count(id) || FromFlow(ids.person_flows, id)) return RouteIdKind::kPerson;
  return ids.unscanned.empty() ? RouteIdKind::kAbsent : RouteIdKind::kCannotTell;
}

}  // namespace criticality::plugin
