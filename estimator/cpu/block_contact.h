#pragma once
// The box test of one collision block in SIMD lanes (issue 23): the steps of a block (at most
// kMaxBlockContactSteps) of one ego path and one CO trajectory go through core::BoxesOverlap's
// separating-axis test together, one step per lane of the widest vector unit the CPU has
// (Highway's run-time dispatch), with the same arithmetic in the same order: the same answer
// as the scalar test step by step, without its branches.
namespace criticality::internal {

constexpr int kMaxBlockContactSteps = 16;

/** One trajectory's poses (centre, cos and sin of the heading at step n: x[n], y[n], c[n],
 *  s[n]) and its box's half length and half width. */
struct BoxTrack {
  const double *x, *y, *c, *s;
  double half_length, half_width;
};

/** The first step n in [n0, n1) (n1 - n0 <= kMaxBlockContactSteps) at which a's and b's boxes
 *  overlap (core::BoxesOverlap), or -1. reach2: a squared distance between centres beyond
 *  which the boxes cannot overlap (the sum of their bounding radii, squared, or more): steps
 *  beyond it skip the box test. `readable`: how many values from x[0] (y[0], c[0], s[0]) of
 *  both tracks may be read (at least n1); steps past n1 are read where readable and ignored. */
using FirstOverlapFn = int (*)(const BoxTrack& a, const BoxTrack& b, int n0, int n1, double reach2,
                               long readable);

/** The best vector target's FirstOverlap, found once (call it through the pointer: the
 *  blocks are many and short). */
FirstOverlapFn FirstOverlapInBlock();

}  // namespace criticality::internal
