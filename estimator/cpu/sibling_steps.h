#pragma once
// Paths in SIMD lanes (issue 23). The ego's section-tree nodes of one level, across profiles
// (each from its parent's end state, tracking its own section over the level's span) and
// another vehicle's paths of one profile (each with its own lateral sample) are simulated
// together, one path per lane of the widest vector unit the CPU has (Highway's run-time
// dispatch: AVX-512, AVX2, SSE4, NEON, ... from one source), through the same steps as
// core::VehicleStep (controller, two-track or one-track model, the kinematic model below the
// seam speed, lane by lane through masks, Euler step, pose), with the same arithmetic in the
// same order; only sin, cos, atan and tan (as sin / cos) differ from libm's: Highway's vector
// math (within 3 ulp), or for angles within 0.35 rad their Taylor series (within 2 ulp), and
// the new yaw's cos/sin by angle addition from the step before's. An angle that needs wrapping
// is wrapped lane by lane by core::WrapAngle.
//
// CosSin is the same vector math over an array (the poses' cos/sin for the box tests).
#include <cstddef>
#include <vector>

#include "core/hypothesis_set.h"
#include "core/trajectory_generation.h"

namespace criticality::internal {

/** Up to kMaxLateralSamples paths of one vehicle hypothesis set, each lane with its profile,
 *  over steps [n_begin, n_end). Lane l starts from state[l] (left there at the end) and writes the
 * pose of step n to x[l][n], y[l][n], yaw[l][n]. */
struct SiblingSpan {
  const core::HypothesisSet* h{nullptr};
  const core::SimulationConfig* cfg{nullptr};
  /** Each lane's profile of h (SpanOf sets one for all; the ego's tree nodes of one level
   *  are packed across profiles). */
  int profile[core::kMaxLateralSamples]{};
  int n_begin{0}, n_end{0};
  int lanes{0};
  int path[core::kMaxLateralSamples]{};
  core::SimulationState state[core::kMaxLateralSamples];
  double* x[core::kMaxLateralSamples]{};
  double* y[core::kMaxLateralSamples]{};
  double* yaw[core::kMaxLateralSamples]{};
  /** Optional (null: not written): cos and sin of the scene-frame heading of step n, to
   *  c[l][n] and s[l][n], from the cos/sin of the local yaw that the next step uses anyway,
   *  turned by the local frame's (the angle-sum identity: within a few ulp of cos(yaw)). */
  double* c[core::kMaxLateralSamples]{};
  double* s[core::kMaxLateralSamples]{};
  /** Optional (null: each lane's computed at each step): every profile's longitudinal demand
   *  by step, as DemandTable gives it, for spans whose lanes mix profiles (the ego's tree). */
  const struct DemandTable* demands{nullptr};
};

/** Each profile's longitudinal demand at each step n of cfg.n_steps (t = n tau), as
 *  core::VehicleStep takes it: `ramp` the profile's ramped value (core::RampedValue), `demand`
 *  what the model gets (the two-track model's slip factor unless profiles are forces). Computed
 *  once per estimate, so that a vector of lanes from several profiles loads its demands
 *  instead of computing each lane's at each step; the same values bit for bit. */
struct DemandTable {
  int steps{0};
  std::vector<double> ramp, demand;  ///< [profile * steps + n]
};
DemandTable DemandsOf(const core::HypothesisSet& h, const core::SimulationConfig& cfg);

/** A span of `lanes` paths of (h, profile) over steps [n_begin, n_end); the caller sets each
 *  lane's path, start state and pose arrays. */
inline SiblingSpan SpanOf(const core::HypothesisSet& h, const core::SimulationConfig& cfg,
                          int profile, int n_begin, int n_end, int lanes) {
  SiblingSpan span;
  span.h = &h;
  span.cfg = &cfg;
  for (int& p : span.profile) p = profile;
  span.n_begin = n_begin;
  span.n_end = n_end;
  span.lanes = lanes;
  return span;
}

/** Lane l of `span`: `path` from `start`, its poses written from x, y, yaw (and, when c and s
 *  are given, the heading's cos/sin) at index n_begin on. */
inline void SetLane(SiblingSpan* span, int l, int path, const core::SimulationState& start,
                    double* x, double* y, double* yaw, double* c = nullptr, double* s = nullptr) {
  span->path[l] = path;
  span->state[l] = start;
  span->x[l] = x;
  span->y[l] = y;
  span->yaw[l] = yaw;
  span->c[l] = c;
  span->s[l] = s;
}

/** Every path of (h, profile) from the set's initial state over cfg.n_steps steps, together
 *  in SIMD lanes (requires SiblingStepsApply and h.n_paths <= kMaxLateralSamples): path p's
 *  poses to x, y, yaw + p * stride (and the heading's cos/sin to c, s + p * stride when given).
 *  Shared by the CPU backend's other road users and the reach shortcut. */
void SimulateProfilePaths(const core::HypothesisSet& h, const core::SimulationConfig& cfg,
                          int profile, double* x, double* y, double* yaw, size_t stride,
                          double* c = nullptr, double* s = nullptr);

/** Whether SimulateSiblingSteps covers this set: a two-track or one-track vehicle off any
 *  track with the lateral controller on; else simulate each path with
 *  core::SimulateVehicleSteps (pedestrians: core::SimulateHypothesis). */
bool SiblingStepsApply(const core::HypothesisSet& h, const core::SimulationConfig& cfg);

/** Simulates the span's lanes together (requires SiblingStepsApply). */
void SimulateSiblingSteps(SiblingSpan* span);

/** c[i] = cos(a[i]), s[i] = sin(a[i]) for i < n, with the vector math of SimulateSiblingSteps. */
void CosSin(const double* a, size_t n, double* c, double* s);

/** The vector target the dispatch chose on this CPU (e.g. "AVX3", "AVX2"), for reports. */
const char* SiblingStepsTarget();

}  // namespace criticality::internal
