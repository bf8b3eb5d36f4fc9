#pragma once
// The road network as the stages read it: lanes (shape, width, length, edge, index), the links
// between them, which vehicle classes a lane allows, and the edges. Read-only; answers are the
// network's as SUMO loaded it, so they may be cached (each answer is one round trip under
// --connect). The SUMO adapter implements it (plugin/sumo/sumo_world.h); tests use an
// in-memory network (tests/plugin/fake_sumo_world.h). No SUMO types.
#include <string>
#include <vector>

#include "criticality/scene.h"

namespace criticality::plugin {

/** One lane of the network. */
struct LaneInfo {
  std::vector<Point2> shape;  ///< centre line in driving direction (network coordinates)
  double width_m{3.2};
  double length_m{0.0};  ///< SUMO's lane length (lane positions run along it)
  std::string edge;
  int index{0};  ///< 0 = rightmost
};

/** A link from a lane to a lane of the next edge (SUMO's TraCIConnection). */
struct LaneLink {
  std::string lane;      ///< the lane it leads to (approachedLane)
  std::string internal;  ///< the junction's internal lane it runs through ("" when none)
  /** SUMO's link state: 'G' priority green, 'g' green without priority, 'r' red, 'y' yellow,
   *  'u' red-yellow, 's' stop sign, 'w' all-way stop, 'm' minor, '=' equal, ... */
  std::string state;
  bool has_foe{false};  ///< a foe approaches the link now (only meaningful when read now)
  /** SUMO's direction of the link: 's' straight, 'l' left, 'r' right, 'L' partly left, 'R'
   *  partly right, 't' turnaround, "" unknown. */
  std::string direction{"s"};
};

class RoadNetwork {
 public:
  virtual ~RoadNetwork() = default;
  /** The lane `id`; an unknown lane is an error of the implementation (SumoError). */
  virtual const LaneInfo& Lane(const std::string& id) = 0;
  /** The lane's links as first read (states and has_foe of that moment: topology only). */
  virtual const std::vector<LaneLink>& Links(const std::string& lane) = 0;
  /** The lane's links read now: has_foe and state of this step. */
  virtual std::vector<LaneLink> LinksNow(const std::string& lane) = 0;
  /** The vehicle classes the lane allows; empty: every class. */
  virtual const std::vector<std::string>& AllowedClasses(const std::string& lane) = 0;
  /** Lanes of an edge. */
  virtual int LaneCount(const std::string& edge) = 0;
  /** Every edge of the network, internal ones (":...") included. */
  virtual std::vector<std::string> Edges() = 0;
};

/** Internal lanes and edges (inside a junction) have IDs that start with ':'. */
inline bool IsInternal(const std::string& id) { return !id.empty() && id[0] == ':'; }

/** A lane position (SUMO's, along its lane length) as a distance along the lane's shape: the
 *  two lengths differ where netconvert smoothed the lane, and SUMO scales one onto the other. */
double OnShape(const LaneInfo& lane, double lane_position_m);

/** Normal lanes whose SUMO length differs from their drawn shape's by more than
 *  kLengthOffShapeShare (and 1 m): a network with explicit edge lengths. SUMO moves vehicles
 *  by the length, so on such a lane they cover a different distance in x/y than their speed
 *  says, while the estimator predicts in x/y at that speed. `worst`: the lane whose ratio of
 *  length to shape is farthest from 1. */
struct LanesOffShape {
  int lanes{0};
  std::string worst;
  double worst_length_m{0.0}, worst_shape_m{0.0};
};
constexpr double kLengthOffShapeShare = 0.1;
LanesOffShape LanesWithLengthOffShape(RoadNetwork& network);

/** Whether `vclass` may use `lane`. */
bool Allows(RoadNetwork& network, const std::string& lane, const std::string& vclass);

/** Whether only pedestrians may use `lane` (a sidewalk, walking area or crossing). */
bool PedestriansOnly(RoadNetwork& network, const std::string& lane);

/** A junction's internal lanes from a link on, in driving order: the link's own, then on while
 *  the next one is internal too (a turn that an internal junction splits runs through two).
 *  Empty when the link has none. */
std::vector<std::string> InternalChain(RoadNetwork& network, const LaneLink& link);

/** The internal lanes (InternalChain) of the link from lane `from` to lane `to`, which
 *  getLinks names by the lane after the junction; empty when no link leads there or it runs
 *  through no internal lane. */
std::vector<std::string> InternalLanesBetween(RoadNetwork& network, const std::string& from,
                                              const std::string& to);

/** The lane a vehicle on `lane` drives onto next: inside a junction the one lane its internal
 *  lane leads to; otherwise a link to the next edge of `route` after `lane`'s edge (searched
 *  from *route_index on, which is advanced to that edge). "" when the route ends here or no
 *  link leads on. */
std::string NextLaneOnRoute(RoadNetwork& network, const std::string& lane,
                            const std::vector<std::string>& route, int* route_index);

/** SUMO's turn signals (getSignals bits 0 and 1), as a vehicle shows them. */
enum class Blinker { kNone, kLeft, kRight };

/** The lane a vehicle on `lane` drives onto next, judged only from what can be seen
 *  (--observable-only, no route): inside a junction the one lane its internal lane leads to;
 *  at a lane's end, among the links its class may use, the one its blinker points to (a left
 *  turn, else a partial left; likewise right), else straight on (straight, then partly left or
 *  right), else the first link. "" when no link leads on. */
std::string NextLaneSeen(RoadNetwork& network, const std::string& lane, const std::string& vclass,
                         Blinker blinker);

}  // namespace criticality::plugin
