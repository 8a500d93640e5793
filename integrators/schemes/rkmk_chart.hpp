#pragma once
// The coordinates an RKMK scheme works in, R = R_n φ(ŵ) (docs/math.md §2):
// the exponential (Munthe-Kaas's original) or the Cayley map. RKMK has the
// tableau's order in any coordinates φ with φ(0) = I and dφ(0) = I, since it
// is the tableau applied to the smooth chart ODE ẇ = dφ⁻¹_body(w) Ω
// (Munthe-Kaas 1999, Thm. 1; Iserles et al., Acta Numerica 9 (2000) §5.3;
// Engø, BIT 40 (2000) 41–61, on the choice of the coordinates). Both maps
// are I + a ŵ + b ŵ², so one stage attitude serves both; they differ in
// a, b and the inverse differential:
//   exp:  a = sinθ/θ, b = (1 − cosθ)/θ², dexp⁻¹ Ω = Ω + ½ w × Ω + c(θ) w × (w × Ω)
//         (lie/exp_series.hpp: Taylor series below θ = 1, one sin/cos above);
//   cay:  a = 4/(4 + θ²), b = a/2,        dcay⁻¹ Ω = Ω + ½ w × Ω + ¼ (w·Ω) w
//         (lie/cayley_coordinates.hpp: one division, and dcay⁻¹ needs no θ).
// The Cayley coordinates take the chain w_i → a, b → Γ_i → K_i → w_{i+1} of a
// stage through one division instead of three series, and dcay⁻¹ off it.
#include <concepts>

#include "integrators/schemes/rkmk_pair_kernels.hpp"
#include "integrators/core/scheme_facts.hpp"
#include "lie/cayley_coordinates.hpp"

namespace lgi::integrators {

/// A coordinate map φ of SO(3) for RKMK: its coefficients a, b (and
/// whatever its dφ⁻¹ needs) from θ² = |w|², and dφ⁻¹_body(w) Ω.
template <class C>
concept RkmkChart = requires(double t2, const double* w, const lie::Vec3& omega,
                             const rkmk_pair_detail::MapCoefficients& m, double* out) {
  { C::coefficients(t2) } -> std::same_as<rkmk_pair_detail::MapCoefficients>;
  C::inverse_differential(w, omega, m, out);
  { C::reference } -> std::convertible_to<const char*>;
};

/// R = R_n exp(ŵ): Munthe-Kaas's RKMK.
struct ExponentialChart {
  static constexpr const char* reference = munthe_kaas_reference;
  static rkmk_pair_detail::MapCoefficients coefficients(double t2) { return rkmk_pair_detail::map_coefficients(t2); }
  static void inverse_differential(const double* w, const lie::Vec3& omega,
                                   const rkmk_pair_detail::MapCoefficients& m, double* out) {
    rkmk_pair_detail::dexpinv(w, omega, m, out);
  }
};

/// R = R_n cay(ŵ).
struct CayleyChart {
  static constexpr const char* reference =
      "Munthe-Kaas, Appl. Numer. Math. 29 (1999) 115-127; Iserles et al., Acta Numerica 9 (2000) 5.3 and the "
      "Cayley map; Diele, Lopez & Peluso, Adv. Comput. Math. 8 (1998) 317-334";
  static rkmk_pair_detail::MapCoefficients coefficients(double t2) {
    const double a = lie::cayley_coordinates::coefficient(t2);
    return {a, 0.5 * a, 0.0};
  }
  static void inverse_differential(const double* w, const lie::Vec3& omega, const rkmk_pair_detail::MapCoefficients&,
                                   double* out) {
    const double o[3] = {omega(0), omega(1), omega(2)};
    lie::cayley_coordinates::dcayinv(w, o, out);
  }
};

static_assert(RkmkChart<ExponentialChart> && RkmkChart<CayleyChart>);

/// R φ(ŵ), every row.
template <RkmkChart Chart>
inline lie::Mat3 times_map(const lie::Mat3& R, const double* w) {
  return rkmk_pair_detail::times_exp(R, w, Chart::coefficients(lie::exp_series::squared_norm(w)));
}

}  // namespace lgi::integrators
