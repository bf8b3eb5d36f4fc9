#pragma once
// Physical parameters of one vehicle, as the motion models need them.
namespace criticality::core {

constexpr double kGravity = 9.81;

struct VehicleParams {
  double mass_kg{1500.0};
  double yaw_inertia_kgm2{2500.0};  ///< I_z
  double lf_m{1.2};                 ///< centre of gravity to front axle
  double lr_m{1.5};                 ///< centre of gravity to rear axle
  double cf_npr{80000.0};           ///< front axle cornering stiffness c_alpha,f, N/rad
  double cr_npr{80000.0};           ///< rear axle cornering stiffness c_alpha,r, N/rad
  double track_m{1.55};             ///< distance between left and right wheels
  double friction{1.0};             ///< tyre-road friction coefficient mu
  /** Speed below which the kinematic single-track model replaces the dynamic models. */
  double kinematic_below_mps{2.0};
  /** Friction-limited lateral dynamics (Params::friction_limited_lateral): the one-track
   *  model's axle side forces saturate within the friction circle, the kinematic model's
   *  steering is limited to it. False: the paper's linear one-track model. */
  bool friction_limited{false};
  /** Driving power at the wheels per unit mass, W/kg (vehicle class, vehicle_class.h). */
  double power_per_mass_wpkg{60.0};
};

}  // namespace criticality::core
