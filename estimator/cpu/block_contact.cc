// The box test of one collision block in SIMD lanes: see block_contact.h. Compiled once per
// vector target by Highway's foreach_target, with -ffp-contract=off: every expression mirrors
// core::BoxesOverlap's (same operands, same order, no fused multiply-add).
#include "cpu/block_contact.h"

#include <cstring>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "cpu/block_contact.cc"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace criticality::internal {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Lanes(d) values from p; from a zero-padded copy where fewer are readable.
template <class D>
HWY_INLINE hn::Vec<D> LoadSteps(D d, const double* p, long readable) {
  if (readable >= static_cast<long>(hn::Lanes(d))) return hn::LoadU(d, p);
  double buf[kMaxBlockContactSteps] = {};
  std::memcpy(buf, p, static_cast<size_t>(readable) * sizeof(double));
  return hn::LoadU(d, buf);
}

int FirstOverlapImpl(const BoxTrack& a, const BoxTrack& b, int n0, int n1, double reach2,
                     long readable) {
  const hn::ScalableTag<double> d;
  const int N = static_cast<int>(hn::Lanes(d));
  const auto ahl = hn::Set(d, a.half_length), ahw = hn::Set(d, a.half_width);
  const auto bhl = hn::Set(d, b.half_length), bhw = hn::Set(d, b.half_width);
  for (int n = n0; n < n1; n += N) {
    const long left = readable - n;
    const auto ax = LoadSteps(d, a.x + n, left), ay = LoadSteps(d, a.y + n, left);
    const auto bx = LoadSteps(d, b.x + n, left), by = LoadSteps(d, b.y + n, left);
    // Lanes past n1 do not count.
    const auto in_block = hn::FirstN(d, static_cast<size_t>(n1 - n));
    const auto dx = hn::Sub(bx, ax), dy = hn::Sub(by, ay);
    // Centres farther apart than `reach` cannot overlap: most blocks end here.
    const auto near =
        hn::And(in_block, hn::Le(hn::Add(hn::Mul(dx, dx), hn::Mul(dy, dy)), hn::Set(d, reach2)));
    if (hn::AllFalse(d, near)) continue;
    const auto ac = LoadSteps(d, a.c + n, left), as = LoadSteps(d, a.s + n, left);
    const auto bc = LoadSteps(d, b.c + n, left), bs = LoadSteps(d, b.s + n, left);
    // core::BoxesOverlap, lane by lane.
    const auto cd = hn::Abs(hn::Add(hn::Mul(ac, bc), hn::Mul(as, bs)));
    const auto sd = hn::Abs(hn::Sub(hn::Mul(as, bc), hn::Mul(ac, bs)));
    auto apart = hn::Gt(hn::Abs(hn::Add(hn::Mul(dx, ac), hn::Mul(dy, as))),
                        hn::Add(hn::Add(ahl, hn::Mul(bhl, cd)), hn::Mul(bhw, sd)));
    apart = hn::Or(apart, hn::Gt(hn::Abs(hn::Add(hn::Mul(hn::Neg(dx), as), hn::Mul(dy, ac))),
                                 hn::Add(hn::Add(ahw, hn::Mul(bhl, sd)), hn::Mul(bhw, cd))));
    apart = hn::Or(apart, hn::Gt(hn::Abs(hn::Add(hn::Mul(dx, bc), hn::Mul(dy, bs))),
                                 hn::Add(hn::Add(bhl, hn::Mul(ahl, cd)), hn::Mul(ahw, sd))));
    apart = hn::Or(apart, hn::Gt(hn::Abs(hn::Add(hn::Mul(hn::Neg(dx), bs), hn::Mul(dy, bc))),
                                 hn::Add(hn::Add(bhw, hn::Mul(ahl, sd)), hn::Mul(ahw, cd))));
    const intptr_t first = hn::FindFirstTrue(d, hn::AndNot(apart, near));
    if (first >= 0) return n + static_cast<int>(first);
  }
  return -1;
}

}  // namespace HWY_NAMESPACE
}  // namespace criticality::internal
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace criticality::internal {

HWY_EXPORT(FirstOverlapImpl);

FirstOverlapFn FirstOverlapInBlock() {
  static const FirstOverlapFn fn = [] {
    // A first call through the dispatch table chooses the target (the table's entries are
    // choosing stubs before it); then the chosen entry itself.
    const BoxTrack none{nullptr, nullptr, nullptr, nullptr, 0.0, 0.0};
    HWY_DYNAMIC_DISPATCH(FirstOverlapImpl)(none, none, 0, 0, 0.0, 0);
    return &(HWY_DYNAMIC_DISPATCH(FirstOverlapImpl));
  }();
  return fn;
}

}  // namespace criticality::internal
#endif  // HWY_ONCE
