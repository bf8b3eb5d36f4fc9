#pragma once
// Event rates per exposure (warnings per vehicle-hour, collisions per million vehicle-km) with a
// 95 % interval across the runs of a group (the seeds and repetitions of one setting).
//
// The rate is pooled: the group's events over its exposure. Its interval treats each run as a
// cluster (ratio estimator): SE^2 = n/(n-1) * sum_i (c_i - R e_i)^2 / (sum_i e_i)^2, and
// R +- t(0.975, n-1) SE, clipped at 0; it says how much the rate moves from seed to seed. With
// fewer than two runs, or no event at all (a spread of nothing is no interval), it is the exact
// Poisson interval of the pooled count instead (Garwood: 0 events give 0 .. 3.69 / exposure).
#include <optional>
#include <string>
#include <vector>

namespace criticality::campaign {

/** One run of a group: its events and its exposure. */
struct RateSample {
  double events{0.0};
  double exposure{0.0};
};

struct Rate {
  std::size_t runs{0};
  double events{0.0};
  double exposure{0.0};
  std::optional<double> value, low, high;  ///< per unit of exposure; none without exposure
  std::string interval;                    ///< "runs" (across runs) or "poisson"
};

Rate RateOf(const std::vector<RateSample>& runs);

/** The 0.975 quantile of Student's t with `df` degrees of freedom (df >= 1). */
double StudentT975(double df);

/** The p-quantile of the chi-square distribution with `k` degrees of freedom (k > 0). */
double ChiSquareQuantile(double p, double k);

}  // namespace criticality::campaign
