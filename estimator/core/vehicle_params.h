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
};

}  // namespace criticality::core
