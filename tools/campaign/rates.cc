#include "tools/campaign/rates.h"

#include <algorithm>
#include <cmath>

namespace criticality::campaign {
namespace {

// Regularised lower incomplete gamma P(a, x) (series for x < a + 1, else continued fraction).
double GammaP(double a, double x) {
  if (x <= 0.0) return 0.0;
  const double log_front = a * std::log(x) - x - std::lgamma(a);
  if (x < a + 1.0) {
    double term = 1.0 / a, sum = term;
    for (int n = 1; n < 1000 && std::fabs(term) > 1e-15 * std::fabs(sum); ++n) {
      term *= x / (a + n);
      sum += term;
    }
    return std::min(1.0, sum * std::exp(log_front));
  }
  // Lentz's continued fraction for Q(a, x).
  const double tiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int n = 1; n < 1000; ++n) {
    const double an = -n * (n - a);
    b += 2.0;
    d = an * d + b;
    if (std::fabs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::fabs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::fabs(delta - 1.0) < 1e-15) break;
  }
  return std::max(0.0, 1.0 - std::exp(log_front) * h);
}

}  // namespace

double ChiSquareQuantile(double p, double k) {
  // Bisection on the distribution function P(k/2, x/2): monotone, and plenty fast here.
  double lo = 0.0, hi = std::max(1.0, k);
  while (GammaP(0.5 * k, 0.5 * hi) < p) hi *= 2.0;
  for (int i = 0; i < 200 && hi - lo > 1e-12 * std::max(1.0, hi); ++i) {
    const double mid = 0.5 * (lo + hi);
    (GammaP(0.5 * k, 0.5 * mid) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double StudentT975(double df) {
  // Tabulated quantiles, interpolated linearly in 1/df (exact at the table's points, within
  // 0.1 % between them); the normal's 1.96 as df grows.
  static const double kDf[] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 12, 15, 20, 25, 30, 40, 60, 120};
  static const double kT[] = {12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262,
                              2.228,  2.179, 2.131, 2.086, 2.060, 2.042, 2.021, 2.000, 1.980};
  const int n = sizeof kDf / sizeof kDf[0];
  if (df <= kDf[0]) return kT[0];
  for (int i = 1; i < n; ++i) {
    if (df <= kDf[i]) {
      const double u = (1.0 / df - 1.0 / kDf[i - 1]) / (1.0 / kDf[i] - 1.0 / kDf[i - 1]);
      return kT[i - 1] + u * (kT[i] - kT[i - 1]);
    }
  }
  const double u = (1.0 / df) / (1.0 / kDf[n - 1]);
  return 1.960 + u * (kT[n - 1] - 1.960);
}

Rate RateOf(const std::vector<RateSample>& runs) {
  Rate r;
  r.runs = runs.size();
  for (const RateSample& s : runs) {
    r.events += s.events;
    r.exposure += s.exposure;
  }
  if (!(r.exposure > 0.0)) return r;
  const double rate = r.events / r.exposure;
  r.value = rate;
  if (runs.size() >= 2 && r.events > 0.0) {
    double ss = 0.0;
    for (const RateSample& s : runs)
      ss += (s.events - rate * s.exposure) * (s.events - rate * s.exposure);
    const double n = static_cast<double>(runs.size());
    const double se = std::sqrt(n / (n - 1.0) * ss) / r.exposure;
    const double half = StudentT975(n - 1.0) * se;
    r.low = std::max(0.0, rate - half);
    r.high = rate + half;
    r.interval = "runs";
    return r;
  }
  const double k = std::round(r.events);
  r.low = k > 0.0 ? 0.5 * ChiSquareQuantile(0.025, 2.0 * k) / r.exposure : 0.0;
  r.high = 0.5 * ChiSquareQuantile(0.975, 2.0 * k + 2.0) / r.exposure;
  r.interval = "poisson";
  return r;
}

}  // namespace criticality::campaign
