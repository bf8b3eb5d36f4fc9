#include "plugin/observe/critical_events.h"

#include <algorithm>
#include <cmath>

#include "criticality/geometry.h"
#include "criticality/scene.h"
#include "plugin/sumo/sumo_conventions.h"

namespace criticality::plugin {
namespace {

using Body = CriticalEventDetector::Body;

// An object's footprint where SUMO places it: a vehicle's box from its front to its back
// (BodyLengthOf: SUMO's box, shorter than the vehicle in a turn) x its width, a person the
// estimator's default pedestrian square.
Body BodyOf(const SumoObject& o) {
  const Pedestrian walker;
  Body b;
  b.centre = CentreOf(o);
  b.half_length = 0.5 * (o.person ? walker.length_m : BodyLengthOf(o));
  b.half_width = 0.5 * (o.person ? walker.width_m : o.width_m);
  b.speed_mps = o.speed_mps;
  return b;
}

bool Placed(const Body& b) {
  return std::isfinite(b.centre.x) && std::isfinite(b.centre.y) && std::isfinite(b.centre.yaw) &&
         b.half_length > 0.0 && b.half_width > 0.0;
}

bool Overlap(const Body& a, const Body& b) {
  return RectanglesOverlap(a.centre, a.half_length, a.half_width, b.centre, b.half_length,
                           b.half_width);
}

// Whether `from` could have moved to `to` in dt seconds at its speeds (plus 1 m: rounding,
// a lane change): a longer jump is a teleport, not a motion to interpolate.
bool Moved(const Body& from, const Body& to, double dt) {
  const double v = std::fmax(std::fmax(from.speed_mps, to.speed_mps), 0.0);
  return std::hypot(to.centre.x - from.centre.x, to.centre.y - from.centre.y) <= v * dt + 1.0;
}

// The body a fraction f of the way from a to b: its centre on the circular arc that leaves a
// along a's heading and ends at b's centre (SUMO moves a vehicle along its lane: through a
// junction turn the straight line between two poses 1 s apart cuts the corner by half a metre
// and more), on the straight line where the arc would turn more than 45 degrees either way
// from the line (not a motion along a lane); its heading turned evenly from a's to b's.
Body Between(const Body& a, const Body& b, double f) {
  constexpr double kMaxArcRad = 0.7853981633974483;  // 45 degrees
  Body m = b;
  m.centre.yaw = a.centre.yaw + f * WrapAngle(b.centre.yaw - a.centre.yaw);
  const double cx = b.centre.x - a.centre.x, cy = b.centre.y - a.centre.y;
  const double chord = std::hypot(cx, cy);
  const double alpha = chord > 0.0 ? WrapAngle(std::atan2(cy, cx) - a.centre.yaw) : 0.0;
  if (std::fabs(alpha) < 1e-9 || std::fabs(alpha) > kMaxArcRad) {
    m.centre.x = a.centre.x + f * cx;
    m.centre.y = a.centre.y + f * cy;
    return m;
  }
  // Radius (signed: left turns positive) of the arc tangent to a's heading through b's centre.
  const double r = chord / (2.0 * std::sin(alpha));
  const double ox = a.centre.x - r * std::sin(a.centre.yaw);
  const double oy = a.centre.y + r * std::cos(a.centre.yaw);
  const double turn = f * 2.0 * alpha;
  const double px = a.centre.x - ox, py = a.centre.y - oy;
  m.centre.x = ox + px * std::cos(turn) - py * std::sin(turn);
  m.centre.y = oy + px * std::sin(turn) + py * std::cos(turn);
  return m;
}

// Whether the two bodies, apart at the last step (a0, b0) and at this one (a1, b1), overlap
// somewhere in between, both moved evenly (Between) over dt seconds: tested at substeps short
// enough that neither body's corners move much more than 0.1 m relative to the other's
// between two of them.
bool PassThrough(const Body& a0, const Body& a1, const Body& b0, const Body& b1, double dt) {
  constexpr double kSubstepM = 0.1;
  const double ra = std::hypot(a0.half_length, a0.half_width);
  const double rb = std::hypot(b0.half_length, b0.half_width);
  // Centres that stay farther apart than the bounding circles' radii cannot overlap, whatever
  // the headings: along the chords the relative motion is a straight line, and an arc
  // (Between) strays from its chord by at most chord x tan(22.5 deg) / 2.
  const double dx0 = b0.centre.x - a0.centre.x, dy0 = b0.centre.y - a0.centre.y;
  const double ux = (b1.centre.x - a1.centre.x) - dx0, uy = (b1.centre.y - a1.centre.y) - dy0;
  const double uu = ux * ux + uy * uy;
  const double closest = uu > 0.0 ? std::clamp(-(dx0 * ux + dy0 * uy) / uu, 0.0, 1.0) : 0.0;
  const double bulge =
      0.21 * (std::hypot(a1.centre.x - a0.centre.x, a1.centre.y - a0.centre.y) +
              std::hypot(b1.centre.x - b0.centre.x, b1.centre.y - b0.centre.y));
  if (std::hypot(dx0 + closest * ux, dy0 + closest * uy) > ra + rb + bulge) return false;
  // In contact at the last step (an overlap, reported then), or a jump: not a pass-through.
  if (Overlap(a0, b0) || !Moved(a0, a1, dt) || !Moved(b0, b1, dt)) return false;
  const double move = std::hypot((a1.centre.x - a0.centre.x) - (b1.centre.x - b0.centre.x),
                                 (a1.centre.y - a0.centre.y) - (b1.centre.y - b0.centre.y)) +
                      ra * std::fabs(WrapAngle(a1.centre.yaw - a0.centre.yaw)) +
                      rb * std::fabs(WrapAngle(b1.centre.yaw - b0.centre.yaw));
  const int n = std::min(1000, static_cast<int>(std::ceil(move / kSubstepM)));
  for (int i = 1; i < n; ++i) {
    const double f = static_cast<double>(i) / n;
    if (Overlap(Between(a0, a1, f), Between(b0, b1, f))) return true;
  }
  return false;
}

}  // namespace

const char* CriticalEventName(CriticalEvent::Kind kind) {
  switch (kind) {
    case CriticalEvent::Kind::kOverlap:
      return "overlap";
    case CriticalEvent::Kind::kHardBraking:
      return "hard-braking";
    case CriticalEvent::Kind::kPassThrough:
      return "pass-through";
  }
  return "?";
}

std::vector<CriticalEvent> CriticalEventDetector::Run(double time_s, const SumoSurroundings& s) {
  std::vector<CriticalEvent> out;
  std::set<std::pair<std::string, std::string>> overlapping;
  std::set<std::string> braking;
  const double dt = time_s - last_time_s_;
  // Every object's body now and, where it was placed at the last step, then (one look-up per
  // object, not per pair).
  const size_t n = s.objects.size();
  std::vector<Body> now(n);
  std::vector<char> placed(n);
  std::vector<const Body*> before(n, nullptr);
  for (size_t i = 0; i < n; ++i) {
    now[i] = BodyOf(s.objects[i]);
    placed[i] = Placed(now[i]);
    const auto it = last_.find(s.objects[i].id);
    if (it != last_.end()) before[i] = &it->second;
  }
  for (const SumoSurroundings::Ego& e : s.egos) {
    const SumoObject& ego = s.objects[e.self];
    const double decel = -ego.accel_mps2;
    if (std::isfinite(decel) && ego.decel_mps2 > 0.0 &&
        decel > ego.decel_mps2 + kHardBrakingMarginMps2) {
      braking.insert(ego.id);
      if (!braking_.count(ego.id))
        out.push_back({time_s, ego.id, CriticalEvent::Kind::kHardBraking, "", decel});
    }
    if (!placed[e.self]) continue;
    const Body& body = now[e.self];
    const double speed = std::isnan(ego.speed_mps) ? ego.speed_mps : std::max(0.0, ego.speed_mps);
    for (int k : e.nearby) {
      if (k == e.self || !placed[k]) continue;
      const SumoObject& o = s.objects[k];
      const Body& other = now[k];
      if (!Overlap(body, other)) {
        // Apart now: did they pass through each other since the last step?
        const Body *e0 = before[e.self], *o0 = before[k];
        if (e0 && o0 && PassThrough(*e0, body, *o0, other, dt))
          out.push_back({time_s, ego.id, CriticalEvent::Kind::kPassThrough, o.id, speed});
        continue;
      }
      std::pair<std::string, std::string> pair{ego.id, o.id};
      if (!overlapping_.count(pair))
        out.push_back({time_s, ego.id, CriticalEvent::Kind::kOverlap, o.id, speed});
      overlapping.insert(std::move(pair));
    }
  }
  overlapping_.swap(overlapping);
  braking_.swap(braking);
  last_.clear();
  for (size_t i = 0; i < n; ++i) {
    if (placed[i]) last_.emplace(s.objects[i].id, now[i]);
  }
  last_time_s_ = time_s;
  return out;
}

}  // namespace criticality::plugin
