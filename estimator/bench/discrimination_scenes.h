#pragma once
// The discrimination benchmark's scenes: designed traffic situations, each labelled safe-close
// (ordinary close traffic that does not lead to a collision unless someone does something
// unusual) or critical (a collision follows if everyone keeps their current motion). Does p
// separate them? criticality-bench --discrimination prints every output per scene;
// tests/estimator/discrimination_test.cc asserts the separation.
//
// Conventions: the ego drives along +x from the origin; lanes are 3.5 m wide and straight;
// cars are 5.0 m x 1.8 m; distances between vehicles are bumper-to-bumper gaps, so that a
// time to collision is gap / closing speed. Other vehicles use the ego's lanes seen from their
// frame (association by centre of gravity) unless they drive on another road (crossing
// traffic), where they carry their own lanes.
#include <string>
#include <vector>

#include "criticality/scene.h"

namespace criticality::bench {

struct DiscriminationScene {
  std::string name;
  bool critical{false};
  /** Time to collision if every object keeps its current motion (s); < 0 for safe-close
   *  scenes, where no collision follows. */
  double ttc_s{-1.0};
  /** Scenes of one family differ only in time to collision (p must rise as it falls); empty
   *  for single scenes. */
  std::string family;
  std::string what;
  Scene scene;
};

/** Every scene of the benchmark, safe-close and critical. */
std::vector<DiscriminationScene> DiscriminationScenes();

}  // namespace criticality::bench
