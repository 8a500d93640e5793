#pragma once
// The modified-inertia series of the preprocessed DMV schemes (`dmv-pre4` …
// `dmv-pre10`, moser_veselov.hpp states them): Hairer & Vilmart, J. Phys. A 39
// (2006) 13225–13235, eq. (6) and Table 1; the h⁸ terms from the authors'
// DMV10.f (version of 29 Aug 2006, corrected 28 Dec 2007).
#include <array>
#include <cstddef>

#include "integrators/core/scheme_interface.hpp"

namespace lgi::integrators::moser_veselov {

/// The scalar series of Hairer & Vilmart (2006), eq. (6) and Table 1, for
/// order 2r = Order: 1/Ĩ_j = css/I_j + cdd with
///   css = 1 + Σ_{k=1}^{r−1} Σ_{i=0}^{k} s_{k,i} x^{k−i} y^{i},
///   cdd =     Σ_{k=1}^{r−1} Σ_{i=0}^{k} d_{k,i} x^{k−i} y^{i},
/// x = h² H, y = h² C (so that x^a y^b carries h^{2(a+b)}).
template <int Order>
struct ModifiedInertiaSeries {
  static_assert(Order == 4 || Order == 6 || Order == 8 || Order == 10, "preprocessed DMV has orders 4, 6, 8, 10");
  static constexpr int degrees = Order / 2 - 1;  // highest power of h² kept
  // s[k−1][i], d[k−1][i]: the coefficient of H^{k−i} C^{i} in s_{2k+1}, d_{2k+1}.
  std::array<std::array<double, 5>, 4> s{}, d{};

  /// x^n for |n| ≤ 4 by multiplication (a run's set-up is on the benchmark's clock, libm's pow is not needed).
  static double ipow(double x, int n) {
    double p = 1.0;
    for (int i = 0; i < (n < 0 ? -n : n); ++i) p *= x;
    return n < 0 ? 1.0 / p : p;
  }

  /// From the principal moments (any order).
  explicit ModifiedInertiaSeries(const Vec3& I = Vec3::Ones()) {
    const double I1 = I.x(), I2 = I.y(), I3 = I.z();
    auto sigma = [&](int a) { return ipow(I1, a) + ipow(I2, a) + ipow(I3, a); };
    // τ_{b,c} = Σ_{i≠j} I_i^b / I_j^c = (I2^b + I3^b)/I1^c + (I3^b + I1^b)/I2^c + (I1^b + I2^b)/I3^c
    auto tau = [&](int b, int c) {
      const double p1 = ipow(I1, b), p2 = ipow(I2, b), p3 = ipow(I3, b);
      return (p2 + p3) / ipow(I1, c) + (p3 + p1) / ipow(I2, c) + (p1 + p2) / ipow(I3, c);
    };
    const double dl = I1 * I2 * I3;  // δ
    const double dl2 = dl * dl, dl3 = dl2 * dl, dl4 = dl2 * dl2;
    const double s1 = sigma(1), s2 = sigma(2), s3 = sigma(3), s4 = sigma(4);
    const double sm1 = sigma(-1), sm2 = sigma(-2), sm3 = sigma(-3), sm4 = sigma(-4);
    const double t11 = tau(1, 1), t12 = tau(1, 2), t21 = tau(2, 1), t13 = tau(1, 3), t31 = tau(3, 1), t22 = tau(2, 2);
    // h²: s₃ = −σ₋₁/3 H + σ₁/(6δ) C,  d₃ = σ₁/(6δ) H − 1/(3δ) C        (Table 1)
    s[0] = {-sm1 / 3.0, s1 / (6.0 * dl)};
    d[0] = {s1 / (6.0 * dl), -1.0 / (3.0 * dl)};
    // h⁴: s₅, d₅                                                         (Table 1)
    s[1] = {(3.0 * s1 + 2.0 * dl * sm2) / (60.0 * dl), (1.0 - t11) / (30.0 * dl), (s2 - dl * sm1) / (30.0 * dl2)};
    d[1] = {-(9.0 + t11) / (60.0 * dl), (6.0 * dl * sm1 - s2) / (60.0 * dl2), -s1 / (60.0 * dl2)};
    // h⁶: s₇, d₇                                                         (Table 1)
    s[2] = {(15.0 - dl * sm3 - 2.0 * t11) / (630.0 * dl),
            (6.0 * dl * t12 - 100.0 * dl * sm1 + 53.0 * s2) / (2520.0 * dl2),
            (9.0 * s1 + 10.0 * dl * sm2 - 6.0 * t21) / (420.0 * dl2),
            (4.0 * dl + 17.0 * s3 - 15.0 * dl * t11) / (2520.0 * dl3)};
    d[2] = {(9.0 * dl * sm1 + dl * t12 - 11.0 * s2) / (1260.0 * dl2),
            (47.0 * s1 + 13.0 * t21 - 38.0 * dl * sm2) / (2520.0 * dl2),
            (s3 + 2.0 * dl * t11 - 85.0 * dl) / (1260.0 * dl3),
            (34.0 * dl * sm1 - 19.0 * s2) / (2520.0 * dl3)};
    // h⁸: s₉, d₉ (not in Table 1; the authors' DMV10.f, S9C5…S9C1, D9C5…D9C1)
    s[3] = {(2.0 * dl2 * sm4 + 5.0 * dl * t12 - 171.0 * dl * sm1 + 159.0 * s2) / (45360.0 * dl2),
            (137.0 * dl * sm2 - dl * t13 + 3.0 * s1 - 69.0 * t21) / (11340.0 * dl2),
            (26.0 * dl * t22 + 55.0 * s3 + 204.0 * dl - 50.0 * dl2 * sm3 - 59.0 * dl * t11) / (7560.0 * dl3),
            (-77.0 * t31 + 75.0 * dl * t12 + 214.0 * s2 - 240.0 * dl * sm1) / (22680.0 * dl3),
            (62.0 * s4 - 94.0 * dl * t21 + 66.0 * dl2 * sm2 + 81.0 * dl * s1) / (45360.0 * dl4)};
    d[3] = {(165.0 * s1 - dl * t13 - 9.0 * t21 - 145.0 * dl * sm2) / (45360.0 * dl2),
            (67.0 * s3 - 735.0 * dl - 15.0 * dl * t22 + 87.0 * dl * t11 + 34.0 * dl2 * sm3) / (22680.0 * dl3),
            (125.0 * dl * sm1 - 5.0 * t31 - 130.0 * s2 + 4.0 * dl * t12) / (7560.0 * dl3),
            (54.0 * dl * s1 - s4 + 218.0 * dl * t21 - 426.0 * dl2 * sm2) / (45360.0 * dl4),
            (60.0 * t11 * dl - 61.0 * s3 - 247.0 * dl) / (45360.0 * dl4)};
  }

  /// css and cdd at x = h² H, y = h² C.
  void evaluate(double x, double y, double& css, double& cdd) const {
    std::array<double, 5> xp{}, yp{};
    xp[0] = yp[0] = 1.0;
    for (std::size_t i = 1; i < 5; ++i) {
      xp[i] = xp[i - 1] * x;
      yp[i] = yp[i - 1] * y;
    }
    css = 1.0;
    cdd = 0.0;
    for (std::size_t k = 1; k <= static_cast<std::size_t>(degrees); ++k) {
      for (std::size_t i = 0; i <= k; ++i) {
        const double m = xp[k - i] * yp[i];  // H^{k−i} C^{i}, times h^{2k}
        css += s[k - 1][i] * m;
        cdd += d[k - 1][i] * m;
      }
    }
  }

  /// The same series as polynomials in x = h² at fixed H and C (a free body,
  /// where both are invariants of the scheme): css = 1 + Σ_k cs[k−1] x^k,
  /// cdd = Σ_k cd[k−1] x^k, cs[k−1] = Σ_i s_{k,i} H^{k−i} C^i (likewise cd).
  void coefficients_in_h2(double H, double C, std::array<double, 4>& cs, std::array<double, 4>& cd) const {
    cs = {};
    cd = {};
    for (std::size_t k = 1; k <= static_cast<std::size_t>(degrees); ++k) {
      for (std::size_t i = 0; i <= k; ++i) {
        const double m = ipow(H, static_cast<int>(k - i)) * ipow(C, static_cast<int>(i));
        cs[k - 1] += s[k - 1][i] * m;
        cd[k - 1] += d[k - 1][i] * m;
      }
    }
  }
};

/// Horner's rule for 1 + x (c₀ + x (c₁ + …)) (offset 1) or x (c₀ + …) (offset 0), `degree` terms.
inline double horner_in_h2(const std::array<double, 4>& c, int degree, double x, double offset) {
  double v = 0.0;
  for (int k = degree - 1; k >= 0; --k) v = c[static_cast<std::size_t>(k)] + x * v;
  return offset + x * v;
}

}  // namespace lgi::integrators::moser_veselov
