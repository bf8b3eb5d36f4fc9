#include "plugin/observe/neighbour_grid.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <vector>

#include "plugin/sumo/sumo_conventions.h"

namespace criticality::plugin {

void FindNeighbours(double cell_m, SumoSurroundings* s) {
  auto cell_of = [&](double v) {
    return std::isfinite(v) ? static_cast<long long>(std::floor(v / cell_m)) : 0LL;
  };
  auto key = [](long long cx, long long cy) {
    return (static_cast<unsigned long long>(cx) << 32) ^
           (static_cast<unsigned long long>(cy) & 0xffffffffULL);
  };
  std::vector<Pose2> centres;
  centres.reserve(s->objects.size());
  std::unordered_map<unsigned long long, std::vector<int>> grid;
  for (int k = 0; k < static_cast<int>(s->objects.size()); ++k) {
    const SumoObject& o = s->objects[k];
    centres.push_back(CentreOf(o));
    grid[key(cell_of(centres[k].x), cell_of(centres[k].y))].push_back(k);
    // A body longer than a cell is in every cell along it (straight back from its front: a
    // train's rear carriages may pass an ego far from its front).
    if (!o.person && o.length_m > cell_m && std::isfinite(centres[k].yaw)) {
      const double c = std::cos(centres[k].yaw), sn = std::sin(centres[k].yaw);
      for (double d = 0.0; d <= o.length_m; d += 0.5 * cell_m) {
        std::vector<int>& in = grid[key(cell_of(o.x_m - c * d), cell_of(o.y_m - sn * d))];
        if (in.empty() || in.back() != k) in.push_back(k);
      }
    }
  }
  for (SumoSurroundings::Ego& e : s->egos) {
    e.nearby.clear();
    const Pose2& c = centres[e.self];
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        auto it = grid.find(key(cell_of(c.x + dx * cell_m), cell_of(c.y + dy * cell_m)));
        if (it == grid.end()) continue;
        for (int k : it->second) {
          if (k != e.self) e.nearby.push_back(k);
        }
      }
    }
    std::sort(e.nearby.begin(), e.nearby.end());
    e.nearby.erase(std::unique(e.nearby.begin(), e.nearby.end()), e.nearby.end());
  }
}

}  // namespace criticality::plugin
