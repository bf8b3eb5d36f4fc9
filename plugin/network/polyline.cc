#include "plugin/network/polyline.h"

#include <cmath>

namespace criticality::plugin {

double PolylineLength(const std::vector<Point2>& line) {
  double length = 0.0;
  for (size_t i = 1; i < line.size(); ++i) {
    length += std::hypot(line[i].x - line[i - 1].x, line[i].y - line[i - 1].y);
  }
  return length;
}

Point2 PointAlong(const std::vector<Point2>& line, double s, double* heading) {
  // Find the segment holding s; before the start and past the end, extend the end segments.
  size_t seg = 1;
  double start = 0.0;
  for (; seg + 1 < line.size(); ++seg) {
    const double len = std::hypot(line[seg].x - line[seg - 1].x, line[seg].y - line[seg - 1].y);
    if (s <= start + len) break;
    start += len;
  }
  const Point2& a = line[seg - 1];
  const Point2& b = line[seg];
  const double len = std::hypot(b.x - a.x, b.y - a.y);
  const double ux = len > 0.0 ? (b.x - a.x) / len : 1.0, uy = len > 0.0 ? (b.y - a.y) / len : 0.0;
  if (heading) *heading = std::atan2(uy, ux);
  const double t = s - start;
  return Point2{a.x + ux * t, a.y + uy * t};
}

}  // namespace criticality::plugin
