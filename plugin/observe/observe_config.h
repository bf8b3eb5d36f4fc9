#pragma once
// What the observe stage needs to know: which vehicles are egos and how far around them to
// read.
#include <functional>
#include <string>
#include <vector>

namespace criticality::plugin {

struct ObserveConfig {
  std::vector<std::string> egos;  ///< --ego (named egos), in the order given
  bool all_vehicles{false};       ///< --all-vehicles: every vehicle present is an ego
  /** With all_vehicles: whether a SUMO vClass is one of the egos' (--ego-classes); the
   *  vehicles of other classes get no ego events. Empty: every class. */
  std::function<bool(const std::string& vehicle_class)> ego_class;
  /** --range: objects whose centre lies within this distance of an ego's are in its scene
   *  (the scenes stage applies it exactly; reading reaches further, kReadMarginM). */
  double range_m{80.0};
  /** --connect: SUMO runs elsewhere, another client may still add a named ego later, and egos
   *  may have departed before the run attached. */
  bool attached{false};
};

/** How much further than the range objects are read: SUMO measures context ranges between
 *  positions (front bumpers), half a length off the centre for the ego and up to half of a
 *  60 m vehicle for the other. */
inline constexpr double kReadMarginM = 35.0;

}  // namespace criticality::plugin
