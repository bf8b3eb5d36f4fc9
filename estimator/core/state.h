#pragma once
// The state every vehicle model integrates, and the derivatives a model returns.
namespace criticality::core {

/** Vehicle state in some planar frame (paper Sec. IV-B-1: x_V, y_V, psi_V, v_V, beta, dpsi,
 *  and the accelerations a_x,V, a_y,V in the vehicle frame). */
struct MotionState {
  double x{0.0};
  double y{0.0};
  double yaw{0.0};       ///< psi
  double v{0.0};         ///< speed over ground, >= 0
  double beta{0.0};      ///< sideslip angle
  double yaw_rate{0.0};  ///< dpsi/dt
  double ax{0.0};        ///< acceleration in the vehicle frame, longitudinal
  double ay{0.0};        ///< acceleration in the vehicle frame, lateral
};

/** What a motion model returns for one step: [dv, dbeta, ddpsi]. */
struct StateDerivative {
  double v_dot{0.0};
  double beta_dot{0.0};
  double yaw_acc{0.0};
};

}  // namespace criticality::core
