#pragma once
// The paper's Euler integration (Sec. IV-B-1), literally:
//   [v, beta]_{n+1} = [v, beta]_n + [dv, dbeta]_n tau
//   psi_{n+1} = psi_n + dpsi_n tau + ddpsi_n tau^2 / 2
//   [ax, ay]_{n+1} = [c(beta_n), s(beta_n)] dv_n + [-s(beta_n), c(beta_n)] v_n (dbeta_n + dpsi_n)
//   [x, y]_{n+1} = [x, y]_n + [c(psi_n + beta_n), s(psi_n + beta_n)] v_n tau
//                  + [c(psi_n), s(psi_n)] ax_n tau^2/2 + [-s(psi_n), c(psi_n)] ay_n tau^2/2
// plus dpsi_{n+1} = dpsi_n + ddpsi_n tau, which the paper leaves implicit.
#include <cmath>

#include "core/hd.h"
#include "core/state.h"

namespace criticality::core {

/** @param cb, sb, cp, sp cos/sin of s->beta and s->yaw (the caller has them). */
CRIT_HD void EulerStep(const StateDerivative& d, double tau, MotionState* s, double cb, double sb,
                       double cp, double sp) {
  // cos/sin(psi + beta) by the angle-sum identities: two products instead of two calls.
  const double cpb = cp * cb - sp * sb, spb = sp * cb + cp * sb;
  const double h = 0.5 * tau * tau;
  const double x = s->x + cpb * s->v * tau + cp * s->ax * h - sp * s->ay * h;
  const double y = s->y + spb * s->v * tau + sp * s->ax * h + cp * s->ay * h;
  const double turn = s->v * (d.beta_dot + s->yaw_rate);
  const double ax = cb * d.v_dot - sb * turn;
  const double ay = sb * d.v_dot + cb * turn;
  s->x = x;
  s->y = y;
  s->yaw = s->yaw + s->yaw_rate * tau + d.yaw_acc * h;
  s->yaw_rate = s->yaw_rate + d.yaw_acc * tau;
  s->v = s->v + d.v_dot * tau;
  s->beta = s->beta + d.beta_dot * tau;
  s->ax = ax;
  s->ay = ay;
}

CRIT_HD void EulerStep(const StateDerivative& d, double tau, MotionState* s) {
  EulerStep(d, tau, s, std::cos(s->beta), std::sin(s->beta), std::cos(s->yaw), std::sin(s->yaw));
}

/** Limits a longitudinal acceleration so that the speed never goes below zero in one step
 *  (vehicles stop, they do not reverse). */
CRIT_HD double NonReversingAccel(double v, double v_dot, double tau) {
  return (v + v_dot * tau < 0.0) ? -v / tau : v_dot;
}

/** Limits a positive longitudinal acceleration so that the speed does not rise above
 *  top_speed in one step (a vehicle's top speed; one already faster keeps its speed). With
 *  top_speed = +inf it returns v_dot unchanged. */
CRIT_HD double TopSpeedAccel(double v, double v_dot, double tau, double top_speed) {
  if (v_dot > 0.0 && v + v_dot * tau > top_speed) {
    const double room = (top_speed - v) / tau;
    return room > 0.0 ? room : 0.0;
  }
  return v_dot;
}

}  // namespace criticality::core
