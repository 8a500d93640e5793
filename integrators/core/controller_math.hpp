#pragma once
// ln x and e^y for the adaptive pairs' step-size controller (rkmk_pair.hpp),
// from + − × ÷ and exact exponent arithmetic only, so that the steps a pair
// takes are the same bits on every machine. glibc's own log, exp and pow come
// in an FMA build and a non-FMA build, picked by the CPU, which round about
// one result in 1400 differently (experiments/io/libm_code_path.hpp); a
// controller that called them gave two machines different step sequences,
// and on HLW's top at tol 1e-8 attitudes 1.8e-5 apart after t = 3000 (about
// 12 000 steps; README, "Numerics policy"). Compiled with -ffp-contract=off like the rest.
//
// ln: x = 2^e m with m in [√½, √2), ln m = 2 atanh s = 2 (s + s³/3 + … + s⁹/9),
// s = (m − 1)/(m + 1), |s| ≤ 0.172 (the first omitted term, 2 s¹¹/11, is below
// 1e-9); ln x = e ln 2 + ln m. exp: y = k ln 2 + r with k the nearest integer
// to y/ln 2 and ln 2 split in two (Cody & Waite, Software Manual for the
// Elementary Functions, 1980, ch. 6), |r| ≤ 0.347, e^r by Taylor to r⁸/8!
// (the first omitted term below 3e-10 relative); e^y = 2^k e^r. A controller's
// factor needs a few digits, not 16: these short series cost no more than
// libm's calls (README, "Numerics policy"), and tests/test_controller_math.cpp
// holds them to 1e-9 of libm's. What matters is that they are the same bits
// on every CPU.
#include <array>
#include <bit>
#include <cstddef>
#include <cmath>
#include <cstdint>
#include <limits>

namespace lgi::integrators::controller_math {

namespace detail {

/// 2^k for an integer k in [−1022, 1023], built from its bits.
inline double power_of_two(int k) {
  return std::bit_cast<double>(static_cast<std::uint64_t>(k + 1023) << 52);
}

/// 1/(2k + 1), k = 0..4: the atanh series of log().
inline constexpr std::array<double, 5> odd_reciprocals = [] {
  std::array<double, 5> c{};
  for (std::size_t k = 0; k < c.size(); ++k) c[k] = 1.0 / static_cast<double>(2 * k + 1);
  return c;
}();
/// 1/n!, n = 0..8: the Taylor series of exp().
inline constexpr std::array<double, 9> inverse_factorials = [] {
  std::array<double, 9> c{};
  double f = 1.0;
  for (std::size_t n = 0; n < c.size(); ++n) {
    if (n > 0) f *= static_cast<double>(n);  // exact
    c[n] = 1.0 / f;
  }
  return c;
}();

inline constexpr double ln2_hi = 6.93147180369123816490e-01;  // ln 2 in 32 bits: k ln2_hi is exact (Cody & Waite)
inline constexpr double ln2_lo = 1.90821492927058770002e-10;  // ln 2 − ln2_hi

}  // namespace detail

/// ln x: −∞ at 0, NaN below 0 or for NaN, +∞ at +∞.
inline double log(double x) {
  if (!(x > 0.0)) return x == 0.0 ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::quiet_NaN();
  if (x == std::numeric_limits<double>::infinity()) return x;
  int e = 0;
  if (x < std::numeric_limits<double>::min()) {  // subnormal: scale into the normal range, exactly
    x *= 18014398509481984.0;                     // 2^54
    e = -54;
  }
  const auto bits = std::bit_cast<std::uint64_t>(x);
  e += static_cast<int>(bits >> 52) - 1023;
  double m = std::bit_cast<double>((bits & 0x000fffffffffffffULL) | 0x3ff0000000000000ULL);  // [1, 2)
  if (m > 1.4142135623730951) {
    m *= 0.5;  // exact
    ++e;
  }
  const double s = (m - 1.0) / (m + 1.0);
  const double z = s * s;
  const auto& c = detail::odd_reciprocals;
  double series = c[4];
  for (std::size_t k = 4; k-- > 0;) series = c[k] + z * series;
  const double ed = static_cast<double>(e);
  return ed * detail::ln2_hi + (ed * detail::ln2_lo + 2.0 * s * series);
}

/// e^y: 0 below −745, +∞ above 709.78, NaN for NaN.
inline double exp(double y) {
  if (std::isnan(y)) return y;
  if (y > 709.782712893384) return std::numeric_limits<double>::infinity();
  if (y < -745.2) return 0.0;
  constexpr double inv_ln2 = 1.44269504088896338700e+00;
  // The nearest integer to y/ln 2 by adding and taking away 1.5·2⁵², exact in
  // IEEE double arithmetic rounding to nearest (std::nearbyint is a libm call
  // on baseline x86-64, and reads the rounding mode).
  constexpr double shifter = 6755399441055744.0;
  const double kd = (y * inv_ln2 + shifter) - shifter;
  const double r = (y - kd * detail::ln2_hi) - kd * detail::ln2_lo;
  // Σ r^n/n!, n ≤ 8, by Estrin's scheme (four levels instead of eight).
  const auto& c = detail::inverse_factorials;
  const double r2 = r * r, r4 = r2 * r2;
  const double p = ((c[0] + c[1] * r) + r2 * (c[2] + c[3] * r)) +
                   r4 * (((c[4] + c[5] * r) + r2 * (c[6] + c[7] * r)) + r4 * c[8]);
  const int k = static_cast<int>(kd);  // in [−1075, 1024]
  // 2^k in two factors where it leaves the normal range (e^y near overflow, or subnormal).
  if (k > 1023) return p * detail::power_of_two(1023) * detail::power_of_two(k - 1023);
  if (k < -1022) return p * detail::power_of_two(-1022) * detail::power_of_two(k + 1022);
  return p * detail::power_of_two(k);
}

/// x^y = e^(y ln x) for x > 0.
inline double pow(double x, double y) { return exp(y * log(x)); }

}  // namespace lgi::integrators::controller_math
