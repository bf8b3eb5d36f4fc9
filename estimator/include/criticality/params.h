#pragma once
/** @file
 * Every tunable of the algorithm, with its default and where the value comes from.
 * "paper" = Sánchez Morales et al., IV 2019 (shared/reference). Where the paper gives no value,
 * the comment names the source we used, or says "project choice" and which test shows its effect.
 */
#include <cstdint>
#include <string>
#include <vector>

#include "criticality/scene.h"

namespace criticality {

/** Limits and model data of one class of road user other than passenger cars (Scene.h
 *  RoadUser; Params::road_user_classes; estimator/ALGORITHM.md "Road users by class"). The
 *  longitudinal limits bound every hypothesis of a vehicle of the class where its VehicleType
 *  gives no value; the model data replace vehicle_class.h's car classes. */
struct RoadUserLimits {
  double accel_mps2{2.6};  ///< the largest acceleration (positive profiles)
  double decel_mps2{4.5};  ///< normal largest deceleration (SUMO's decel)
  /** The largest deceleration: the hardest braking profile. Where a VehicleType gives decel but
   *  no emergency_decel, the larger of its decel and this (SUMO's own default rule). */
  double emergency_decel_mps2{9.0};
  double max_speed_mps{55.6};  ///< positive profiles stop at this speed
  double mass_kg{1500.0};      ///< the model mass where the VehicleType gives none
  /** Driving power at the wheels per unit mass, W/kg (Params::power_limited_drive). */
  double power_per_mass_wpkg{60.0};
  /** Wheelbase as a share of the box length, clamped to [wheelbase_min_m, wheelbase_max_m]. */
  double wheelbase_share{0.6};
  double wheelbase_min_m{1.8};
  double wheelbase_max_m{4.0};
  /** Axle cornering stiffness per kg of vehicle mass, N/rad per axle (the one- and two-track
   *  models; scaled with mass as for cars, vehicle_class.h). */
  double cornering_stiffness_per_kg{55.0};
  /** The kinematic single-track model at every speed (no tyre model): bicycles, whose tyre
   *  dynamics mean little at 5 m/s (rail vehicles, on their track, use none). */
  bool kinematic{false};
};

struct Params {
  // --- Horizon (paper Sec. IV-C and V-B: 2 s predicted with 20 ms resolution = 100 steps) ---
  double horizon_s{2.0};
  double step_s{0.02};

  // --- Longitudinal hypotheses (paper Sec. IV-B-2a) ---
  /** Acceleration / slip profiles per object, h_acc. Paper Sec. V-B: 6 (or 5). At least 3
   *  (maximum, minimum and zero are always sampled). */
  int profiles{6};
  /** One-track (other vehicles) acceleration range, paper: -9.7..9.7 m/s^2 (about 1 g). */
  double vehicle_accel_min_mps2{-9.7};
  double vehicle_accel_max_mps2{9.7};
  /** Two-track (ego) longitudinal slip range, paper: -0.1..0.1. */
  double ego_slip_min{-0.1};
  double ego_slip_max{0.1};
  /** Actuator + driver latency before a profile starts to act. DESIGN.md: brake latency about
   *  0.15-0.3 s; we take the middle. */
  double latency_s{0.2};
  /** Build-up of acceleration after the latency (jerk limit). DESIGN.md: 20-50 m/s^3 in an
   *  emergency. The ego's slip ramps at the equivalent rate:
   *  ego_slip_max * jerk_mps3 / vehicle_accel_max_mps2 per second. */
  double jerk_mps3{30.0};

  // --- Lateral hypotheses: paths (paper Sec. IV-B-2b) ---
  /** Instants at which the lanes are sampled; each opens a new path section. Paper: 1.0, 1.5,
   *  2.0 s. 1 to 4 strictly increasing positive values. */
  std::vector<double> path_sample_times_s{1.0, 1.5, 2.0};
  /** Samples across the own lane and across each neighbouring lane (paper: 3 and 2), equally
   *  distributed over the lane width. With all three lanes: 7 samples, so 7^3 = 343 ego paths
   *  (every combination of sections) and 7 paths per other vehicle (no combination). */
  int own_lane_samples{3};
  int neighbour_lane_samples{2};
  /** Narrow vehicles hold their line: where a vehicle is at most this share of its own lane's
   *  width wide (a bicycle or a motorcycle in a car lane, with room for two more beside it; a
   *  car in a wide lane is not), the own-lane sample nearest to where
   *  it rides becomes that place (kept its half width inside the dividers), and its reference
   *  path runs there instead of along the lane's centre: a cyclist riding at the right edge is
   *  predicted to keep there, not to steer into the middle of the lane beside the car passing
   *  it. Observable: its width and its place between its lane's dividers. 0: off (the paper:
   *  every vehicle heads for its lane's centre). paper-literal: 0. Driver: --no-hold-line. */
  double hold_line_max_width_share{1.0 / 3.0};

  // --- Pedestrians (paper Sec. IV-B-3) ---
  /** Headings sampled over 0..360 deg, relative to the current heading. Paper: as many as the
   *  complete paths of a CO with three lanes (7). */
  int pedestrian_headings{7};
  /** Acceleration samples (as many as `profiles`) equally distributed over -12..12 m/s^2. */
  double pedestrian_accel_min_mps2{-12.0};
  double pedestrian_accel_max_mps2{12.0};
  /** Speed limit, paper: 2.7 m/s (slow to running, not sprinting; Zebala et al. 2012). */
  double pedestrian_max_speed_mps{2.7};
  /** kNaturalistic: a pedestrian outside the ego's lanes that stays on the footway
   *  (Pedestrian::stays_on_footway) has the lane crossings of each heading counted from none,
   *  not against its straight-on heading's: walking on along a corner's footway whose straight
   *  line would cut into the road is not read as stepping out. Project choice (SUMO's walking
   *  areas); paper-literal: off. */
  bool footway_pedestrians{true};

  // --- Lateral controller (paper Sec. IV-B-2b) ---
  /** Steering-angle limit at the front wheels. DESIGN.md: at most about 0.5 rad. */
  double max_steer_rad{0.5};
  /** Steering-rate limit at the wheels. Forkenbrock & Elsasser (NHTSA 2005): a fast human
   *  driver turns the wheel several hundred deg/s; with a ratio of 15-16 that is 0.7-1.1 rad/s
   *  at the wheels. We take 0.9 rad/s. */
  double max_steer_rate_radps{0.9};
  /** The paper's controller acts on a predicted position whose prediction time adapts to speed
   *  (values not given). Project choice: t_p = preview_s_per_mps * v clamped to
   *  [preview_min_s, preview_max_s], tuned by simulation so that a 3.5 m lane change reaches
   *  90 % in about 1.2 s at 20-40 m/s with at most a few percent overshoot, and stays damped
   *  at 5 m/s (tests/estimator/core/lateral_controller_test.cc). */
  double preview_s_per_mps{0.008};
  double preview_min_s{0.05};
  double preview_max_s{0.4};

  // --- Vehicle models ---
  /** Below this speed the one- and two-track models (singular in 1/v) are replaced by the
   *  kinematic single-track model. The seam is raised per vehicle, when needed, to the speed at
   *  which explicit Euler with step_s stays stable: v >= stability_factor * step_s *
   *  max((c_f + c_r)/m, (c_f l_f^2 + c_r l_r^2)/I_z). Project choice, tested at the seam. */
  double kinematic_below_mps{2.0};
  double euler_stability_factor{1.5};
  /** Tyre-road friction coefficient, dry asphalt about 1.0 (DESIGN.md; the paper's +-9.7 m/s^2
   *  range is about 1 g). */
  double friction{1.0};

  // --- Road users by class (Scene.h RoadUser, VehicleType; estimator/ALGORITHM.md "Road users
  // by class"). SUMO's vClass defaults: sumo.dlr.de/docs/Vehicle_Type_Parameter_Defaults.html
  // and SUMOVTypeParameter.cpp (getDefaultAccel, getDefaultDecel, getDefaultEmergencyDecel,
  // VClassDefaultValues: maxSpeed, mass), github.com/eclipse-sumo/sumo, 2025. ---
  /** With true, a vehicle's (and the ego's) VehicleType bounds its hypotheses and its class
   *  picks its model. A class other than kCar: profiles from its emergency deceleration (the
   *  VehicleType's, else the class's) up to its acceleration, never above its top speed, mass,
   *  yaw inertia, wheelbase, cornering stiffness and power of its class, bicycles and rail
   *  vehicles kinematic, rail vehicles on one path (their own lane's centre). A kCar keeps the
   *  paper's grid (vehicle_accel_min/max_mps2, positive profiles bounded by power and traction);
   *  its VehicleType's emergency deceleration only floors the samples and its top speed caps
   *  them. A kCar without VehicleType values keeps vehicle_class.h and no top speed, so results
   *  without types are those without classes, bit for bit.
   *  Paper-literal: false (every vehicle a car with the paper's ranges, VehicleType ignored). */
  bool road_user_classes{true};
  /** Motorcycles and mopeds. SUMO (vClass motorcycle): accel 6, decel 10, emergencyDecel 10
   *  m/s^2, maxSpeed 200 km/h, mass 200 kg without its rider; + 70 kg (SUMO's person) = 270 kg.
   *  Power at the wheels: our estimate for a mid-size machine, 50 kW for 270 kg with rider, at
   *  0.9 drivetrain efficiency (as vehicle_class.h): 165 W/kg (the accel bound and traction cap
   *  it below about 5 m/s^2 at most speeds). Wheelbase: 1.4-1.5 m on a 2.2 m motorcycle
   *  (SUMO's length): 0.65 of the length. Cornering stiffness per kg as for cars (no better
   *  single-track figure; the one-track model treats it as a narrow car). */
  RoadUserLimits motorcycle{6.0,  10.0, 10.0, 200.0 / 3.6, 270.0, 165.0,
                            0.65, 1.0,  1.8,  55.0,        false};
  /** Bicycles (and e-scooters). SUMO (vClass bicycle): accel 1.2, decel 3, emergencyDecel 7
   *  m/s^2, a speed of 20 km/h (5.56 m/s: SUMO 1.7's maxSpeed; today's SUMO keeps it as the
   *  desiredMaxSpeed beside a maxSpeed of 50 km/h; a vType's own maxSpeed replaces it), mass
   *  10 kg + 70 kg rider = 80 kg. Power at the wheels 8 W/kg (640 W for 80 kg, a sprint from
   *  the pedals; our estimate), so that the accel bound, not the power, limits a cyclist up to
   *  its top speed. Wheelbase about 1.0-1.1 m on SUMO's 1.6 m bicycle: 0.62 of the length.
   *  Kinematic: a tyre model means little at 5 m/s. */
  RoadUserLimits bicycle{1.2, 3.0, 7.0, 20.0 / 3.6, 80.0, 8.0, 0.62, 0.8, 1.3, 55.0, true};
  /** Trucks, trailers, buses and coaches. SUMO: accel 1.3 (truck; trailer 1.1, bus 1.2, coach
   *  2), decel 4, emergencyDecel 7, maxSpeed 130 km/h (truck, trailer; bus, coach 100 km/h),
   *  mass 4.5 t (truck), 13 t (trailer), 12 t (bus), 25 t (coach), all unladen. Emergency
   *  deceleration 6 m/s^2, below SUMO's 7: FMVSS 121 (NHTSA final rule, Federal Register
   *  74(142), 27 July 2009) stops a loaded truck tractor from 60 mph within 250 ft, a mean 4.7
   *  m/s^2 over the stop, about 5.6 m/s^2 once the air brakes' build-up (about 0.45 s) is taken
   *  out; 6 leaves room for better brakes. Mass 12 t (SUMO's bus; a medium truck with load).
   *  Power at the wheels 10 W/kg (our estimate: a 40 t articulated truck has 330-420 kW, a
   *  loaded 18 t city bus 220-250 kW). Wheelbase 0.5 of the length (a 12 m bus about 6 m, a
   *  7.1 m truck about 3.6 m), 2.5-8 m. Cornering stiffness 30 N/rad per kg per axle, about
   *  11 % of the axle load per degree: Gillespie (Fundamentals of Vehicle Dynamics, SAE 1992,
   *  as quoted in the McHenry SMAC documentation) gives 11-19 % for radial tyres (our cars'
   *  55 N/rad/kg is about 20 %); heavily loaded truck tyres at the low end is our estimate. */
  RoadUserLimits heavy{1.3, 4.0, 6.0, 130.0 / 3.6, 12000.0, 10.0, 0.5, 2.5, 8.0, 30.0, false};
  /** Trains, trams and light rail. Braking about 1 m/s^2 normal and 2.5-3 m/s^2 in an emergency
   *  (issue 21; SUMO: decel 1.3 for trains, 3 for trams, emergencyDecel 5 and 7): 3 m/s^2, the
   *  upper end (trams with magnetic track brakes were measured at 3.5 m/s^2 in 1990 and 4.9
   *  m/s^2 in 2017 on dry rail, salingre.de "Strassenbahn"; mainline trains brake far less: a
   *  vType's own emergencyDecel replaces it). Accel 1 m/s^2 (SUMO tram; rail 0.25), maxSpeed
   *  160 km/h (SUMO rail; tram 80), mass 37.9 t (SUMO tram). Power at the wheels 12 W/kg (our
   *  estimate: a 40 t tram with 500-600 kW). Wheelbase: bogie pivots at about 0.7 of a
   *  coach's length (19 m on a 26.4 m coach), 2-20 m. The track steers it: it keeps to one
   *  path, its own lane's centre, moving along it by the distance its speed covers
   *  (core::TrackStep, no steering, no latency, no motion model across its way). */
  RoadUserLimits rail{1.0, 1.0, 3.0, 160.0 / 3.6, 37900.0, 12.0, 0.7, 2.0, 20.0, 55.0, true};
  /** Yaw inertia of the classes above: this share of a uniform box's, m (L^2 + W^2) / 12 (a
   *  vehicle's mass lies nearer its centre than a box's). The car classes of vehicle_class.h
   *  (Heydinger et al.) lie at 0.78-0.95 of the box of a typical car of their segment; project
   *  choice 0.8 (a 12 t, 12 m bus: 120,000 kg m^2). */
  double yaw_inertia_box_share{0.8};

  /** The paper's ablation "controller off" (Sec. V-A, Fig. "results"): with false, no lateral
   *  controller tracks the path sections. Steering keeps its initial value until the lateral
   *  latency, then, at the start of each path section, an open-loop steering angle is set once
   *  (pure pursuit towards the section's point one section span ahead) and held (rate-limited):
   *  constant steering in the manner the paper criticises (Broadhurst et al.), so that
   *  hypotheses leave the road. For evaluations only; default true. */
  bool lateral_controller{true};
  /** The paper's steering law reacts to errors only, so a vehicle in a tight turn (a junction's
   *  right turn, radius 5-10 m) builds up an error before it steers and leaves the turn wide,
   *  into the lane beside the exit. With true, for a vehicle already turning the way its lane
   *  turns (a yaw rate of at least 0.1 rad/s), the curvature kappa of the path section at the
   *  predicted position adds its steady-state angle atan(wheelbase * kappa) (kinematic
   *  single-track), as path-tracking controllers do (feed-forward); the angle and rate limits
   *  still apply. A vehicle still straight before a turn gets none: the parabola spreads the
   *  turn over the straight before it, and would turn it in early. Project choice;
   *  paper-literal: false. */
  bool steer_curvature_feedforward{true};

  // --- Street data (paper Sec. IV-A) ---
  /** Width of the virtual own lane when the sensors deliver none. RAA (FGSV 2008): 3.5-3.75 m. */
  double virtual_lane_width_m{3.5};
  /** The paper's "without road modelling" (Sec. V-A: 300 ms anticipation instead of 932): with
   *  false, every lane in the scene is ignored; the ego and every vehicle get a virtual own lane
   *  (virtual_lane_width_m, curving with yaw rate / speed) with a virtual lane of the same width
   *  on each side, so the number of hypotheses stays the same but they know nothing of the road
   *  (its curves, which lanes exist, counter traffic). For evaluations only; default true. */
  bool road_model{true};
  /** The paper's lane model is a parabola y(x) in the observer's frame: it cannot follow a lane
   *  that turns across the observer's heading (a junction turn), and fitted through such a
   *  turn it runs on into the lanes beside the turn's exit (estimator/ALGORITHM.md "Lanes in
   *  junction turns"). With true, an observer whose own lane's centre, from its closest to its
   *  farthest sample (the chord), points at least turn_lane_frame_min_rad away from its heading
   *  has its lanes fitted in the frame along that chord instead, where a turn of up to about
   *  90 degrees is a function y(x); lanes that turn less keep the paper's frame. Either way,
   *  every lane then continues straight along its tangent beyond its farthest sample (the
   *  SUMO driver samples a turn up to its end) instead of the parabola curving on.
   *  Project choice; paper-literal: false. */
  bool turn_lane_frame{true};
  /** See turn_lane_frame: 20 degrees (a chord that far off belongs to a turn of about 40
   *  degrees; road curves over a sampled reach turn far less). */
  double turn_lane_frame_min_rad{0.35};
  /** A parabola through three samples of a road that runs straight and then turns (a junction
   *  ahead) bends away from the turn on the straight first: with the turn 25-45 m ahead it
   *  swept 1.3 m out of the lane towards the kerb. With true, a lane marked
   *  Lane::straight_to_middle (the SUMO driver samples its middle point where the turn
   *  starts) is fitted as the straight line through its first two samples, continued by the
   *  parabola tangent to it through the third (estimator/ALGORITHM.md "Straight road before a
   *  turn"); with false the mark is ignored. Project choice; paper-literal: false. */
  bool straight_before_turn{true};
  /** The SUMO driver's lane sampling: straight_before_turn applies to straights of 15 m or more
   *  (shorter ones lead into turns a vehicle may be steering into already, where the parabola
   *  through the whole turn followed it better). From 2 m up to 15 m, and at least half a
   *  second of the vehicle's travel (time to steer into the turn at the controller's steering
   *  rate), the middle samples go to the straight's end where that fit keeps closer to the
   *  road's centre line than the parabola through the reach's middle (LaneCentreDeviation).
   *  Traced: the switch at 15 m moved a car's reference 0.7 m towards a pedestrian on the
   *  footway in one 0.1 s step (bench/RESULTS.md, 2026-12-06, "flicker"). Project choice;
   *  paper-literal: false (needs straight_before_turn). Driver: --no-straight-by-fit. */
  bool straight_before_turn_by_fit{true};
  /** The SUMO driver's lane sampling: a lane that runs straight for 2 m ahead of the vehicle
   *  and then turns by at least 15 degrees over its sampled reach is sent as a corner (Lane::corner_tangent_m): the straights along the road's
   *  direction at its first and last samples, their meeting point, and where the turn begins
   *  and ends, so that the divider is straight, a parabola tangent to both straights, and
   *  straight again. A parabola through three samples of a straight road into a 90 degree
   *  junction turn swings out on the straight and turns on past the turn's end (traced in
   *  bench/RESULTS.md, 2026-12-05, "corners"). Replaces straight_before_turn's sampling where it
   *  applies. An experiment, off: fewer false alarms at 0.1 s steps, more at 1 s, more on the
   *  held-out set as a whole (bench/RESULTS.md; plugin/scenes/lane_corridor.h; driver
   *  --lane-corners). */
  bool lane_corners{false};
  /** The SUMO driver's lane sampling: where no reach gives an own lane that can be fitted
   *  within the lane (a tight junction turn, whose inner divider, offset from the centre line
   *  by half the lane's width, folds back once the turn's radius is about that half width:
   *  SUMO's right turns of 1.6 m radius on 3.2 m lanes), the lanes are sent as a corner
   *  (Lane::corner_tangent_m) from where the vehicle is, also when it is already in the turn,
   *  if that corner's fitted centre stays within the lane; before, such a vehicle had no lanes
   *  and was predicted on a virtual lane out of its turn (traced in bench/RESULTS.md,
   *  seventeenth stop). An experiment, off: on the tuning grid it gave the traced car a lane
   *  but changed no warning (the car's 0.5 rad of steering cannot follow SUMO's 1.6 m radius
   *  either). Driver: --lane-corner-in-turn. */
  bool lane_corner_in_turn{false};
  /** A vehicle that brings its way (Vehicle::way: the SUMO driver sends it for a vehicle whose
   *  body is in a junction) moves along it as the simulation moves it: its front and its back
   *  on the way, its heading from back to front, at the speed of each profile; one path (it
   *  cannot leave its internal lane). Without it a car in a tight turn was predicted on a
   *  wide arc or its back swung across the road along its chord heading (bench/RESULTS.md,
   *  twenty-fourth stop). Project choice; reads which lane of the junction it is on, which a
   *  map gives from its place and blinker and SUMO from its route. Paper-literal: off.
   *  Driver: --no-junction-ways stops sending the ways. */
  bool bodies_on_way{true};
  /** An experiment, off: a vehicle on its way (bodies_on_way) keeps the lateral samples of its
   *  lanes as its paths along the way: from the lateral latency on, each path moves its body
   *  sideways from where it started beside the way to that sample's offset from its reference
   *  path by each sample instant (linearly in time, at most tan 0.35 rad per metre driven,
   *  turned by that angle), scored as any vehicle's paths. Meant for SUMO's sublane model,
   *  which moves vehicles sideways inside a junction; judged on the held-out families it lost
   *  two warned body overlaps (one held-out, the overlap it was meant to recover) and a
   *  held-out violation collision's victim was warned 0.5 s later, for 4 fewer held-out false
   *  alarms (bench/RESULTS.md, twenty-fifth stop). false: one path, on the way. Driver:
   *  --way-lateral-paths. */
  bool way_lateral_paths{false};
  /** An experiment, off: the ego, where it brings its way (Ego::way: the SUMO driver sends it
   *  while its body is in a junction, as for other vehicles), moves along it as bodies_on_way
   *  moves other vehicles: on one path along it, without lateral latency (its hypotheses are
   *  its profiles), or, with way_lateral_paths too, its path tree's sections as sideways
   *  offsets beside its way (that mechanism, with every combination of sections). Traced (bench/RESULTS.md, twenty-fifth stop): 10 of the 15 held-out sublane false
   *  alarms at 0.1 s had the ego in a turn of 0.9-2.6 m radius, which its steering (4.9 m at
   *  0.5 rad) cannot drive, predicted out on a wide arc into the traffic it turns across.
   *  Judged (same stop, with its path tree beside the way): a third to a half fewer false
   *  alarms on every set, but warned collisions and overlaps lost, so off. On one path
   *  (twenty-sixth stop, a fresh held-out sublane grid among the sets): held-out false alarms
   *  40 -> 31, but a held-out collision at 1 s (p 0.907 -> 0.881) and a held-out overlap (of
   *  a body the driver misread, traced) no longer warned, so off. Reads which lane of the junction it is on, which
   *  its own route gives. Driver: --ego-on-way. */
  bool ego_on_way{false};
  /** The SUMO driver's lane sampling: a lane whose fitted centre line leaves the lane between
   *  its samples (lies farther than half the lane's width from its centre line, as a parabola
   *  through three samples of a short straight and a sharp junction turn does: 3.4 m towards
   *  the lane beside it, traced in bench/RESULTS.md) is sampled over a shorter reach, as one
   *  that cannot be fitted at all (plugin/scenes/lane_corridor.h). Project choice;
   *  paper-literal: false. */
  bool lane_fit_within_lane{true};
  /** A vehicle (or the ego) whose ObjectState::route_end_m is set leaves the scene once it has
   *  travelled that far: its hypotheses' poses from then on collide with nothing. SUMO removes
   *  a vehicle at the end of its route at full speed, often just before a junction; carried
   *  on, its hypotheses crossed the junction into traffic that had the green light
   *  (estimator/ALGORITHM.md "Vehicles that leave the simulation"). Project choice (SUMO's
   *  arrivals); paper-literal: false. */
  bool route_end_leaves{true};

  // --- Drivability (DESIGN.md: every hypothesis must be drivable). The paper asks for drivable
  // trajectories but leaves these limits open; ParamsPreset("paper-literal") turns them off. ---
  /** Lateral reaction latency: until this time a vehicle (ego or other) keeps following its
   *  reference path (its own lane's centre, which needs no reaction: a car finishing a turn
   *  straightens up with its lane); then the lateral controller steers towards its
   *  hypothesis' path. The counterpart of latency_s for braking (DESIGN.md: "reaction latency
   *  for steering as for braking").
   *  Summala (1981, Human Factors 23(6)) measured about 1.5 s for unalerted drivers to start an
   *  avoidance steer; hypotheses also cover manoeuvres already decided, so we take the
   *  movement-and-actuation part only: about 0.2 s to move the hands (as latency_s for the
   *  foot) plus about 0.1 s for the steering system and tyres to build side force. Project
   *  choice: 0.3 s; paper-literal: 0 (steering from t = 0). */
  double steer_latency_s{0.3};
  /** Friction limit of the lateral dynamics: the one-track model's axle side forces saturate at
   *  what the friction circle leaves beside the longitudinal force (mu F_z per axle, static
   *  loads), and the kinematic model's steering is limited so that v^2 tan(delta) / L stays
   *  within it. So |a| = hypot(a_x, a_y) <= mu g for every vehicle hypothesis (the two-track
   *  ego has its friction circle per wheel already). A measured yaw rate beyond the limit (v r >
   *  mu g: SUMO's headings jump on junction lanes) is limited to mu g / v. Paper-literal: off
   *  (the linear one-track model of the paper has no grip limit: lane changes reached 1.6 g). */
  bool friction_limited_lateral{true};
  /** Positive acceleration limited by traction and power: a <= min(drive_traction_share mu g,
   *  P / (m v)), P / m by vehicle class (vehicle_class.h: segment averages, at the wheels).
   *  Applies to the other vehicles' acceleration profiles and to the ego's driving force.
   *  Paper-literal: off (+9.7 m/s^2, and the ego's +0.1 slip = +1 g, at any speed). */
  bool power_limited_drive{true};
  /** Share of mu m g the driven axle transmits: front-wheel drive (the common layout of the
   *  classes here) with the static front axle load of our vehicle geometry, l_r / L = 0.55
   *  (vehicle_class.h). Project choice: 0.55. */
  double drive_traction_share{0.55};
  /** The ego's braking hypotheses spread in deceleration, like the other vehicles' (equally
   *  spaced over vehicle_accel_min_mps2..0: gentle to emergency, -2.4 to -9.7 m/s^2 with 6
   *  profiles), ramped with latency_s and jerk_mps3 in acceleration and applied as tyre force
   *  demand (F_x = m a on the four wheels, within each wheel's friction circle). Paper-literal:
   *  false: equally spaced longitudinal slip ego_slip_min..ego_slip_max, which the tyre curve
   *  maps to -9.8, -9.6, -8.3 and -5.2 m/s^2 (no gentle braking). */
  bool ego_profiles_in_accel{true};
  /** The profile sample nearest to the object's current acceleration (minimum and maximum
   *  excepted) is replaced by the current acceleration itself, so that the reference
   *  hypothesis of the paper ("keep driving with the current acceleration") is one of the
   *  hypotheses. Project choice; paper-literal: false (the zero profile, "cruising"). */
  bool profiles_include_current_accel{true};
  /** Where the caller gives an object's expected acceleration (ObjectState::
   *  expected_accel_mps2: what its driver is expected to do about a slower vehicle ahead or a
   *  stop line) and it is below the current acceleration, it replaces the current acceleration
   *  as the reference: the profile sample nearest to it becomes it, and the scores measure
   *  deviations from it. The paper's reference, "keep the current acceleration", assumes
   *  nobody reacts: a car rolling up to a queue at a red light then "hits" the last car in
   *  every likely hypothesis, and both get warned (the largest source of false alarms in
   *  city traffic, bench/RESULTS.md). Drivers react to what is ahead of them; hypotheses
   *  around the expected reaction keep the ones in which they do not, with their lower
   *  scores. Project choice; paper-literal: false. */
  bool expected_accel_reference{true};
  /** With true, another vehicle whose caller gives an expected acceleration below its current
   *  one (ObjectState::expected_accel_mps2) does it from now: its profiles start from it
   *  instead of holding the current acceleration through latency_s. SUMO's drivers decide
   *  afresh every step and apply the decision in the next one, without a reaction latency: a
   *  car accelerating at +2.2 m/s^2 towards its yield line 2 m ahead stopped there at -4.5
   *  m/s^2 at once, while its hypotheses held +2.2 m/s^2 for 0.2 s and ran 2 m on into the car
   *  waiting in the junction (bench/RESULTS.md, seventeenth stop). The ego keeps the latency:
   *  its hypotheses are what its driver (or the closed loop's actuator) can still do, and
   *  applied to the ego too the rule cost the designed collisions their anticipation where the
   *  ego is scripted not to brake (cut_in 1.6 -> 0.7 s). Reads what only the simulator knows
   *  (its drivers react without latency); off for an on-board use. Project choice;
   *  paper-literal: false. Driver: --no-expected-accel-at-once. */
  bool expected_accel_at_once{true};
  /** With true, another vehicle with a credible stop obligation (stop_obligations) acts on it
   *  from now, as SUMO's drivers do: its profiles start from the constant deceleration that
   *  stops its front at the line, -v^2 / (2 d), where that is below its current (and expected)
   *  acceleration, instead of holding the current acceleration through latency_s. Traced
   *  (bench/RESULTS.md, eighteenth stop): a car turning left, accelerating at +2.1 m/s^2 at 5
   *  m/s towards its yield line 3.9 m ahead, needed 3.2 m/s^2 to stop there from now; held
   *  through the latency and the jerk ramp no profile could stop it at the line, so its
   *  stopping profile was dropped and it was predicted to turn on across the oncoming car's
   *  lane (p 0.95); SUMO braked it at -4.5 m/s^2 from the next step and it stopped short. Its
   *  hypotheses that drive on (stop_violation_probability) start from the same deceleration.
   *  And the obligation stays credible while the deceleration it needs is within the vehicle
   *  type's normal largest one (VehicleType::decel_mps2, where that is above
   *  stop_comfortable_decel_mps2): SUMO's drivers brake up to it to stop at a line (the same
   *  car one step later, 5.3 m/s and 3.4 m from the line, needed 4.1 m/s^2 and stopped there
   *  at its type's 4.5). The ego keeps its latency and the comfortable deceleration (as for
   *  expected_accel_at_once). Reads what only the simulator knows (its drivers react without
   *  latency and brake to their type's limit); off for an on-board use. Project choice;
   *  paper-literal: false. Driver: --no-stop-at-once. */
  bool stop_obligation_at_once{true};
  /** With true, the reference of a vehicle (the ego too) that is too fast for the curve of its
   *  own lane ahead brakes for it: the constant deceleration that brings it, by the point of the
   *  lane's centre within speed x horizon where it matters most, to the speed at which that
   *  point's curvature asks curve_lateral_accel_mps2 of it (at most curve_decel_max_mps2), where
   *  that is below the current acceleration. SUMO moves its vehicles along a junction's lanes
   *  at speeds whose lateral acceleration no tyre transmits beside acceleration (9 m/s^2 in a
   *  5.6 m right turn at 7.2 m/s); a reference that kept accelerating there left the turn wide
   *  and crossed the exit road's other lane. Project choice; paper-literal: false. */
  bool curve_speed_reference{true};
  /** With true, the reference of a vehicle (the ego too) whose caller knows its reasons to
   *  brake (ObjectState::braking_causes_known) and that brakes harder than all of them ask (its
   *  expected_accel_mps2, the curve of its lane ahead, and otherwise holding its speed) releases
   *  to what they ask: the reference acceleration is min(0, expected, curve) instead of the
   *  current one. The paper's reference keeps the current acceleration for the whole horizon;
   *  SUMO's drivers decide afresh every step, and at 1 s steps an acceleration is one step's
   *  average: a car that slowed for a junction turn (-4.5 m/s^2 over the last second, at turn
   *  speed now) was predicted to stop within 1.9 s in the junction, short of the crossing lane
   *  where it hit the oncoming car 1 s later. A vehicle that brakes for a stop line keeps its
   *  stopping profile (the mixture of stop_obligations); only the branch that drives on is
   *  released. An experiment, off: judged on the violation family's held-out set it warned no
   *  collision more (bench/RESULTS.md, 2026-12-04, "braking that has no cause"). */
  bool release_unexplained_braking{false};
  /** Collisions only where the world looks for them: with a simulator's Euler step
   *  (Scene::euler_update_step_s, a multiple of step_s), the poses between its steps repeat the
   *  pose of its last step (HypothesisSet::pose_hold_steps), so that a pair counts as colliding
   *  only if it overlaps at a step the simulator checks. SUMO at 1 s steps moves a vehicle
   *  v(k+1) dt in a step and can stop it at its yield line with no displacement, while a
   *  truck's body sweeps past its nose between two steps: every ego hypothesis collided in
   *  between, none at the steps (bench/RESULTS.md, 2026-12-04, "collisions where the world
   *  looks"). On the held-out networks it halved the false alarms and warned every collision it
   *  warned before. Reads what only the simulator knows (its step); driver
   *  --no-world-step-collisions turns it off. No effect on scenes without an Euler step. */
  bool collisions_at_world_steps{true};
  /** With held poses (collisions_at_world_steps, an Euler step a whole number of steps): a
   *  body whose speed is 0 at one of the world's steps stays where the world's previous step
   *  left it, as SUMO's update does (x += v_new dt moves it by 0). The shift (v - v0) dt / 2
   *  is SUMO's position only while the speed changes linearly between the world's steps; a
   *  hypothesis that stops inside a step was put behind that place, and one that stops within
   *  the first step behind where it stands now (1.1 m back for 5.2 m/s braking at 9 m/s^2 with
   *  1 s steps; traced at the twenty-sixth stop, bench/RESULTS.md). An experiment: judged on
   *  the held-out networks (same stop) one false alarm fewer of 31, the same collisions as
   *  early, three pedestrian overlaps warned a 1 s step later; off. Driver --euler-stops. */
  bool euler_stops{false};
  /** See curve_speed_reference. 5.5 m/s^2: the lateral acceleration from which SUMO's
   *  netconvert sets turning speeds (junctions.limit-turn-speed), above what drivers choose in
   *  comfort (about 0.3-0.4 g), so that only a speed that is too high for any normal driving
   *  makes the reference brake. */
  double curve_lateral_accel_mps2{5.5};
  /** See curve_speed_reference: normal braking (4.5 m/s^2, AASHTO; the cap of the driver's
   *  car-following expectation, plugin/scenes/car_following.h). */
  double curve_decel_max_mps2{4.5};

  // --- Stop obligations (Vehicle::stop_line; the paper is silent: estimator/ALGORITHM.md) ---
  /** With true, a vehicle with a credible obligation to stop (below) gets a stopping profile:
   *  the constant deceleration, reached through latency_s and jerk_mps3 like every profile,
   *  that stops its front at the line. Its hypotheses are then a mixture: with probability
   *  1 - stop_violation_probability the vehicle complies (every hypothesis scored against the
   *  stopping profile as the reference), with stop_violation_probability it drives as if there
   *  were no line (scored against its current acceleration, as without an obligation).
   *  Needs kNaturalistic scoring and at least 4 profiles; paper-literal: false. */
  bool stop_obligations{true};
  /** With true (and stop_obligations), the ego's own credible stop line (Ego::stop_line, the
   *  same credibility as below) makes its reference the constant deceleration that stops it
   *  there, where that is below its reference otherwise: a driver turning left across oncoming
   *  traffic it must yield to is expected to stop, as it is expected to brake for a slower car
   *  ahead (expected_accel_reference). No mixture as for the others: the hypotheses that drive
   *  on keep their lower scores. An experiment, off by default (bench/RESULTS.md, 2026-12-04,
   *  "the ego's own yield line"). */
  bool ego_stop_obligations{false};
  /** The share of drivers who do not stop where they must. Red-light running, measured on
   *  vehicle trajectories at nine signalised sites: 0.9-2.0 % of the vehicles near the stop line
   *  at the onset of yellow entered on red (a US DOT-funded dilemma-zone study, table 6.4, as
   *  quoted at
   * https://1library.co/article/apertura-evaluaci%C3%B3n-ofertas-documento-licitaci%C3%B3n.zlg3mn7g;
   *  Hunter's Rhode Island study counts 1.2-15 violations per intersection-hour). Project
   *  choice: 0.02, the upper end, also for yield lines (no comparable data found). */
  double stop_violation_probability{0.02};
  /** An obligation counts only while complying is consistent with what the vehicle does: the
   *  deceleration it needs to stop at the line, v^2 / (2 d), is comfortable (at most this), or
   *  it already brakes at least half that hard. A driver who needs more and does not brake is
   *  not going to stop (an inattentive one, or one past the point of no return at yellow): then
   *  its hypotheses are those without a line. AASHTO (2011): 3.4 m/s^2 is comfortable for most
   *  drivers (the same source as decel_score_sigma_mps2). */
  double stop_comfortable_decel_mps2{3.4};

  // --- Scoring (paper Sec. IV-D-1): n_h = (w_acc n_acc + w_str d_str) / (c_com c_cou) ---
  /** Which functions fill the paper's formula. kNaturalistic (default): Gaussian deviation
   *  scores with widths from naturalistic driving data, d_str scoring the hypothesis' position
   *  against the reference trajectory along AND across the road, c_com counting lane crossings
   *  of every object. kPaperLiteral: the first implementation's functions, kept so that
   *  evaluations can show both (see the fields marked paper-literal below). */
  enum class Scoring { kPaperLiteral, kNaturalistic };
  Scoring scoring{Scoring::kNaturalistic};
  /** Weights. The paper gives none ("domain knowledge"). With kNaturalistic, n_acc and d_str
   *  both fall with an acceleration deviation (d_str through the distance it gains or loses),
   *  so w_acc n_acc is the share a path deviation keeps: w_acc / (w_acc + w_str) = 1/5 of the
   *  reference's score for a path that deviates only laterally. Project choice (see
   *  bench/RESULTS.md for the sensitivity); paper-literal: equal weights 1, 1. */
  double w_acc{1.0};
  double w_str{4.0};
  /** kNaturalistic: n_acc = exp(-(a_k - a_ref)^2 / (2 sigma_a^2)), a_ref = the current
   *  acceleration, sigma_a = accel_score_sigma_mps2 for a_k > a_ref. Bosetti, Da Lio & Saroldi
   * (2014, Eur. Transp. Res. Rev. 6:157-170; 35 h of naturalistic urban, extra-urban and motorway
   * driving): drivers' longitudinal accelerations stay within about +-2 m/s^2 outside emergencies,
   * far inside the friction limit; sigma_a = 1 m/s^2 puts that envelope at 2 sigma. */
  double accel_score_sigma_mps2{1.0};
  /** The same for a deceleration (a_k < a_ref, and in d_str a distance lost): drivers brake
   *  harder than they accelerate. AASHTO (A Policy on Geometric Design of Highways and
   *  Streets, 2011, stopping sight distance): most drivers stopping for an unexpected object
   *  decelerate at more than 4.5 m/s^2, and 3.4 m/s^2 is comfortable for most; sigma = 2.5
   *  m/s^2 puts them at 1.4 and 1.8 sigma (a car braking at 4-5 m/s^2 to yield at a junction is
   *  not a rare event: SUMO's drivers do it late), while an emergency stop (9.7 m/s^2) stays
   *  out at 3.9 sigma. */
  double decel_score_sigma_mps2{2.5};
  /** kNaturalistic: d_str = exp(-(mean_i (dy_i / sigma_y)^2 + mean_i (dx_i / sigma_x(t_i))^2) / 2)
   *  over the sample instants t_i: dy_i the path sample's offset from the reference (own-lane
   *  centre; for pedestrians the heading change over heading_score_sigma_rad replaces it), dx_i
   *  the distance the profile gains or loses on the reference trajectory, sigma_x(t_i) what a
   *  profile one sigma_a off the reference (decel_score_sigma_mps2 for a distance lost) gains
   *  or loses by t_i through the same latency, ramp and drive limit: the same deviation as
   *  n_acc measures, in distance, so that a stop or the power limit counts as it happens.
   *  sigma_y: the standard deviation of lateral position of sober drivers on a motorway is
   *  about 0.18-0.25 m (Verster & Roth 2011, Int. J. Gen. Med. 4:359-371, the on-the-road
   *  driving test); we take 0.25 m. */
  double lateral_offset_sigma_m{0.25};
  /** kNaturalistic, pedestrians: sigma_x(t) = pedestrian_speed_sigma_mps * t in d_str: a
   *  walker's position strays from the constant-speed prediction as walking speeds spread. Fugger
   * et al. (2001, SAE 2001-01-0896; 288 pedestrians at signalised crosswalks): steady walking
   * speed 1.36 +- 0.24 m/s. */
  double pedestrian_speed_sigma_mps{0.24};
  /** kNaturalistic, pedestrians: heading change width. Project choice (no naturalistic source
   *  found): 0.5 rad, so that the neighbouring headings (+-51 deg with 7 headings) keep about
   *  a fifth of the straight-on score. */
  double heading_score_sigma_rad{0.5};
  /** kNaturalistic: c_com = lane_crossing_penalty ^ (lane crossings of the path), for every
   *  object: a crossing is a change of lane between consecutive sample instants (from its own
   *  lane at t = 0); a pedestrian's are the ego lane dividers its heading line crosses within
   *  its current speed x horizon, counted against the straight-on heading (|n - n_ref|), so
   *  both stepping onto the road and turning back from it are manoeuvres. Krajewski et al.
   *  (2018, the highD dataset, ITSC): 5,600 complete lane changes in 45,000 vehicle-km of German
   *  motorway traffic, i.e. about 0.12 per vehicle-km, about 0.75 % per vehicle in a 2 s
   *  horizon at 30 m/s. With 100, a vehicle's four neighbour-lane paths get about 1 % of its
   *  mass. */
  double lane_crossing_penalty{100.0};
  /** c_cou for a path with any section on a lane of counter traffic as seen from the object
   *  (every vehicle: the ego, and others through their own lanes or the ego's lanes seen from
   *  their frame). kNaturalistic: 10 on top of the lane crossing: entering oncoming traffic
   *  (overtaking on a two-lane road) needs a gap in it, and is far rarer with an oncoming car
   *  in sight than a lane change on a motorway. Project choice; paper-literal: 4. */
  double counter_traffic_penalty{10.0};
  /** Paper-literal scoring: n_acc = 1 / (1 + |target - current| / (accel_score_scale * range)),
   *  range = the profile range's maximum (a profile at the range limit scores about 1/4 of the
   *  current-acceleration one); d_str = 1 / (1 + mean lateral offset of the path's samples from
   *  the own-lane centre / path_score_scale_m) (a full lane change scores about 1/3; for
   *  pedestrians the heading change over heading_score_scale_rad); c_com = 1 +
   *  complexity_penalty * (section changes along the path). Project choices of the first
   *  implementation. */
  double accel_score_scale{0.3};
  double path_score_scale_m{1.5};
  double heading_score_scale_rad{1.0};
  double complexity_penalty{0.5};

  // --- Outputs and limits ---
  /** How many escape routes to return: the ego hypotheses ranked by their collision
   *  probability (lowest first), then by their own probability (Result::escape_routes). */
  int max_escape_routes{10};
  /** Upper bound on the memory one estimate may use (trajectories and the pair matrix). */
  std::uint64_t max_memory_bytes{std::uint64_t{4} << 30};

  /** The limits of a class other than kCar (nullptr for kCar: the paper's range and
   *  vehicle_class.h). */
  const RoadUserLimits* LimitsOf(RoadUser road_user) const;

  /** Number of predicted time steps: round(horizon_s / step_s). */
  int TimeSteps() const;
  /** Number of lateral samples with all three lanes present (7 with the defaults). */
  int LateralSamplesThreeLanes() const { return own_lane_samples + 2 * neighbour_lane_samples; }
};

/** Throws InputError naming the first invalid field and its value. */
void ValidateParams(const Params& params);

/** Named parameter sets: "default" (Params{}: drivable hypotheses, naturalistic scoring) and
 *  "paper-literal" (the first implementation: the paper's profiles and linear models without
 *  friction or power limits, no steering latency, and its scoring), so that evaluations can
 *  show both. @throws InputError naming the accepted names. */
Params ParamsPreset(const std::string& name);
/** The names ParamsPreset accepts. */
std::vector<std::string> ParamsPresetNames();

}  // namespace criticality
