#include "plugin/options/option_table.h"

#include <cstdio>
#include <sstream>

namespace po = boost::program_options;

namespace criticality::plugin {
namespace {

// A number as --help shows its default: 0.9, not 0.90000000000000002.
std::string Shown(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

template <typename T>
po::typed_value<T>* Value(T* target) {
  return po::value(target)->default_value(*target, Shown(*target));
}

}  // namespace

OptionTable::OptionTable(DriverOptions* o) {
  General();
  Simulation(o);
  Acting(o);
  Estimator(o);
  ModelChoices();
  Output(o);
}

void OptionTable::General() {
  po::options_description g("General");
  g.add_options()("help,h", "show this help and exit")(
      "version", "show the version (and the SUMO it was built for) and exit")(
      "check-options",
      "check every option as a run would (values, the --config file, that the SUMO "
      "configuration exists) and exit: 0 and 'options ok' when a run would start with them, "
      "else the run's error and exit code; SUMO's own options (after '--') are not checked")(
      "config", po::value(&raw.config),
      "read further options from FILE (same names, one 'name = value' per line; a scenario's "
      "scenario.cfg). Paths in it are relative to its folder. Command-line values win.");
  all_.add(g);
}

void OptionTable::Simulation(DriverOptions* o) {
  po::options_description s("Simulation");
  s.add_options()("sumo-config,c", po::value(&o->run.sumo_config),
                  "SUMO configuration (.sumocfg) to run in-process (libsumo)")(
      "connect", po::value(&o->run.connect),
      "HOST:PORT of a SUMO or sumo-gui already running with --remote-port PORT; attach to it "
      "through libtraci instead of running SUMO in-process")(
      "ego", po::value(&o->observe.egos)->composing(),
      "vehicle ID whose criticality is estimated (repeatable)")(
      "all-vehicles", po::bool_switch(&o->observe.all_vehicles),
      "every vehicle present is an ego (but parked ones; of the --ego-classes)")(
      "ego-classes", po::value(&raw.ego_classes),
      "with --all-vehicles, the SUMO vClasses that are egos, comma-separated, or all (default: "
      "every road user but rail: cars, trucks, buses, motorcycles, bicycles, ...; persons are "
      "never egos, 'pedestrian' names vehicles of that vClass)")(
      "event", po::value(&raw.events)->composing(),
      "scripted event 'TIME TARGET ACTION ARGS' (repeatable; usually in a scenario.cfg). ACTION: "
      "speed-mode VEH BITS | lane-change-mode VEH BITS | speed VEH MPS | slow-down VEH MPS SEC | "
      "lane-change VEH INDEX SEC | param VEH KEY VALUE | person-speed PERSON MPS")(
      "end", po::value(&o->run.end_time_s)->default_value(-1.0, "when SUMO ends"),
      "stop at this simulated time (s)")(
      "expect", po::value(&raw.expect),
      "scenario expectation, reported in the summary: collision | no-collision")(
      "expect-partner", po::value(&o->run.expect_partner),
      "scenario expectation: ID of the vehicle or person the ego collides with")(
      "quiet-until", Value(&o->run.quiet_until_s),
      "scenario metadata: end of the quiet phase (s); a warning that starts earlier is a false "
      "alarm")("category", po::value(&o->run.category),
               "scenario metadata for evaluations: static-object, moving-object, pedestrian or "
               "free (collision-free)");
  all_.add(s);
}

void OptionTable::Acting(DriverOptions* o) {
  WarningConfig& w = o->act.warning;
  AvoidancePolicyConfig& p = o->act.closed_loop.policy;
  po::options_description a("Acting on the estimate");
  a.add_options()(
      "act", po::value(&raw.act)->default_value(raw.act),
      "none: only record; warn: record warning episodes, publish the criticality as vehicle "
      "parameter 'criticality' and colour the ego red while warning; brake: warn and also take "
      "control (plugin/README.md, Closed loop): from p >= brake threshold follow the best "
      "escape route (its braking, and its lane change unless --no-steer), never braking less "
      "than SUMO would; hand control back after --act-hold once p stays below --brake-release "
      "for --act-release-after")(
      "warn-on", po::value(&raw.warn_on)->default_value(raw.warn_on),
      "the estimate the warning reads: p_collision (the paper's p_cra: the probability that the "
      "scene ends in a collision of the ego, over all its hypotheses), p_reference (if the ego "
      "keeps its most probable course) or unavoidability (the least colliding ego hypothesis: 1 "
      "= nothing helps)")("warn-threshold", Value(&w.threshold),
                          "value of the --warn-on estimate that starts a warning episode")(
      "warn-release", po::value(&w.release)->default_value(-1.0, "0.8 x warn threshold"),
      "value below which a warning episode ends (hysteresis)")(
      "warn-release-after", Value(&w.release_after_s),
      "seconds the estimate must stay below --warn-release before the episode ends (a one-step "
      "dip does not split a warning; 0: end at the first step below)")(
      "brake-threshold", Value(&p.engage_threshold),
      "value of the --warn-on estimate at which --act brake takes control")(
      "brake-release",
      po::value(&p.release_threshold)->default_value(-1.0, "0.5 x brake threshold"),
      "value of the --warn-on estimate below which --act brake may hand control back "
      "(hysteresis)")("act-hold", Value(&p.min_hold_s),
                      "seconds --act brake keeps control at least, whatever the estimate")(
      "act-release-after", Value(&p.release_after_s),
      "seconds the estimate must stay below --brake-release before control is handed back")(
      "no-steer", po::bool_switch(&o->act.closed_loop.no_steer),
      "--act brake only brakes: follows the best escape route that keeps its lane")(
      "no-hand-back-check", po::bool_switch(&raw.no_hand_back_check),
      "ablation (ours): --act brake hands control back once the estimate is low; by default "
      "it also re-estimates the scene with the ego as SUMO would drive it after the hand-back, "
      "and waits while that is at or above --brake-release");
  all_.add(a);
}

void OptionTable::Estimator(DriverOptions* o) {
  Params& p = o->params;
  po::options_description e("Estimator");
  e.add_options()("backend", po::value(&raw.backend)->default_value(raw.backend),
                  "reference | cpu | cuda | auto (cuda when a GPU is usable, else cpu)")(
      "preset", po::value(&raw.preset)->default_value(raw.preset),
      "estimator parameters to start from: default (drivable hypotheses, naturalistic scores) "
      "or paper-literal (the paper's models and our first scoring, for comparisons; "
      "plugin/README.md says which of the driver's own choices stay on); the options below "
      "change them further")(
      "no-lateral-controller", po::bool_switch(&raw.no_lateral_controller),
      "ablation (paper Sec. V-A): no lateral controller, constant open-loop steering per path "
      "section, so hypotheses may leave the road")(
      "no-road-model", po::bool_switch(&raw.no_road_model),
      "ablation (paper Sec. V-A): ignore SUMO's lanes; every vehicle gets virtual lanes along "
      "its heading")(
      "observable-only", po::bool_switch(&o->scenes.observable_only),
      "scenes hold only what the vehicles' sensors could know (positions, speeds, headings, "
      "sizes, classes, lane geometry, signals, turn signals): each vehicle's way on is its "
      "blinker's or straight on, not its route; no route ends, no pedestrians' next edges, a "
      "class's limits instead of its vType's (plugin/README.md, \"Observable-only inputs\")")(
      "threads", po::value(&o->estimator.threads)->default_value(0, "0 = all cores"),
      "estimator threads; 0: all cores, but with named egos and the pipelined driver (--act "
      "none or warn) all but one, which SUMO's step takes")(
      "no-pipeline", po::bool_switch(&raw.no_pipeline),
      "estimate each step before SUMO makes the next; by default, under --act none and warn, "
      "step k is estimated on a thread of its own while SUMO makes step k+1 (the same results, "
      "the criticality published to SUMO one step later; --act brake always waits)")(
      "profiles", Value(&p.profiles), "acceleration/slip profiles per object (paper: 6 or 5)")(
      "own-lane-samples", Value(&p.own_lane_samples),
      "lateral path samples across the own lane (paper: 3)")(
      "neighbour-lane-samples", Value(&p.neighbour_lane_samples),
      "lateral path samples across each neighbouring lane (paper: 2); ego paths = samples^3")(
      "horizon", Value(&p.horizon_s),
      "prediction horizon (s); the path sample instants (paper: 1.0, 1.5, 2.0 s of 2 s) scale "
      "with it")("step", Value(&p.step_s),
                  "the estimator's prediction step (s; not SUMO's --step-length, which goes "
                  "after '--')")(
      "range", Value(&o->observe.range_m),
      "vehicles and pedestrians within this distance of an ego are considered (m)")(
      "accel-window", Value(&o->scenes.accel_window_s),
      "experimental (ours, 0 = off by default: it lowers the flicker of p at 0.1 s steps but "
      "did not lower the held-out false alarms, bench/RESULTS.md): a vehicle's acceleration is "
      "its speed change over this time (s), the mean of SUMO's per-step accelerations within "
      "it, which SUMO's driver imperfection makes jump from step to step at short steps; a "
      "window no longer than SUMO's step: the last step's (plugin/README.md, \"Acceleration\")")(
      "no-simd", po::bool_switch(&raw.no_simd),
      "cpu backend: the scalar fast path instead of SIMD lanes (the same pair matrix as the "
      "plain reference, bit for bit; SIMD differs at most in contacts within 1 mm)")(
      "no-reach-shortcut", po::bool_switch(&raw.no_shortcut),
      "estimate objects that cannot reach the ego within the horizon, and egos with no object "
      "in reach, in full (the exact shortcut changes no result; this is for checking that)");
  all_.add(e);
}

void OptionTable::ModelChoices() {
  po::options_description m("Model choices (ours; estimator/ALGORITHM.md, plugin/README.md)");
  m.add_options()(
      "no-crossing-obligations", po::bool_switch(&raw.no_crossing_obligations),
      "ablation (ours): a pedestrian at a crossing it may not enter yet (red, or no priority "
      "while a vehicle approaches) is not read as waiting on the footway; the rule reads the "
      "person's next edge, which only the simulator knows (plugin/README.md, \"Pedestrians "
      "on the footway\")")(
      "no-crossing-stops", po::bool_switch(&raw.no_crossing_stops),
      "ablation (ours): such a waiting pedestrian keeps its speed in its reference hypothesis "
      "instead of stopping where the crossing begins, as SUMO's persons do (simulator "
      "knowledge too: plugin/README.md, \"Pedestrians on the footway\")")(
      "no-yield-stops", po::bool_switch(&raw.no_yield_stops),
      "experiment: no yield line for a vehicle at a link without priority while SUMO has a foe "
      "approaching it (simulator knowledge: the link's has_foe); stop signs, red and yellow "
      "lights stay")(
      "no-lane-heading-yaw-rate", po::bool_switch(&raw.no_lane_heading_yaw_rate),
      "ablation (ours): at steps up to 0.25 s take every vehicle's yaw rate from its last "
      "step's heading change (0 or a spike along a junction's lane of straight pieces); by "
      "default a vehicle whose heading is SUMO's along its lanes (from its back to its front "
      "on them) turns as that heading turns around its front at its speed (plugin/README.md, "
      "\"Yaw rate\")")(
      "lane-change-target", po::bool_switch(&raw.lane_change_target),
      "experimental (ours, off by default): a vehicle seen changing lanes over time "
      "(lanechange.duration > 0, the sublane model: its blinker, its front off its lane's "
      "centre and its heading turned that way) is taken as on the lane it moves into; by "
      "default its own lane until SUMO moves it over. More false alarms on held-out sublane "
      "grids (plugin/README.md, \"Lane changes\")")(
      "no-lane-change-yaw-rate", po::bool_switch(&raw.no_lane_change_yaw_rate),
      "ablation (ours): with continuous lane changes a vehicle SUMO moves sideways along its "
      "lane turns as its heading changed since the last step; by default at its lane's yaw "
      "rate, as SUMO's heading jumps when such a move begins or ends (plugin/README.md, "
      "\"Lane changes\")")(
      "no-junction-shapes", po::bool_switch(&raw.no_junction_shapes),
      "ablation (ours): draw the lanes ahead through a junction as the straight chord from the "
      "lane's end to the next lane's start (by default along the junction's internal lanes, "
      "the turn SUMO drives: plugin/README.md)")(
      "junction-shapes", po::bool_switch(&raw.junction_shapes),
      "the default since 2026-12-05 (lanes through a junction along its internal lanes); "
      "accepted so that older campaign files still run")(
      "no-junction-ways", po::bool_switch(&raw.no_junction_ways),
      "ablation (ours): a vehicle whose body is in a junction is predicted like any other, "
      "steering after its lanes; by default it moves along its way through the junction as "
      "SUMO moves it, front and back on its lanes (estimator Params::bodies_on_way)")(
      "way-lateral-paths", po::bool_switch(&raw.way_lateral_paths),
      "experimental (ours, off by default: it lost warned overlaps on the held-out networks, "
      "bench/RESULTS.md): a vehicle moving along its way through a junction gets the lateral "
      "samples of its lanes as paths beside its way; by default it has one path, on its way "
      "(estimator Params::way_lateral_paths)")(
      "ego-on-way", po::bool_switch(&raw.ego_on_way),
      "experimental (ours, off by default: fewer false alarms but warned collisions lost on "
      "the held-out networks, bench/RESULTS.md): an ego whose body is in a junction moves "
      "along its way as other vehicles do, on one path (with --way-lateral-paths: its path "
      "tree's sections as offsets beside the way; estimator Params::ego_on_way)")(
      "no-sumo-box", po::bool_switch(&raw.no_sumo_box),
      "ablation (ours): a vehicle's box is its length from its front along SUMO's angle, "
      "reaching past its back in a tight turn; by default it is SUMO's box, from its front to "
      "its back on its way, shorter than the vehicle where that way bends")(
      "bodies-on-path", po::bool_switch(&raw.bodies_on_path),
      "experimental (ours, off by default: it did not help the held-out networks as a whole, "
      "bench/RESULTS.md): every vehicle of one box (no carriages) is SUMO's box of it (front to "
      "back), predicted in a "
      "turn centred on the chord of its path, not on the path, where its outer corners stand "
      "out of its lane (plugin/README.md, \"Bodies in a turn\")")(
      "bent-bodies", po::bool_switch(&raw.bent_bodies),
      "experimental (ours, off by default: it did not help the held-out networks, "
      "bench/RESULTS.md): a vehicle whose way from back to front a turn bends (a bus or truck "
      "in a junction turn) is a chain of boxes along that way, not one box along SUMO's angle "
      "(plugin/README.md, \"Bodies in a turn\")")(
      "internal-junction-yield", po::bool_switch(&raw.internal_junction_yield),
      "the default, kept so that older campaign files still run: a vehicle that must yield "
      "where its turn waits inside the junction (SUMO's internal junction, e.g. a left turn "
      "across oncoming traffic) gets its yield line there, not at the junction's entry")(
      "no-internal-junction-yield", po::bool_switch(&raw.no_internal_junction_yield),
      "ablation (ours): such a vehicle's yield line stays at the junction's entry, although "
      "SUMO lets it drive in and wait at its internal junction")(
      "ego-stops", po::bool_switch(&raw.ego_stops),
      "experimental (ours, off by default): an ego that must stop ahead (a red or yellow light, "
      "a stop sign, a yield line while a foe approaches) and can do so comfortably is expected "
      "to: its reference stops at the line (estimator Params::ego_stop_obligations)")(
      "release-braking", po::bool_switch(&raw.release_braking),
      "experimental (ours, off by default): a vehicle (the ego too) that brakes harder than its "
      "leader, its stop line and its lane's curve ask is expected to release its brake (its "
      "reference holds its speed, or what those ask) instead of braking on for the whole "
      "horizon (estimator Params::release_unexplained_braking)")(
      "no-expected-accel-at-once", po::bool_switch(&raw.no_expected_accel_at_once),
      "ablation (ours): another vehicle's hypotheses hold its current acceleration through "
      "the reaction latency also where its expected (car-following) acceleration is lower; by "
      "default they start from the expected one, as SUMO's drivers act in their next step "
      "(the ego keeps its latency; estimator Params::expected_accel_at_once; reads SUMO's "
      "driver model)")(
      "no-stop-at-once", po::bool_switch(&raw.no_stop_at_once),
      "ablation (ours): another vehicle with a credible stop line (a red light, a yield line "
      "with a foe) holds its current acceleration through the reaction latency and counts as "
      "complying only while 3.4 m/s^2 stops it; by default it brakes for the line from now, "
      "up to its type's decel, as SUMO's drivers do (the ego keeps its latency; estimator "
      "Params::stop_obligation_at_once; reads SUMO's driver model)")(
      "no-car-following", po::bool_switch(&raw.no_car_following),
      "ablation (ours): the reference hypothesis keeps the current acceleration (the paper's) "
      "instead of the braking each vehicle's leader asks for (estimator/ALGORITHM.md)");
  LaneChoices(&m);
  HeadingChoices(&m);
  WorldStepChoices(&m);
  all_.add(m);
}

void OptionTable::HeadingChoices(po::options_description* m) {
  m->add_options()(
      "no-heading-hold", po::bool_switch(&raw.no_heading_hold),
      "ablation (ours): take every vehicle's heading as SUMO reports it, also where it turns "
      "faster than the vehicle can between two steps (at a junction's corners; by default "
      "held up to 0.5 s: plugin/README.md, \"Headings\")")(
      "no-way-heading", po::bool_switch(&raw.no_way_heading),
      "ablation (ours): take SUMO's angle also just after a lane change past a junction, where "
      "it points from the body's back, still on the old lane, to its front in the new one (by "
      "default the heading of the way behind the new lane: plugin/README.md, \"Headings\")")(
      "no-junction-chord-heading", po::bool_switch(&raw.no_junction_chord_heading),
      "ablation (ours): read a vehicle whose body is in a junction with SUMO's angle (of the "
      "internal lane's piece at its front, which jumps at the piece's corners) or the heading "
      "held over such a jump; by default with its lanes' chord from its back to its front, as "
      "SUMO places the body (plugin/README.md, \"Headings\")")(
      "junction-chord-heading", po::bool_switch(&raw.junction_chord_heading),
      "the default since 2026-12-08; accepted so that campaign files of the experiment run");
}

void OptionTable::WorldStepChoices(po::options_description* m) {
  m->add_options()(
      "no-world-step-collisions", po::bool_switch(&raw.no_world_step_collisions),
      "ablation (ours): a pair of hypotheses collides wherever it overlaps, not only at SUMO's "
      "steps, where SUMO looks for collisions (by default, with SUMO's Euler position update, "
      "the estimator reads SUMO's step length for this; estimator "
      "Params::collisions_at_world_steps)")(
      "euler-stops", po::bool_switch(&raw.euler_stops),
      "experimental (ours, off by default: no gain on the held-out networks, bench/RESULTS.md): "
      "a hypothesis whose speed is 0 at one of SUMO's steps "
      "stays where SUMO's previous step left it, as SUMO's Euler update leaves a vehicle that "
      "stops within a step (by default it is put half a step's speed change back, which for a "
      "stop inside a step lies behind that place; estimator Params::euler_stops)");
}

void OptionTable::LaneChoices(po::options_description* m) {
  m->add_options()(
      "no-lane-fit-check", po::bool_switch(&raw.no_lane_fit_check),
      "ablation (ours): use a lane's three samples over the full reach even where the parabola "
      "through them leaves the lane between them (by default such a lane is sampled over a "
      "shorter reach; estimator Params::lane_fit_within_lane)")(
      "no-straight-by-fit", po::bool_switch(&raw.no_straight_by_fit),
      "ablation (ours): where a straight of 2 to 15 m (and half a second of the vehicle's "
      "travel) leads into a turn, take the middle samples at the middle of the reach; by "
      "default they go to the straight's end instead where that fit keeps closer to the road "
      "(estimator Params::straight_before_turn_by_fit)")(
      "no-hold-line", po::bool_switch(&raw.no_hold_line),
      "ablation (ours): every vehicle heads for its lane's centre (the paper); by default a "
      "vehicle at most a third of its lane's width wide (a bicycle in a car lane) holds the line "
      "it rides in its lane (estimator Params::hold_line_max_width_share)")(
      "lane-corners", po::bool_switch(&raw.lane_corners),
      "experimental (ours, off by default): a lane that turns by 15 degrees or more over its "
      "sampled reach is sent as a corner (straight, a parabola tangent to both straights, "
      "straight) instead of three samples on it (estimator Params::lane_corners)")(
      "lane-corner-in-turn", po::bool_switch(&raw.lane_corner_in_turn),
      "experimental (ours, off by default): a vehicle in a junction turn too tight for its "
      "lane's three samples (the inner divider folds back) gets its lanes as a corner from "
      "where it is instead of none (a virtual lane) (estimator Params::lane_corner_in_turn)");
}

void OptionTable::Output(DriverOptions* o) {
  po::options_description out("Output");
  out.add_options()("output", po::value(&o->run.output),
                    "results database (SQLite) to create; must not exist")(
      "record-scenes", po::value(&o->record.scene_folder),
      "write every estimated scene to DIR as a scene file that 'criticality-bench --scene-file' "
      "replays without SUMO")("no-progress", po::bool_switch(&raw.no_progress),
                              "no progress line even on a terminal");
  all_.add(out);
}

std::string HelpText(const OptionTable& table) {
  std::ostringstream o;
  o << "sumo-criticality: runs SUMO and estimates, every step, each ego's collision "
       "probability with the multi-hypothesis algorithm; records steps, warnings, "
       "actions and SUMO's collisions in SQLite.\n\n"
       "Usage: sumo-criticality -c scenario.sumocfg --ego ego0 --act warn --output "
       "run.sqlite [-- SUMO options]\n"
       "       sumo-criticality --config scenarios/rear_end/scenario.cfg --output "
       "run.sqlite\n"
    << table.all()
    << "\nThe last line of standard output, on every exit, is a JSON summary. Exit "
       "codes: 0 done, 1 internal error, 2 bad options or input, 3 SUMO error, 4 results "
       "could not be written, 5 ego error (a named ego SUMO never loads, or a person), 130 "
       "interrupted (SIGINT), 143 terminated (SIGTERM).\n";
  return o.str();
}

}  // namespace criticality::plugin
