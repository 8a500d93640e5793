#pragma once
// The arithmetic of one RKMK stage on SO(3) × ℝ³ (rkmk_pair.hpp), written on
// plain doubles: in a 12-stage step GCC stops inlining Eigen's fixed-size
// kernels (each Vec3 axpy became a call), which cost half the step. Every
// formula here is one of lie/so3.hpp, evaluated in the same way.
//
// exp(ŵ) = I + a ŵ + b ŵ² and dexp⁻¹_body(w) Ω = Ω + ½ w × Ω + c w × (w × Ω)
// (docs/math.md §1; Iserles et al., Acta Numerica 9 (2000), eq. (2.46)) with
//   a = sinθ/θ,  b = (1 − cosθ)/θ²,  c = (1 − (θ/2) cot(θ/2))/θ²,  θ = |w|,
// all three from their Taylor series below θ = 1, or from one sin/cos of θ/2.
#include <array>
#include <cmath>
#include <cstddef>

#include "lie/so3.hpp"

namespace lgi::integrators::rkmk_pair_detail {

using lie::Mat3;
using lie::Vec3;

/// A stage's derivatives in the chart: (k̃, K) = (dexp⁻¹(w) Ω, Π̇).
using Slope = std::array<double, 6>;

struct MapCoefficients {
  double a, b, c;
};

namespace series {
/// Taylor coefficients in θ²: a = Σ (−1)^k θ^2k/(2k+1)!, b = Σ (−1)^k θ^2k/(2k+2)!,
/// c = Σ_{k≥1} |B_2k| θ^(2k−2)/(2k)! (Bernoulli numbers B_2k, from
/// x cot x = 1 − Σ 2^2k |B_2k| x^2k/(2k)!).
constexpr std::array<double, 10> a = [] {
  std::array<double, 10> out{};
  double factorial = 1.0;  // (2k+1)!
  for (std::size_t k = 0; k < 10; ++k) {
    if (k > 0) factorial *= static_cast<double>((2 * k) * (2 * k + 1));
    out[k] = (k % 2 == 0 ? 1.0 : -1.0) / factorial;
  }
  return out;
}();
constexpr std::array<double, 10> b = [] {
  std::array<double, 10> out{};
  double factorial = 2.0;  // (2k+2)!
  for (std::size_t k = 0; k < 10; ++k) {
    if (k > 0) factorial *= static_cast<double>((2 * k + 1) * (2 * k + 2));
    out[k] = (k % 2 == 0 ? 1.0 : -1.0) / factorial;
  }
  return out;
}();
constexpr std::array<double, 12> c = {1.0 / 12.0,
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
static_assert(a[1] == -1.0 / 6.0 && b[1] == -1.0 / 24.0 && a[9] == -1.0 / 121645100408832000.0);

/// Σ_k coefficients[k] x^k by Estrin's scheme: pairs c_2j + c_2j+1 x, then
/// pairs of those with x², x⁴, …, so the dependency chain is log₂ N
/// multiply-adds deep instead of N (Horner's chains made these three series
/// a quarter of a DOP853 step). The terms fall fast, so either order of
/// summation rounds alike.
template <std::size_t N>
inline double estrin(const std::array<double, N>& coefficients, double x) {
  std::array<double, N> v = coefficients;
  std::size_t n = N;
  double power = x;
  while (n > 1) {
    const std::size_t m = (n + 1) / 2;
    for (std::size_t j = 0; j < m; ++j) v[j] = 2 * j + 1 < n ? v[2 * j] + v[2 * j + 1] * power : v[2 * j];
    n = m;
    power *= power;
  }
  return v[0];
}
}  // namespace series

/// a, b, c from θ² = |w|². For θ < 1 their Taylor series in θ², whose first
/// neglected terms are below 2e-20 relative (θ²⁰/21! for a, θ²⁰/22! for b,
/// |B₂₆| θ²⁴/26! for c; the terms alternate or shrink by (2π)⁻² each, so no
/// digit cancels): no sqrt, sin, cos or division. Above, with s = sin(θ/2),
/// k = cos(θ/2): a = 2 s k/θ, b = 2 (s/θ)², c = (1 − (θ/2) k/s)/θ², which has
/// c's own cancellation only (ε/θ² absolute in c, so ε|Ω| in k̃).
inline MapCoefficients map_coefficients(double t2) {
  if (t2 < 1.0) return {series::estrin(series::a, t2), series::estrin(series::b, t2), series::estrin(series::c, t2)};
  const double theta = std::sqrt(t2);
  const double half = 0.5 * theta;
  const double s = std::sin(half), k = std::cos(half);
  const double s_over = s / theta;
  return {2.0 * s_over * k, 2.0 * s_over * s_over, (1.0 - half * k / s) / t2};
}

/// R exp(ŵ): row r of R becomes r + a (r × w) + b ((r × w) × w), since the
/// rows of R ŵ are r × w.
inline Mat3 times_exp(const Mat3& R, const double* w, const MapCoefficients& m) {
  Mat3 out;
  for (int i = 0; i < 3; ++i) {
    const double r0 = R(i, 0), r1 = R(i, 1), r2 = R(i, 2);
    const double x0 = r1 * w[2] - r2 * w[1], x1 = r2 * w[0] - r0 * w[2], x2 = r0 * w[1] - r1 * w[0];
    const double y0 = x1 * w[2] - x2 * w[1], y1 = x2 * w[0] - x0 * w[2], y2 = x0 * w[1] - x1 * w[0];
    out(i, 0) = r0 + m.a * x0 + m.b * y0;
    out(i, 1) = r1 + m.a * x1 + m.b * y1;
    out(i, 2) = r2 + m.a * x2 + m.b * y2;
  }
  return out;
}

/// k̃ = dexp⁻¹_body(w) Ω into out[0..2].
inline void dexpinv(const double* w, const Vec3& omega, const MapCoefficients& m, double* out) {
  const double o0 = omega(0), o1 = omega(1), o2 = omega(2);
  const double x0 = w[1] * o2 - w[2] * o1, x1 = w[2] * o0 - w[0] * o2, x2 = w[0] * o1 - w[1] * o0;
  const double y0 = w[1] * x2 - w[2] * x1, y1 = w[2] * x0 - w[0] * x2, y2 = w[0] * x1 - w[1] * x0;
  out[0] = o0 + 0.5 * x0 + m.c * y0;
  out[1] = o1 + 0.5 * x1 + m.c * y1;
  out[2] = o2 + 0.5 * x2 + m.c * y2;
}

/// Σ_J W[J] k[J] over the first N slopes, zero weights skipped at compile time.
template <const auto& W, std::size_t N, std::size_t Stored>
inline Slope combination(const std::array<Slope, Stored>& k) {
  Slope sum{};
  [&]<std::size_t... J>(std::index_sequence<J...>) {
    auto add = [&](double weight, const Slope& kj) {
      for (std::size_t d = 0; d < 6; ++d) sum[d] += weight * kj[d];
    };
    ((W[J] != 0.0 ? add(W[J], k[J]) : void()), ...);
  }(std::make_index_sequence<N>{});
  return sum;
}

}  // namespace lgi::integrators::rkmk_pair_detail
