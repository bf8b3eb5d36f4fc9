#pragma once
// Inline min/max/clamp for the hot paths (std::fmin/fmax are library calls on the host). Same
// results as fmin/fmax for numbers; NaN never reaches them (inputs are validated).
#include "core/hd.h"

namespace criticality::core {

CRIT_HD double Min(double a, double b) { return b < a ? b : a; }
CRIT_HD double Max(double a, double b) { return a < b ? b : a; }
CRIT_HD double Clamp(double x, double lo, double hi) { return Min(Max(x, lo), hi); }

}  // namespace criticality::core
