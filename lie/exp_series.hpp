#pragma once
// exp and dexp⁻¹ on so(3) ≅ ℝ³ written on plain numbers of any type T (double,
// or the ensemble's lane numbers, integrators/ensemble/lanes.hpp), so that a
// scalar scheme and its ensemble kernel share one source and therefore the
// same operations in the same order (docs/ensemble.md). No Eigen here: the
// ensemble kernels are compiled once per instruction set and must share no
// inline non-template code with the rest of lgi.
//
//   exp(ŵ) = I + a ŵ + b ŵ²,   dexp⁻¹_body(w) Ω = Ω + ½ w × Ω + c w × (w × Ω),
//   a = sinθ/θ,  b = (1 − cosθ)/θ²,  c = (1 − (θ/2) cot(θ/2))/θ²,  θ = |w|
// (docs/math.md §1; Iserles et al., Acta Numerica 9 (2000), eq. (2.46)).
// For θ < 1 the coefficients come from their Taylor series in θ², whose
// first neglected terms are below 2e-20 relative (θ²⁰/21! for a, θ²⁰/22!
// for b, |B₂₆| θ²⁴/26! for c; the terms alternate or shrink by (2π)⁻² each,
// so no digit cancels): only + and ×, no sqrt, sin, cos or division, which
// vectorises. For θ < 1/2 the first 8 terms of each suffice (first neglected
// terms below 5e-20 relative for a and b, 3e-18 for c), one level less of
// Estrin's scheme: the series sits on the critical path of every RKMK stage,
// from a stage's w to its attitude and torque (docs/math.md §2). The short
// series give the same bits as the full ones there (tests/test_lie_so3.cpp).
// Above θ = 1, with s = sin(θ/2), k = cos(θ/2): a = 2 s k/θ,
// b = 2 (s/θ)², c = (1 − (θ/2) k/s)/θ² (c's own cancellation only: ε/θ²
// absolute in c, so ε|Ω| in dexp⁻¹).
#include <array>
#include <cstddef>

namespace lgi::lie::exp_series {

/// Below this θ² the series are used.
inline constexpr double series_bound = 1.0;

/// Taylor coefficients in θ²: a = Σ (−1)^k θ^2k/(2k+1)!, b = Σ (−1)^k θ^2k/(2k+2)!,
/// c = Σ_{k≥1} |B_2k| θ^(2k−2)/(2k)! (Bernoulli numbers B_2k, from
/// x cot x = 1 − Σ 2^2k |B_2k| x^2k/(2k)!).
inline constexpr std::array<double, 10> a_series = [] {
  std::array<double, 10> out{};
  double factorial = 1.0;  // (2k+1)!
  for (std::size_t k = 0; k < 10; ++k) {
    if (k > 0) factorial *= static_cast<double>((2 * k) * (2 * k + 1));
    out[k] = (k % 2 == 0 ? 1.0 : -1.0) / factorial;
  }
  return out;
}();
inline constexpr std::array<double, 10> b_series = [] {
  std::array<double, 10> out{};
  double factorial = 2.0;  // (2k+2)!
  for (std::size_t k = 0; k < 10; ++k) {
    if (k > 0) factorial *= static_cast<double>((2 * k + 1) * (2 * k + 2));
    out[k] = (k % 2 == 0 ? 1.0 : -1.0) / factorial;
  }
  return out;
}();
inline constexpr std::array<double, 12> c_series = {1.0 / 12.0,
                                                    1.0 / 720.0,
                                                    1.0 / 30240.0,
                                                    1.0 / 1209600.0,
                                                    1.0 / 47900160.0,
                                                    691.0 / 1307674368000.0,
                                                    1.0 / 74724249600.0,
                                                    3617.0 / 10670622842880000.0,
                                                    43867.0 / 5109094217170944000.0,
                                                    174611.0 / 802857662698291200000.0,
                                                    77683.0 / 14101100039391805440000.0,
                                                    236364091.0 / 1693824136731743669452800000.0};
static_assert(a_series[1] == -1.0 / 6.0 && b_series[1] == -1.0 / 24.0 &&
              a_series[9] == -1.0 / 121645100408832000.0 && b_series[9] == -1.0 / 2432902008176640000.0);

/// Σ_k coefficients[k] x^k by Estrin's scheme: pairs c_2j + c_2j+1 x, then
/// pairs of those with x², x⁴, …, so the dependency chain is log₂ N
/// multiply-adds deep instead of N. The terms fall fast, so either order of
/// summation rounds alike.
template <std::size_t N, class T>
inline T estrin(const std::array<double, N>& coefficients, const T& x) {
  constexpr std::size_t first = (N + 1) / 2;
  std::array<T, first> v;
  for (std::size_t j = 0; j < first; ++j)
    v[j] = 2 * j + 1 < N ? coefficients[2 * j] + coefficients[2 * j + 1] * x : T(coefficients[2 * j]);
  std::size_t n = first;
  T power = x * x;
  while (n > 1) {
    const std::size_t m = (n + 1) / 2;
    for (std::size_t j = 0; j < m; ++j) v[j] = 2 * j + 1 < n ? v[2 * j] + v[2 * j + 1] * power : v[2 * j];
    n = m;
    power = power * power;
  }
  return v[0];
}

/// Below this θ² (θ < 1/2) the short series (the first 8 terms) are used.
inline constexpr double short_series_bound = 0.25;

/// The first M of N coefficients.
template <std::size_t M, std::size_t N>
constexpr std::array<double, M> leading(const std::array<double, N>& coefficients) {
  static_assert(M <= N);
  std::array<double, M> out{};
  for (std::size_t i = 0; i < M; ++i) out[i] = coefficients[i];
  return out;
}
inline constexpr auto a_short = leading<8>(a_series);
inline constexpr auto b_short = leading<8>(b_series);
inline constexpr auto c_short = leading<8>(c_series);

/// a, b and c by their series: every term, or with Short the first 8 (for θ² below short_series_bound).
template <bool Short = false, class T>
inline T series_a(const T& t2) {
  if constexpr (Short) return estrin(a_short, t2);
  else return estrin(a_series, t2);
}
template <bool Short = false, class T>
inline T series_b(const T& t2) {
  if constexpr (Short) return estrin(b_short, t2);
  else return estrin(b_series, t2);
}
template <bool Short = false, class T>
inline T series_c(const T& t2) {
  if constexpr (Short) return estrin(c_short, t2);
  else return estrin(c_series, t2);
}

/// The closed forms from θ² = t2, θ, s = sin(θ/2) and k = cos(θ/2).
template <class T>
inline T closed_a(const T& theta, const T& s, const T& k) {
  return 2.0 * (s / theta) * k;
}
template <class T>
inline T closed_b(const T& theta, const T& s) {
  const T s_over = s / theta;
  return 2.0 * s_over * s_over;
}
template <class T>
inline T closed_c(const T& t2, const T& theta, const T& s, const T& k) {
  return (1.0 - 0.5 * theta * k / s) / t2;
}

/// |w|² as (w0² + w1²) + w2².
template <class T>
inline T squared_norm(const T* w) {
  return w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
}

/// One row r of R exp(ŵ): r + a (r × w) + b ((r × w) × w) (the rows of R ŵ are r × w).
template <class T>
inline void times_exp_row(const T* r, const T* w, const T& a, const T& b, T* out) {
  const T x0 = r[1] * w[2] - r[2] * w[1], x1 = r[2] * w[0] - r[0] * w[2], x2 = r[0] * w[1] - r[1] * w[0];
  const T y0 = x1 * w[2] - x2 * w[1], y1 = x2 * w[0] - x0 * w[2], y2 = x0 * w[1] - x1 * w[0];
  out[0] = r[0] + a * x0 + b * y0;
  out[1] = r[1] + a * x1 + b * y1;
  out[2] = r[2] + a * x2 + b * y2;
}

/// dexp⁻¹_body(w) Ω = Ω + ½ w × Ω + c w × (w × Ω).
template <class T>
inline void dexpinv(const T* w, const T* omega, const T& c, T* out) {
  const T x0 = w[1] * omega[2] - w[2] * omega[1], x1 = w[2] * omega[0] - w[0] * omega[2],
          x2 = w[0] * omega[1] - w[1] * omega[0];
  const T y0 = w[1] * x2 - w[2] * x1, y1 = w[2] * x0 - w[0] * x2, y2 = w[0] * x1 - w[1] * x0;
  out[0] = omega[0] + 0.5 * x0 + c * y0;
  out[1] = omega[1] + 0.5 * x1 + c * y1;
  out[2] = omega[2] + 0.5 * x2 + c * y2;
}

}  // namespace lgi::lie::exp_series
