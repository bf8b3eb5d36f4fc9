// Sibling ego paths in SIMD lanes: see sibling_steps.h. Compiled once per vector target by
// Highway's foreach_target; the entry points at the end dispatch to the best target at run
// time. Every expression below mirrors one of core::VehicleStep's (same operands, same order),
// so that lanes agree with the scalar step up to the vector sin/cos/atan. This file is built
// with -ffp-contract=off: no multiply-add is fused that the scalar code does not fuse.
#include "cpu/sibling_steps.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "cpu/sibling_steps.cc"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
#include "hwy/contrib/math/math-inl.h"

HWY_BEFORE_NAMESPACE();
namespace criticality::internal {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using core::kMaxLateralSamples;

constexpr size_t kBuf = 16;  // lanes of the widest vector of doubles Highway has, or more

// The per-lane state of the span, structure of arrays (lane l of each array).
struct Lanes {
  double x[kBuf], y[kBuf], yaw[kBuf], v[kBuf], beta[kBuf], yaw_rate[kBuf], ax[kBuf], ay[kBuf];
  double steer[kBuf], travelled[kBuf];
  double cyaw[kBuf], syaw[kBuf];  // cos/sin of yaw, from the end of the step before
  // The section each lane tracks now (parabola coefficients and frame).
  double a[kBuf], b[kBuf], c[kBuf], rot[kBuf], cos_rot[kBuf], sin_rot[kBuf], x_start[kBuf],
      x_end[kBuf];
};

void ToLanes(const core::SimulationState& st, size_t l, Lanes* L) {
  const core::MotionState& s = st.s;
  L->x[l] = s.x;
  L->y[l] = s.y;
  L->yaw[l] = s.yaw;
  L->v[l] = s.v;
  L->beta[l] = s.beta;
  L->yaw_rate[l] = s.yaw_rate;
  L->ax[l] = s.ax;
  L->ay[l] = s.ay;
  L->steer[l] = st.steer;
  L->travelled[l] = st.travelled;
}

void FromLanes(const Lanes& L, size_t l, core::SimulationState* st) {
  core::MotionState& s = st->s;
  s.x = L.x[l];
  s.y = L.y[l];
  s.yaw = L.yaw[l];
  s.v = L.v[l];
  s.beta = L.beta[l];
  s.yaw_rate = L.yaw_rate[l];
  s.ax = L.ax[l];
  s.ay = L.ay[l];
  st->steer = L.steer[l];
  st->travelled = L.travelled[l];
}

void SectionToLanes(const core::Parabola& p, size_t l, Lanes* L) {
  L->a[l] = p.a;
  L->b[l] = p.b;
  L->c[l] = p.c;
  L->rot[l] = p.rot;
  L->cos_rot[l] = p.cos_rot;
  L->sin_rot[l] = p.sin_rot;
  L->x_start[l] = p.x_start;
  L->x_end[l] = p.x_end;
}

// hn::Atan, the same operations lane for lane, without its division when no lane needs it:
// hn::Atan always computes 1 / |x| for the lanes with |x| > 1, and the angles here (slip
// angles, path slopes, sideslip) mostly have none.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V AtanOf(D d, V x) {
  const V sign = hn::And(hn::SignBit(d), x);
  const V abs_x = hn::Xor(x, sign);
  if (!hn::AllFalse(d, hn::Gt(abs_x, hn::Set(d, 1.0)))) return hn::Atan(d, x);
  return hn::Or(hn::impl::AtanImpl<double>().AtanPoly(d, abs_x), sign);
}

// Sine and cosine of x together. Where every lane has |x| <= kSmallAngle (sideslip, steering
// and the yaw turned in one step mostly are), their Taylor series to x^13 / x^14, whose first
// dropped terms (|x|^15 / 15!, |x|^16 / 16!) stay below 1e-20, sharing x^2 and needing no range
// reduction; elsewhere Highway's Sin and Cos.
constexpr double kSmallAngle = 0.35;

template <class D, class V = hn::Vec<D>>
HWY_INLINE void SinCos(D d, V x, V* s, V* c) {
  if (!hn::AllTrue(d, hn::Le(hn::Abs(x), hn::Set(d, kSmallAngle)))) {
    *s = hn::Sin(d, x);
    *c = hn::Cos(d, x);
    return;
  }
  const V x2 = hn::Mul(x, x);
  // Horner in x^2 over the series' coefficients, highest first.
  V ps = hn::Set(d, -1.0 / 6227020800.0);  // -1/13!
  ps = hn::MulAdd(ps, x2, hn::Set(d, 1.0 / 39916800.0));
  ps = hn::MulAdd(ps, x2, hn::Set(d, -1.0 / 362880.0));
  ps = hn::MulAdd(ps, x2, hn::Set(d, 1.0 / 5040.0));
  ps = hn::MulAdd(ps, x2, hn::Set(d, -1.0 / 120.0));
  ps = hn::MulAdd(ps, x2, hn::Set(d, 1.0 / 6.0));
  *s = hn::NegMulAdd(hn::Mul(ps, x2), x, x);  // x - x^3 (1/3! - ...)
  V pc = hn::Set(d, 1.0 / 87178291200.0);     // 1/14!
  pc = hn::MulAdd(pc, x2, hn::Set(d, -1.0 / 479001600.0));
  pc = hn::MulAdd(pc, x2, hn::Set(d, 1.0 / 3628800.0));
  pc = hn::MulAdd(pc, x2, hn::Set(d, -1.0 / 40320.0));
  pc = hn::MulAdd(pc, x2, hn::Set(d, 1.0 / 720.0));
  pc = hn::MulAdd(pc, x2, hn::Set(d, -1.0 / 24.0));
  pc = hn::MulAdd(pc, x2, hn::Set(d, 0.5));
  *c = hn::NegMulAdd(pc, x2, hn::Set(d, 1.0));  // 1 - x^2 (1/2! - ...)
}

// What a model returns for one step (core::StateDerivative), per lane.
template <class V>
struct Derivative {
  V v_dot, beta_dot, yaw_acc;
};

// core::DriveAccelLimit per lane.
template <class D, class V = hn::Vec<D>>
V DriveLimit(D d, const core::HypothesisSet& h, V v) {
  const V power = hn::Div(hn::Set(d, h.vehicle.power_per_mass_wpkg),
                          hn::IfThenElse(hn::Gt(v, hn::Set(d, 0.1)), v, hn::Set(d, 0.1)));
  const V traction = hn::Set(d, h.drive_traction);
  return hn::IfThenElse(hn::Lt(power, traction), power, traction);
}

// core::TwoTrackDerivative (TwoTrackForces inlined) per lane.
template <class D, class V = hn::Vec<D>>
Derivative<V> TwoTrack(D d, const core::VehicleParams& p, V v, V yr, V cb, V sb, V steer,
                       V cos_steer, V sin_steer, V factor) {
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0);
  const double wheelbase = p.lf_m + p.lr_m;
  const double weight = p.mass_kg * core::kGravity;
  const double fz_front = 0.5 * weight * p.lr_m / wheelbase;
  const double fz_rear = 0.5 * weight * p.lf_m / wheelbase;
  const V vx_cog = hn::Mul(v, cb), vy_cog = hn::Mul(v, sb);
  V fx = zero, fy = zero, mz = zero;
  for (int wheel = 0; wheel < 4; ++wheel) {
    const bool front = wheel < 2;
    const double xw = front ? p.lf_m : -p.lr_m;
    const double yw = (wheel % 2 == 0) ? 0.5 * p.track_m : -0.5 * p.track_m;
    const double fz = front ? fz_front : fz_rear;
    const double c_wheel = 0.5 * (front ? p.cf_npr : p.cr_npr);
    const V wx = hn::Sub(vx_cog, hn::Mul(yr, hn::Set(d, yw)));
    const V wy = hn::Add(vy_cog, hn::Mul(yr, hn::Set(d, xw)));
    const V delta = front ? steer : zero;
    const V alpha = hn::Sub(delta, AtanOf(d, hn::Div(wy, wx)));
    V fl = hn::Mul(hn::Set(d, p.friction * fz), factor);
    V fs = hn::Mul(hn::Set(d, c_wheel), alpha);
    // The friction circle: the force scaled onto it where its norm is beyond the limit. Where
    // the squared norm is clearly below the squared limit in every lane, no lane is beyond,
    // and the square root and the division are not needed.
    const double limit_s = p.friction * fz;
    const V norm2 = hn::Add(hn::Mul(fl, fl), hn::Mul(fs, fs));
    if (!hn::AllTrue(d, hn::Lt(norm2, hn::Set(d, limit_s * limit_s * (1.0 - 1e-9))))) {
      const V limit = hn::Set(d, limit_s);
      const V norm = hn::Sqrt(norm2);
      const auto over = hn::Gt(norm, limit);
      const V ratio = hn::Div(limit, norm);
      fl = hn::IfThenElse(over, hn::Mul(fl, ratio), fl);
      fs = hn::IfThenElse(over, hn::Mul(fs, ratio), fs);
    }
    const V cd = front ? cos_steer : one, sd = front ? sin_steer : zero;
    const V fxv = hn::Sub(hn::Mul(cd, fl), hn::Mul(sd, fs));
    const V fyv = hn::Add(hn::Mul(sd, fl), hn::Mul(cd, fs));
    fx = hn::Add(fx, fxv);
    fy = hn::Add(fy, fyv);
    mz = hn::Add(mz, hn::Sub(hn::Mul(hn::Set(d, xw), fyv), hn::Mul(hn::Set(d, yw), fxv)));
  }
  const V mass = hn::Set(d, p.mass_kg);
  Derivative<V> out;
  out.v_dot = hn::Div(hn::Add(hn::Mul(fx, cb), hn::Mul(fy, sb)), mass);
  out.beta_dot =
      hn::Sub(hn::Div(hn::Add(hn::Mul(hn::Neg(fx), sb), hn::Mul(fy, cb)), hn::Mul(mass, v)), yr);
  out.yaw_acc = hn::Div(mz, hn::Set(d, p.yaw_inertia_kgm2));
  return out;
}

// core::Clamp per lane.
template <class V>
V ClampV(V x, V lo, V hi) {
  return hn::Min(hn::Max(x, lo), hi);
}

// core::OneTrackDerivative per lane.
template <class D, class V = hn::Vec<D>>
Derivative<V> OneTrack(D d, const core::VehicleParams& p, V v, V beta, V yr, V steer, V v_dot) {
  const double m = p.mass_kg, iz = p.yaw_inertia_kgm2;
  const double cf = p.cf_npr, cr = p.cr_npr, lf = p.lf_m, lr = p.lr_m;
  const V mv = hn::Mul(hn::Set(d, m), v);
  Derivative<V> out;
  if (p.friction_limited) {
    const V zero = hn::Zero(d);
    const double mu_g = p.friction * core::kGravity;
    const V ax = ClampV(v_dot, hn::Set(d, -mu_g), hn::Set(d, mu_g));
    const V r = hn::Div(ax, hn::Set(d, mu_g));
    const V left = hn::Sub(hn::Set(d, 1.0), hn::Mul(r, r));
    const V side = hn::Mul(hn::Set(d, p.friction),
                           hn::Sqrt(hn::IfThenElse(hn::Lt(zero, left), left, zero)));
    const double wheelbase = lf + lr;
    const double weight_per_l = m * core::kGravity / wheelbase;
    const V f_max = hn::Mul(hn::Mul(side, hn::Set(d, weight_per_l)), hn::Set(d, lr));
    const V r_max = hn::Mul(hn::Mul(side, hn::Set(d, weight_per_l)), hn::Set(d, lf));
    const double gradient = core::Max(0.0, m * (cr * lr - cf * lf) / (cf * cr * wheelbase));
    const V vv = hn::Mul(v, v);
    const V steer_max = hn::Div(
        hn::Mul(hn::Mul(hn::Add(hn::Set(d, wheelbase), hn::Mul(hn::Mul(hn::Set(d, gradient), v), v)),
                        side),
                hn::Set(d, core::kGravity)),
        vv);
    const V st = ClampV(steer, hn::Neg(steer_max), steer_max);
    const V fyf = ClampV(
        hn::Mul(hn::Set(d, cf),
                hn::Sub(hn::Sub(st, beta), hn::Div(hn::Mul(hn::Set(d, lf), yr), v))),
        hn::Neg(f_max), f_max);
    const V fyr = ClampV(
        hn::Mul(hn::Set(d, cr), hn::Add(hn::Neg(beta), hn::Div(hn::Mul(hn::Set(d, lr), yr), v))),
        hn::Neg(r_max), r_max);
    out.v_dot = ax;
    out.beta_dot = hn::Sub(hn::Div(hn::Add(fyf, fyr), mv), yr);
    out.yaw_acc = hn::Div(hn::Sub(hn::Mul(hn::Set(d, lf), fyf), hn::Mul(hn::Set(d, lr), fyr)),
                          hn::Set(d, iz));
    return out;
  }
  out.v_dot = v_dot;
  const V b1 = hn::Mul(hn::Div(hn::Set(d, -(cf + cr)), mv), beta);
  const V b2 = hn::Mul(hn::Sub(hn::Div(hn::Set(d, cr * lr - cf * lf), hn::Mul(mv, v)),
                               hn::Set(d, 1.0)),
                       yr);
  const V b3 = hn::Mul(hn::Div(hn::Set(d, cf), mv), steer);
  out.beta_dot = hn::Add(hn::Add(b1, b2), b3);
  const V y1 = hn::Mul(hn::Set(d, (cr * lr - cf * lf) / iz), beta);
  const V y2 = hn::Mul(hn::Div(hn::Set(d, cf * lf * lf + cr * lr * lr), hn::Mul(hn::Set(d, iz), v)),
                       yr);
  const V y3 = hn::Mul(hn::Set(d, cf * lf / iz), steer);
  out.yaw_acc = hn::Add(hn::Sub(y1, y2), y3);
  return out;
}

// Step n's poses of lanes [first, first + count) into the span (c, s unless bc is null). With
// held poses (HypothesisSet::pose_hold_steps, core::HoldPose), a step the world does not look at
// stores each lane's held pose, and a step it looks at keeps the pose as the lane's held one,
// except for a lane whose speed bv[l] is 0 there with HypothesisSet::hold_stops (it stays).
HWY_INLINE void StorePoses(SiblingSpan* span, int first, int count, int n, const double* bx,
                           const double* by, const double* byaw, const double* bc,
                           const double* bs, const double* bv) {
  const int hold = span->h->pose_hold_steps;
  const bool seen = hold <= 1 || (n + 1) % hold == 0;
  const bool stops = hold > 1 && seen && span->h->hold_stops;
  if (!seen || stops) {
    for (int l = 0; l < count; ++l) {
      if (seen && bv[l] != 0.0) continue;  // moving at a step the world looks at: below
      core::SimulationState& st = span->state[first + l];
      st.pose_x = bx[l];  // where the step left it (core::VehicleStep)
      st.pose_y = by[l];
      span->x[first + l][n] = st.held_x;
      span->y[first + l][n] = st.held_y;
      span->yaw[first + l][n] = st.held_yaw;
      if (bc) {
        span->c[first + l][n] = st.held_c;
        span->s[first + l][n] = st.held_s;
      }
    }
    if (!seen) return;
  }
  for (int l = 0; l < count; ++l) {
    if (stops && bv[l] == 0.0) continue;  // it stays where the world last saw it (above)
    span->state[first + l].pose_x = bx[l];
    span->state[first + l].pose_y = by[l];
    if (hold > 1) {
      core::SimulationState& st = span->state[first + l];
      st.held_x = bx[l];
      st.held_y = by[l];
      st.held_yaw = byaw[l];
      if (bc) {
        st.held_c = bc[l];
        st.held_s = bs[l];
      }
    }
    span->x[first + l][n] = bx[l];
    span->y[first + l][n] = by[l];
    span->yaw[first + l][n] = byaw[l];
    if (bc) {
      span->c[first + l][n] = bc[l];
      span->s[first + l][n] = bs[l];
    }
  }
}

// Steps [n, n_end) of lanes [first, first + count) hold the pose of step n - 1 (c, s unless bc
// is null).
void HoldPoses(SiblingSpan* span, int first, int count, int n, const double* bx, const double* by,
               const double* byaw, const double* bc, const double* bs) {
  const int n_end = span->n_end;
  for (int l = 0; l < count; ++l) {
    std::fill(span->x[first + l] + n, span->x[first + l] + n_end, bx[l]);
    std::fill(span->y[first + l] + n, span->y[first + l] + n_end, by[l]);
    std::fill(span->yaw[first + l] + n, span->yaw[first + l] + n_end, byaw[l]);
    if (bc) {
      std::fill(span->c[first + l] + n, span->c[first + l] + n_end, bc[l]);
      std::fill(span->s[first + l] + n, span->s[first + l] + n_end, bs[l]);
    }
  }
}

// A standstill for good, exactly (issue 23: about half of a city fleet's egos wait at a light
// or in a queue, and most of their profiles brake). A lane whose state after a step has speed,
// acceleration and yaw rate all 0, below the seam speed (the kinematic model), and whose demand
// stays <= 0 to the horizon (its ramp between the value now and a target <= 0) goes on storing
// the same pose: each later step adds a speed times tau and accelerations times tau^2 / 2 that
// are all (signed) 0, turns the yaw by 0 (so the heading's cos/sin by angle addition stay, and
// the sagitta of a body on its path is 0), NonReversingAccel keeps v at 0, and the shift along
// the course (v - v0) * position_lead is 0 when v0 = 0 or there is none. Only the steering
// angle and the kinematic sideslip would move, and they move no pose while v stays 0; the
// lanes' end states keep the values of the step where the standstill began (the children of a
// tree node start from them, and stand as well: their profile is the same). With held poses
// (pose_hold_steps > 1) a lane stands for good only where it stands at its held pose
// (StandsAtHeldPose): every later step, held or not, is then that pose.
bool StandstillMayHold(const core::HypothesisSet& h) {
  return h.seam_speed > 0.0 && h.rate >= 0.0 && (h.position_lead <= 0.0 || h.v0 == 0.0) &&
         (h.pose_hold_steps <= 1 || h.v0 == 0.0);  // held poses: the same pose throughout
}

// With held poses: whether lanes [first, first + count) stand where their held pose is (centre
// and yaw, bit for bit), as a vehicle that has not moved since the world last looked does. Then
// the held pose's cos/sin go into bc, bs for the steps to come: the step's own cos/sin of the
// same yaw come by angle addition from the frame's and may differ from the held ones (cos of
// the yaw) in the last bit, and a pose that changes in its last bit is not still to the
// still-subtree shortcut of the collision walk (CpuBackend::RecognizeCollisions).
bool StandsAtHeldPose(SiblingSpan* span, int first, int count, const double* bx, const double* by,
                      const double* byaw, double* bc, double* bs) {
  for (int l = 0; l < count; ++l) {
    const core::SimulationState& st = span->state[first + l];
    if (bx[l] != st.held_x || by[l] != st.held_y || byaw[l] != st.held_yaw) return false;
  }
  if (bc == nullptr) return true;
  for (int l = 0; l < count; ++l) {
    bc[l] = span->state[first + l].held_c;
    bs[l] = span->state[first + l].held_s;
  }
  return true;
}

// Whether every lane's state after a step is at rest (the rest of the rule: StandstillMayHold
// and the demand, checked by the caller).
template <class D, class V = hn::Vec<D>>
HWY_INLINE bool StandsStill(D d, V v, V ax, V ay, V yaw_rate) {
  const V zero = hn::Zero(d);
  const auto still = hn::And(hn::And(hn::Eq(v, zero), hn::Eq(ax, zero)),
                             hn::And(hn::Eq(ay, zero), hn::Eq(yaw_rate, zero)));
  return hn::AllTrue(d, still);
}

// Lanes [first, first + count) of the span, count <= Lanes(d); the vector's other lanes repeat
// lane `first` and are never written back.
template <class D>
void SimulateChunk(D d, SiblingSpan* span, int first, int count) {
  using V = hn::Vec<D>;
  const core::HypothesisSet& h = *span->h;
  const core::SimulationConfig& cfg = *span->cfg;
  const core::ControllerLimits& ctl = cfg.controller;
  const core::VehicleParams& p = h.vehicle;
  const size_t N = hn::Lanes(d);
  const double tau = cfg.tau;
  auto lane_of = [&](size_t l) { return first + static_cast<int>(l < size_t(count) ? l : 0); };
  // Each lane's profile target; the lanes may come from different profiles of the set (the
  // ego's tree nodes of one level are packed across profiles).
  double target[kBuf];
  for (size_t l = 0; l < N; ++l) target[l] = h.profile_target[span->profile[lane_of(l)]];
  bool uniform = true;
  for (size_t l = 1; l < N; ++l) uniform = uniform && target[l] == target[0];
  core::StepContext ctx = core::MakeStepContext(h);
  const double mu_g = ctx.mu_g;
  core::StepContext lane_ctx[kBuf];  // each lane's slip-factor cache (mixed profiles)
  for (size_t l = 0; l < N; ++l) lane_ctx[l] = ctx;

  Lanes L;
  for (size_t l = 0; l < N; ++l) ToLanes(span->state[lane_of(l)], l, &L);
  int instant = span->state[first].instant;

  // Constants of the controller (SteeringCommand).
  const double feedforward = h.steer_feedforward ? p.lf_m + p.lr_m : 0.0;
  const double rate_step = ctl.max_steer_rate_radps * tau;
  const double half_tau2 = 0.5 * tau * tau;
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0), two = hn::Set(d, 2.0);
  const V vtau = hn::Set(d, tau);
  const V neg_pi = hn::Set(d, -core::kPi), pi = hn::Set(d, core::kPi);

  {
    const V yaw0 = hn::LoadU(d, L.yaw);
    hn::StoreU(hn::Cos(d, yaw0), d, L.cyaw);
    hn::StoreU(hn::Sin(d, yaw0), d, L.syaw);
  }
  const bool heading_trig = span->c[first] != nullptr;
  // The last stored pose of each lane, in the scene frame (kept for a standstill, below).
  double bx[kBuf], by[kBuf], byaw[kBuf], bc[kBuf], bs[kBuf];
  // Whether a standstill for good can hold for this set (then the rest of a span holds a pose).
  const bool can_stand = StandstillMayHold(h);
  int section_key = -2;  // (latent, instant) the section lanes were filled for
  for (int n = span->n_begin; n < span->n_end; ++n) {
    const double t = n * tau;
    instant = core::InstantAt(h, instant, t);
    const bool latent = t < h.steer_latency;
    const int key = latent ? -1 : instant;
    if (key != section_key) {
      section_key = key;
      for (size_t l = 0; l < N; ++l) {
        const int lateral = core::SectionOfPath(h, span->path[lane_of(l)], instant);
        SectionToLanes(latent ? h.reference_path : h.section[instant][lateral], l, &L);
      }
    }
    const V v = hn::LoadU(d, L.v);
    {
      const V x = hn::LoadU(d, L.x), y = hn::LoadU(d, L.y), yaw = hn::LoadU(d, L.yaw);
      const V beta = hn::LoadU(d, L.beta), yr = hn::LoadU(d, L.yaw_rate);
      const V ax = hn::LoadU(d, L.ax), ay = hn::LoadU(d, L.ay);
      V cb, sb;
      SinCos(d, beta, &sb, &cb);
      const V cy = hn::LoadU(d, L.cyaw), sy = hn::LoadU(d, L.syaw);
      const V course_x = hn::Sub(hn::Mul(cy, cb), hn::Mul(sy, sb));
      const V course_y = hn::Add(hn::Mul(sy, cb), hn::Mul(cy, sb));

      // SteeringCommand on each lane's section.
      const V tp = hn::Min(hn::Max(hn::Mul(hn::Set(d, ctl.preview_s_per_mps), v),
                                   hn::Set(d, ctl.preview_min_s)),
                           hn::Set(d, ctl.preview_max_s));
      V xp = hn::Add(x, hn::Mul(hn::Mul(course_x, v), tp));
      V yp = hn::Add(y, hn::Mul(hn::Mul(course_y, v), tp));
      const V rot = hn::LoadU(d, L.rot);
      const V cr = hn::LoadU(d, L.cos_rot), sr = hn::LoadU(d, L.sin_rot);
      const auto rotated = hn::Ne(rot, zero);
      const V xr = hn::Add(hn::Mul(cr, xp), hn::Mul(sr, yp));
      const V yr_ = hn::Add(hn::Mul(hn::Neg(sr), xp), hn::Mul(cr, yp));
      xp = hn::IfThenElse(rotated, xr, xp);
      yp = hn::IfThenElse(rotated, yr_, yp);
      const V a = hn::LoadU(d, L.a), b = hn::LoadU(d, L.b), c = hn::LoadU(d, L.c);
      const V xs = hn::LoadU(d, L.x_start), xe = hn::LoadU(d, L.x_end);
      // x clamped to [x_start, x_end] as Parabola::Slope and Eval clamp it.
      const V xc = hn::IfThenElse(hn::Lt(xp, xs), xs, hn::IfThenElse(hn::Gt(xp, xe), xe, xp));
      const V two_a = hn::Mul(two, a);
      const V slope = hn::Add(hn::Mul(two_a, xc), b);
      const V eval = hn::Add(hn::Add(hn::Mul(hn::Add(hn::Mul(a, xc), b), xc), c),
                             hn::Mul(slope, hn::Sub(xp, xc)));
      const V q = hn::Add(one, hn::Mul(slope, slope));
      const V root_q = hn::Sqrt(q);
      const V d_path = hn::Div(hn::Sub(eval, yp), root_q);
      V e_psi = hn::Sub(hn::Add(AtanOf(d, slope), rot), yaw);
      if (!hn::AllTrue(d, hn::And(hn::Ge(e_psi, neg_pi), hn::Lt(e_psi, pi)))) {
        double e[kBuf];
        hn::StoreU(e_psi, d, e);
        for (size_t l = 0; l < N; ++l) e[l] = core::WrapAngle(e[l]);
        e_psi = hn::LoadU(d, e);
      }
      // PaperSteeringLawDeg
      const V g = hn::Abs(hn::Mul(hn::Add(hn::Mul(hn::Set(d, -0.018), v), hn::Set(d, 1.5)), d_path));
      V cmd = hn::Add(hn::Mul(hn::Add(g, hn::Set(d, 0.5)), d_path),
                      hn::Mul(hn::Add(hn::Neg(g), hn::Set(d, 9.5)),
                              hn::Mul(hn::Set(d, 3.8197), e_psi)));
      cmd = hn::Mul(cmd, hn::Set(d, core::kPi / 180.0));
      if (feedforward > 0.0) {
        const auto curved = hn::And(hn::Ge(xp, xs), hn::Le(xp, xe));
        const V kappa = hn::Div(hn::Mul(two, hn::IfThenElseZero(curved, a)), hn::Mul(q, root_q));
        cmd = hn::Add(cmd, AtanOf(d, hn::Mul(hn::Set(d, feedforward), kappa)));
      }
      cmd = hn::Min(hn::Max(cmd, hn::Set(d, -ctl.max_steer_rad)), hn::Set(d, ctl.max_steer_rad));
      const V prev = hn::LoadU(d, L.steer);
      const V steer = hn::Min(hn::Max(cmd, hn::Sub(prev, hn::Set(d, rate_step))),
                              hn::Add(prev, hn::Set(d, rate_step)));

      // Longitudinal demand (each lane's profile's; one value when the lanes share a profile):
      // the slip factor the two-track model gets (unless profiles are forces) or the one-track
      // model's m/s^2, then the drive's limit (per lane) where it drives, and the derivative.
      const bool two_track = h.model == core::MotionModelKind::kTwoTrack;
      const size_t distinct = uniform ? 1 : N;
      double demand[kBuf];
      bool drives = false;
      bool brakes_for_good = true;  // every lane's demand <= 0 from now to the horizon
      const DemandTable* table = span->demands;
      for (size_t l = 0; l < distinct; ++l) {
        double a;
        if (table) {
          const size_t at = static_cast<size_t>(span->profile[lane_of(l)]) * table->steps + n;
          a = table->ramp[at];
          demand[l] = table->demand[at];
        } else {
          a = core::RampedValue(t, h.profile_start, target[l], h.latency, h.rate);
          demand[l] = two_track && !h.force_profiles ? core::SlipFactor(&lane_ctx[l], a) : a;
        }
        drives = drives || demand[l] > 0.0;
        brakes_for_good = brakes_for_good && a <= 0.0 && target[l] <= 0.0;
      }
      V lon_demand = uniform ? hn::Set(d, demand[0]) : hn::LoadU(d, demand);
      if (h.power_limited && drives) {
        V cap = DriveLimit(d, h, v);
        if (two_track) cap = hn::Div(cap, hn::Set(d, mu_g));
        lon_demand = hn::IfThenElse(hn::And(hn::Gt(lon_demand, zero), hn::Lt(cap, lon_demand)), cap,
                                    lon_demand);
      }
      Derivative<V> der;
      // cos/sin of the steering angle: the two-track model's, and the kinematic model's below
      // the seam speed (computed once for both).
      V cos_steer = zero, sin_steer = zero;
      bool steer_trig = false;
      // Below the seam speed: core::KinematicSingleTrack, which sets the sideslip and the yaw
      // rate itself (the dynamic model's numbers are dropped in those lanes, so where every
      // lane is below it, as when a waiting vehicle starts, the dynamic model is not run).
      const auto kin = hn::Lt(v, hn::Set(d, h.seam_speed));
      if (hn::AllTrue(d, kin)) {
        der = Derivative<V>{zero, zero, zero};
      } else if (two_track) {
        SinCos(d, steer, &sin_steer, &cos_steer);
        steer_trig = true;
        der = TwoTrack(d, p, v, yr, cb, sb, steer, cos_steer, sin_steer, lon_demand);
      } else {
        der = OneTrack(d, p, v, beta, yr, steer, lon_demand);
      }
      V v_dot = der.v_dot, beta_dot = der.beta_dot, yaw_acc = der.yaw_acc;
      V beta_e = beta, yr_e = yr, cb_e = cb, sb_e = sb, course_xe = course_x, course_ye = course_y;
      if (!hn::AllFalse(d, kin)) {
        V kv_dot = h.model == core::MotionModelKind::kTwoTrack
                       ? hn::Mul(hn::Set(d, mu_g), lon_demand)
                       : lon_demand;
        const double wheelbase = p.lf_m + p.lr_m;
        if (!steer_trig) SinCos(d, steer, &sin_steer, &cos_steer);
        V tan_steer = hn::Div(sin_steer, cos_steer);
        if (p.friction_limited) {
          kv_dot = ClampV(kv_dot, hn::Set(d, -mu_g), hn::Set(d, mu_g));
          const V room = hn::Sub(hn::Set(d, mu_g * mu_g), hn::Mul(kv_dot, kv_dot));
          const V lateral = hn::Sqrt(hn::IfThenElse(hn::Lt(zero, room), room, zero));
          const V v2 = hn::Mul(v, v);
          const V lw = hn::Mul(lateral, hn::Set(d, wheelbase));
          const auto over = hn::Gt(hn::Mul(v2, hn::Abs(tan_steer)), lw);
          tan_steer = hn::IfThenElse(over, hn::CopySign(hn::Div(lw, v2), tan_steer), tan_steer);
        }
        const V kbeta =
            AtanOf(d, hn::Div(hn::Mul(hn::Set(d, p.lr_m), tan_steer), hn::Set(d, wheelbase)));
        V kcb, ksb;
        SinCos(d, kbeta, &ksb, &kcb);
        const V kyr = hn::Div(hn::Mul(hn::Mul(v, kcb), tan_steer), hn::Set(d, wheelbase));
        v_dot = hn::IfThenElse(kin, kv_dot, v_dot);
        beta_dot = hn::IfThenElseZero(hn::Not(kin), beta_dot);
        yaw_acc = hn::IfThenElseZero(hn::Not(kin), yaw_acc);
        beta_e = hn::IfThenElse(kin, kbeta, beta);
        yr_e = hn::IfThenElse(kin, kyr, yr);
        cb_e = hn::IfThenElse(kin, kcb, cb);
        sb_e = hn::IfThenElse(kin, ksb, sb);
        course_xe = hn::Sub(hn::Mul(cy, cb_e), hn::Mul(sy, sb_e));
        course_ye = hn::Add(hn::Mul(sy, cb_e), hn::Mul(cy, sb_e));
      }

      // TopSpeedAccel, then NonReversingAccel.
      const V top = hn::Set(d, h.top_speed);
      const auto too_fast = hn::And(hn::Gt(v_dot, zero), hn::Gt(hn::Add(v, hn::Mul(v_dot, vtau)), top));
      V room = hn::Div(hn::Sub(top, v), vtau);
      room = hn::IfThenElseZero(hn::Gt(room, zero), room);
      v_dot = hn::IfThenElse(too_fast, room, v_dot);
      v_dot = hn::IfThenElse(hn::Lt(hn::Add(v, hn::Mul(v_dot, vtau)), zero),
                             hn::Div(hn::Neg(v), vtau), v_dot);

      // EulerStep
      const V h2 = hn::Set(d, half_tau2);
      const V nx = hn::Sub(hn::Add(hn::Add(x, hn::Mul(hn::Mul(course_xe, v), vtau)),
                                   hn::Mul(hn::Mul(cy, ax), h2)),
                           hn::Mul(hn::Mul(sy, ay), h2));
      const V ny = hn::Add(hn::Add(hn::Add(y, hn::Mul(hn::Mul(course_ye, v), vtau)),
                                   hn::Mul(hn::Mul(sy, ax), h2)),
                           hn::Mul(hn::Mul(cy, ay), h2));
      const V turn = hn::Mul(v, hn::Add(beta_dot, yr_e));
      const V nax = hn::Sub(hn::Mul(cb_e, v_dot), hn::Mul(sb_e, turn));
      const V nay = hn::Add(hn::Mul(sb_e, v_dot), hn::Mul(cb_e, turn));
      const V nyaw = hn::Add(hn::Add(yaw, hn::Mul(yr_e, vtau)), hn::Mul(yaw_acc, h2));
      const V nyr = hn::Add(yr_e, hn::Mul(yaw_acc, vtau));
      V nv = hn::Add(v, hn::Mul(v_dot, vtau));
      const V nbeta = hn::Add(beta_e, hn::Mul(beta_dot, vtau));
      nv = hn::IfThenElse(hn::Lt(nv, zero), zero, nv);  // rounding guard
      const V travelled = hn::Add(hn::LoadU(d, L.travelled), hn::Mul(nv, vtau));
      hn::StoreU(nx, d, L.x);
      hn::StoreU(ny, d, L.y);
      hn::StoreU(nyaw, d, L.yaw);
      hn::StoreU(nv, d, L.v);
      hn::StoreU(nbeta, d, L.beta);
      hn::StoreU(nyr, d, L.yaw_rate);
      hn::StoreU(nax, d, L.ax);
      hn::StoreU(nay, d, L.ay);
      hn::StoreU(steer, d, L.steer);
      hn::StoreU(travelled, d, L.travelled);

      // StorePose
      V px = nx, py = ny;
      // core::BodyCurvature, once for the shift along the way and the body on its path.
      V kappa = zero;
      if (h.position_lead > 0.0 || h.body_on_path)
        kappa = hn::IfThenElse(hn::Gt(nv, one), hn::Div(nyr, nv), hn::Mul(nyr, nv));
      if (h.position_lead > 0.0) {  // core::ShiftAlongPath
        const V shift = hn::Mul(hn::Sub(nv, hn::Set(d, h.v0)), hn::Set(d, h.position_lead));
        const V phi = ClampV(hn::Mul(kappa, shift), hn::Set(d, -core::kMaxShiftTurnRad),
                             hn::Set(d, core::kMaxShiftTurnRad));
        const auto straight = hn::Eq(phi, zero);
        const V r = hn::Div(shift, hn::IfThenElse(straight, one, phi));
        V s_half, c_half;
        SinCos(d, hn::Mul(hn::Set(d, 0.5), phi), &s_half, &c_half);
        const V two_s = hn::Mul(two, s_half);
        const V along = hn::IfThenElse(straight, shift, hn::Mul(hn::Mul(two_s, c_half), r));
        const V across = hn::IfThenElseZero(hn::Not(straight), hn::Mul(hn::Mul(two_s, s_half), r));
        px = hn::Add(px, hn::Sub(hn::Mul(course_xe, along), hn::Mul(course_ye, across)));
        py = hn::Add(py, hn::Add(hn::Mul(course_ye, along), hn::Mul(course_xe, across)));
      }
      if (h.body_on_path) {  // core::PathSagitta of core::BodyCurvature, across the course
        const double c = 2.0 * h.half_length, limit = 2.0 / c;
        const V e = hn::Mul(ClampV(kappa, hn::Set(d, -limit), hn::Set(d, limit)),
                            hn::Set(d, 0.125 * c * c));
        px = hn::Sub(px, hn::Mul(course_ye, e));
        py = hn::Add(py, hn::Mul(course_xe, e));
      }
      const V c0 = hn::Set(d, ctx.c0), s0 = hn::Set(d, ctx.s0);
      V wx = hn::Sub(hn::Add(hn::Set(d, h.X_WL.x), hn::Mul(c0, px)), hn::Mul(s0, py));
      V wy = hn::Add(hn::Add(hn::Set(d, h.X_WL.y), hn::Mul(s0, px)), hn::Mul(c0, py));
      const auto gone = hn::Gt(travelled, hn::Set(d, h.leave_distance));
      wx = hn::IfThenElse(gone, hn::Set(d, core::GoneX(h)), wx);
      wy = hn::IfThenElseZero(hn::Not(gone), wy);
      const V wyaw = hn::Add(hn::Set(d, h.X_WL.yaw), nyaw);
      // cos/sin of the new yaw: the next step's, and (turned by the frame's) the pose's.
      // The yaw turns by a small angle per step: the new cos/sin by angle addition.
      V cturn, sturn;
      SinCos(d, hn::Sub(nyaw, yaw), &sturn, &cturn);
      const V ncy = hn::Sub(hn::Mul(cy, cturn), hn::Mul(sy, sturn));
      const V nsy = hn::Add(hn::Mul(sy, cturn), hn::Mul(cy, sturn));
      hn::StoreU(ncy, d, L.cyaw);
      hn::StoreU(nsy, d, L.syaw);
      if (heading_trig) {
        hn::StoreU(hn::Sub(hn::Mul(c0, ncy), hn::Mul(s0, nsy)), d, bc);
        hn::StoreU(hn::Add(hn::Mul(s0, ncy), hn::Mul(c0, nsy)), d, bs);
      }
      hn::StoreU(wx, d, bx);
      hn::StoreU(wy, d, by);
      hn::StoreU(wyaw, d, byaw);
      StorePoses(span, first, count, n, bx, by, byaw, heading_trig ? bc : nullptr, bs, L.v);
      if (can_stand && brakes_for_good && StandsStill(d, nv, nax, nay, nyr) &&
          (h.pose_hold_steps <= 1 ||
           StandsAtHeldPose(span, first, count, bx, by, byaw, heading_trig ? bc : nullptr, bs))) {
        // The rest of the span holds this pose; the instants still advance as step by step.
        for (int m = n + 1; m < span->n_end; ++m) instant = core::InstantAt(h, instant, m * tau);
        HoldPoses(span, first, count, n + 1, bx, by, byaw, heading_trig ? bc : nullptr, bs);
        break;
      }
    }
  }
  for (int l = 0; l < count; ++l) {
    FromLanes(L, l, &span->state[first + l]);
    span->state[first + l].instant = instant;
  }
}

void SiblingStepsImpl(SiblingSpan* span) {
  const hn::ScalableTag<double> d;
  const int N = static_cast<int>(hn::Lanes(d));
  for (int first = 0; first < span->lanes; first += N) {
    SimulateChunk(d, span, first, span->lanes - first < N ? span->lanes - first : N);
  }
}

void CosSinImpl(const double* a, size_t n, double* c, double* s) {
  const hn::ScalableTag<double> d;
  const size_t N = hn::Lanes(d);
  size_t i = 0;
  hn::Vec<decltype(d)> vc, vs;
  for (; i + N <= n; i += N) {
    SinCos(d, hn::LoadU(d, a + i), &vs, &vc);
    hn::StoreU(vc, d, c + i);
    hn::StoreU(vs, d, s + i);
  }
  if (i < n) {  // the tail through the same vector code
    double va[kBuf] = {}, bc[kBuf], bs[kBuf];
    std::memcpy(va, a + i, (n - i) * sizeof(double));
    SinCos(d, hn::LoadU(d, va), &vs, &vc);
    hn::StoreU(vc, d, bc);
    hn::StoreU(vs, d, bs);
    std::memcpy(c + i, bc, (n - i) * sizeof(double));
    std::memcpy(s + i, bs, (n - i) * sizeof(double));
  }
}

const char* TargetImpl() { return hwy::TargetName(HWY_TARGET); }

}  // namespace HWY_NAMESPACE
}  // namespace criticality::internal
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace criticality::internal {

HWY_EXPORT(SiblingStepsImpl);
HWY_EXPORT(CosSinImpl);
HWY_EXPORT(TargetImpl);

bool SiblingStepsApply(const core::HypothesisSet& h, const core::SimulationConfig& cfg) {
  return h.model != core::MotionModelKind::kPedestrian && !h.on_track && !h.on_way &&
         cfg.controller.feedback &&
         h.n_lateral <= core::kMaxLateralSamples &&
         (h.combine_sections || h.n_paths <= core::kMaxLateralSamples);
}

DemandTable DemandsOf(const core::HypothesisSet& h, const core::SimulationConfig& cfg) {
  DemandTable table;
  table.steps = cfg.n_steps;
  const size_t n_all = static_cast<size_t>(h.n_profiles) * cfg.n_steps;
  table.ramp.resize(n_all);
  table.demand.resize(n_all);
  const bool slip = h.model == core::MotionModelKind::kTwoTrack && !h.force_profiles;
  for (int profile = 0; profile < h.n_profiles; ++profile) {
    const double target = h.profile_target[profile];
    for (int n = 0; n < cfg.n_steps; ++n) {
      const double t = n * cfg.tau;  // as SimulateChunk's step
      const double a = core::RampedValue(t, h.profile_start, target, h.latency, h.rate);
      const size_t at = static_cast<size_t>(profile) * cfg.n_steps + n;
      table.ramp[at] = a;
      table.demand[at] = slip ? core::LongitudinalForceFactor(a) : a;  // core::SlipFactor's
    }
  }
  return table;
}

void SimulateSiblingSteps(SiblingSpan* span) { HWY_DYNAMIC_DISPATCH(SiblingStepsImpl)(span); }

void SimulateProfilePaths(const core::HypothesisSet& h, const core::SimulationConfig& cfg,
                          int profile, double* x, double* y, double* yaw, size_t stride, double* c,
                          double* s) {
  SiblingSpan span = SpanOf(h, cfg, profile, 0, cfg.n_steps, h.n_paths);
  const core::SimulationState start = core::InitialSimulationState(h, cfg);
  for (int path = 0; path < h.n_paths; ++path) {
    const size_t at = static_cast<size_t>(path) * stride;
    SetLane(&span, path, path, start, x + at, y + at, yaw + at, c ? c + at : nullptr,
            s ? s + at : nullptr);
  }
  SimulateSiblingSteps(&span);
}

void CosSin(const double* a, size_t n, double* c, double* s) {
  HWY_DYNAMIC_DISPATCH(CosSinImpl)(a, n, c, s);
}

const char* SiblingStepsTarget() { return HWY_DYNAMIC_DISPATCH(TargetImpl)(); }

}  // namespace criticality::internal
#endif  // HWY_ONCE
