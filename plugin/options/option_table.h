#pragma once
// The table of sumo-criticality's options (what --help lists), bound to where each value goes:
// straight into DriverOptions where the types match, into RawOptions where a text or a switch
// still has to be interpreted (plugin/options/driver_options.cc).
#include <boost/program_options.hpp>
#include <string>
#include <vector>

#include "plugin/options/driver_options.h"

namespace criticality::plugin {

/** Values parsed as given, interpreted after parsing. */
struct RawOptions {
  std::string config;  ///< --config FILE
  std::string act{"warn"};
  std::string backend{"cpu"};
  std::string warn_on{"p_collision"};
  std::string expect;
  std::string preset{"default"};
  std::vector<std::string> events;
  std::string ego_classes;  ///< --ego-classes ("": the default)
  bool no_lateral_controller{false}, no_road_model{false}, no_car_following{false},
      no_lane_fit_check{false}, lane_corners{false}, no_lane_heading_yaw_rate{false},
      no_straight_by_fit{false}, no_hand_back_check{false}, lane_change_target{false},
      no_lane_change_yaw_rate{false}, lane_corner_in_turn{false}, no_expected_accel_at_once{false},
      no_stop_at_once{false}, no_hold_line{false};
  bool no_progress{false}, no_shortcut{false}, no_crossing_obligations{false},
      no_crossing_stops{false}, no_yield_stops{false}, no_heading_hold{false},
      no_way_heading{false}, junction_shapes{false}, no_junction_shapes{false}, bent_bodies{false},
      bodies_on_path{false}, no_sumo_box{false}, no_junction_ways{false}, way_lateral_paths{false},
      ego_on_way{false}, release_braking{false}, no_world_step_collisions{false},
      euler_stops{false}, junction_chord_heading{false}, no_junction_chord_heading{false},
      ego_stops{false}, internal_junction_yield{false},
      no_internal_junction_yield{false}, no_simd{false}, no_pipeline{false};
};

/** Not copyable or movable: the table points into `raw` and the options it was built for. */
class OptionTable {
 public:
  explicit OptionTable(DriverOptions* options);
  OptionTable(const OptionTable&) = delete;
  OptionTable& operator=(const OptionTable&) = delete;
  const boost::program_options::options_description& all() const { return all_; }
  RawOptions raw;

 private:
  void General();
  void Simulation(DriverOptions* o);
  void Acting(DriverOptions* o);
  void Estimator(DriverOptions* o);
  void ModelChoices();  ///< the driver's and estimator's own rules: ablations, experiments
  /** ModelChoices' rules on how lanes are sampled and followed. */
  void LaneChoices(boost::program_options::options_description* m);
  /** ModelChoices' rules on the headings vehicles are read with. */
  void HeadingChoices(boost::program_options::options_description* m);
  /** ModelChoices' rules on SUMO's steps (its Euler position update, where it looks). */
  void WorldStepChoices(boost::program_options::options_description* m);
  void Output(DriverOptions* o);

  boost::program_options::options_description all_;
};

/** --help's text. */
std::string HelpText(const OptionTable& table);

}  // namespace criticality::plugin
