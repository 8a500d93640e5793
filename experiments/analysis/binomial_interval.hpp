#pragma once
// A fraction k/n of orbits (the chaotic fraction of lgi chaos-map and lgi
// poincare) as an estimate of a phase-space fraction p, with the Wilson
// score interval (E. B. Wilson, "Probable inference, the law of succession,
// and statistical inference", J. Am. Stat. Assoc. 22 (1927) 209; its
// coverage: L. D. Brown, T. T. Cai and A. DasGupta, Statist. Sci. 16 (2001)
// 101): the p with |k − np| ≤ z √(np(1 − p)), z = 1.959964 for 95 %.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

namespace lgi::experiments {

struct BinomialInterval {
  double fraction = NAN, low = NAN, high = NAN;  // NaN for n = 0
};

/// The 95 % Wilson score interval of k successes in n trials.
inline BinomialInterval wilson_interval(std::int64_t k, std::int64_t n) {
  if (n <= 0) return {};
  constexpr double z = 1.959963984540054;  // the 0.975 quantile of the normal law
  const double nn = static_cast<double>(n), p = static_cast<double>(k) / nn, z2 = z * z;
  const double centre = (p + z2 / (2.0 * nn)) / (1.0 + z2 / nn);
  const double half = z / (1.0 + z2 / nn) * std::sqrt(p * (1.0 - p) / nn + z2 / (4.0 * nn * nn));
  // At k = 0 (n) the low (high) end is 0 (1) exactly; the formula leaves round-off.
  return {p, k == 0 ? 0.0 : centre - half, k == n ? 1.0 : centre + half};
}

/// "k/n = 0.700 [0.633, 0.759]": the count, the fraction and its interval.
inline std::string format_fraction(std::int64_t k, std::int64_t n) {
  const BinomialInterval w = wilson_interval(k, n);
  char b[96];
  std::snprintf(b, sizeof b, "%lld/%lld = %.3f [%.3f, %.3f]", static_cast<long long>(k), static_cast<long long>(n),
                w.fraction, w.low, w.high);
  return b;
}

}  // namespace lgi::experiments
