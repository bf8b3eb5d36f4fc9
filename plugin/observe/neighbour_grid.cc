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
    centres.push_back(CentreOf(s->objects[k]));
    grid[key(cell_of(centres[k].x), cell_of(centres[k].y))].push_back(k);
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
  }
}

}  // namespace criticality::plugin
