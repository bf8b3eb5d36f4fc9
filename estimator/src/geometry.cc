// The public geometry (criticality/geometry.h) as calls of the core functions the estimator
// uses, so that both give the same bits (the project compiles with -ffp-contract=off, so an
// out-of-line copy rounds as an inlined one does).
#include "criticality/geometry.h"

#include "core/geometry.h"
#include "core/oriented_box.h"

namespace criticality {
namespace {

core::Pose2 ToCore(const Pose2& p) { return core::Pose2{p.x, p.y, p.yaw}; }

}  // namespace

static_assert(kPi == core::kPi, "one pi for the public and the core geometry");

double WrapAngle(double a) { return core::WrapAngle(a); }

void WorldToLocal(const Pose2& X_WL, double xw, double yw, double* xl, double* yl) {
  core::WorldToLocal(ToCore(X_WL), xw, yw, xl, yl);
}

void LocalToWorld(const Pose2& X_WL, double xl, double yl, double* xw, double* yw) {
  core::LocalToWorld(ToCore(X_WL), xl, yl, xw, yw);
}

bool RectanglesOverlap(const Pose2& a, double half_length_a, double half_width_a, const Pose2& b,
                       double half_length_b, double half_width_b) {
  return core::BoxesOverlap(core::MakeBox(a.x, a.y, a.yaw, half_length_a, half_width_a),
                            core::MakeBox(b.x, b.y, b.yaw, half_length_b, half_width_b));
}

}  // namespace criticality
