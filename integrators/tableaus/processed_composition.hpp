#pragma once
// Coefficients of processed compositions ψ_h = π_h ∘ K_h ∘ π_h⁻¹ of a
// symmetric method Φ of order 2 (integrators/schemes/processed_composition.hpp):
// a symmetric kernel K_h = Φ_{γ_s h} ∘ ⋯ ∘ Φ_{γ_1 h} and a processor π_h,
// itself a composition of Φ. The kernel needs only the conditions that no
// conjugation can remove (its effective order): with Φ_h = exp(h E₁ + h³ E₃ +
// h⁵ E₅ + …), Σγ = 1 and Σγ³ = Σγ⁵ (= Σγ⁷ for order 8) = 0, while terms such
// as [E₁,[E₁,E₃]] are left to the processor (Blanes, Casas & Ros, SIAM J. Sci.
// Comput. 21 (1999) 711–727; Blanes, Casas & Murua, SIAM J. Sci. Comput. 27
// (2006) 1817–1843, whose kernels and processors these are, as tabulated in
// Blanes, Casas & Murua, Acta Numerica 33 (2024) 1–161, §8, Table 8.1).
//
// The processor is stored as the preprocessing map π_h⁻¹: the stages
// z_1, …, z_P applied first to last, Φ_{z_P h} ∘ ⋯ ∘ Φ_{z_1 h}, with
// z_{m+i} = −z_i (P = 2m), so Σz = 0 and π_h = id + O(h²). As Φ is
// symmetric (Φ_{−a} = Φ_a⁻¹), π_h applies −z_P, …, −z_1 in that order. The
// ordering and signs were checked by the observed orders 6 and 8 of ψ on a
// non-integrable problem (the other three orderings give order 4), and are
// checked again by the generic order tests (tests/test_composition.cpp).
#include <array>
#include <cstddef>

#include "integrators/tableaus/composition.hpp"

namespace lgi::tableaus {

template <std::size_t S, std::size_t P>
struct ProcessedCoefficients {
  static constexpr std::size_t stages = S;
  static constexpr std::size_t processor_stages = P;
  std::array<double, S> gamma{};   // the kernel, symmetric
  std::array<double, P> z{};       // the preprocessing π_h⁻¹, first stage first
  int order = 0;                   // the order of ψ (the kernel's effective order)
  const char* name = "";
  const char* citation = "";
};

/// The kernel's conditions of effective order `order` (header comment): symmetry,
/// Σγ = 1 and the odd power sums up to order − 1. The bracket conditions are
/// not required: the processor removes them.
template <std::size_t S, std::size_t P>
constexpr bool kernel_has_effective_order(const ProcessedCoefficients<S, P>& c, double tolerance = 1e-14) {
  if (!composition_consistent(CompositionCoefficients<S>{c.gamma, c.order})) return false;  // symmetric, Σγ = 1
  for (int k = 3; k < c.order; k += 2)
    if (!power_sum_is(c.gamma, k, 0.0, tolerance)) return false;
  return true;
}

/// The processor's shape: z_{m+i} = −z_i, so that Σz = 0 exactly.
template <std::size_t S, std::size_t P>
constexpr bool processor_is_balanced(const ProcessedCoefficients<S, P>& c) {
  if (P % 2 != 0) return false;
  for (std::size_t i = 0; i < P / 2; ++i)
    if (c.z[P / 2 + i] != -c.z[i]) return false;
  return true;
}

namespace detail {
/// The processor from its first half y_2, …, y_m (y_1 = −Σ y_i, so that the
/// half sums to zero, as tabulated) and its negated second half.
template <std::size_t P, std::size_t H>
constexpr std::array<double, P> balanced_processor(const std::array<double, H>& tail) {
  static_assert(P == 2 * (H + 1));
  std::array<double, P> z{};
  double sum = 0.0;
  for (std::size_t i = 0; i < H; ++i) {
    z[i + 1] = tail[i];
    sum += tail[i];
  }
  z[0] = -sum;
  for (std::size_t i = 0; i < P / 2; ++i) z[P / 2 + i] = -z[i];
  return z;
}
}  // namespace detail

/// Order 6: an 11-stage kernel (a₁ four times, a₅, the middle) and a 12-stage
/// processor (Blanes, Casas & Murua 2006; Acta Numerica 2024, Table 8.1, "BCM06", s = 11).
inline constexpr ProcessedCoefficients<11, 12> bcm_processed6{
    symmetric_from_half<11>(std::array<double, 5>{0.1705768865009222157, 0.1705768865009222157,
                                                        0.1705768865009222157, 0.1705768865009222157,
                                                        -0.423366140892658048}),
    // Tabulated as g_1..g_6 (g_1 = −(g_2 + … + g_6)); the preprocessing applies −g_1..−g_6, then g_1..g_6.
    detail::balanced_processor<12>(
        std::array<double, 5>{0.20621953139126, -0.23651387483203, -0.09086982276241, -0.24687306977659, 0.1}),
    6, "bcm-processed6", "Blanes, Casas & Murua, SIAM J. Sci. Comput. 27 (2006); Acta Numerica 33 (2024) Table 8.1"};

/// Order 8: a 13-stage kernel and a 20-stage processor (Blanes, Casas & Murua
/// 2006; Acta Numerica 2024, Table 8.1, "BCM06", s = 13).
inline constexpr ProcessedCoefficients<13, 20> bcm_processed8{
    symmetric_from_half<13>(std::array<double, 6>{0.168, 0.168, 0.585550530805562, -0.460090457516872,
                                                        0.172863148729731, 0.179664539695039}),
    detail::balanced_processor<20>(std::array<double, 9>{
        0.008488123494574411, 0.337188967354338, -0.333987768164597, -0.588351189003849, -0.162324207599241,
        0.511744926116413, -0.236885952363384, -0.598212975943381, 0.543415765371656}),
    8, "bcm-processed8", "Blanes, Casas & Murua, SIAM J. Sci. Comput. 27 (2006); Acta Numerica 33 (2024) Table 8.1"};

static_assert(kernel_has_effective_order(bcm_processed6) && kernel_has_effective_order(bcm_processed8));
static_assert(processor_is_balanced(bcm_processed6) && processor_is_balanced(bcm_processed8));
// The kernels alone are of order 4 only: processing is what raises them. The
// order-6 kernel fails the bracket condition a plain order-6 composition
// needs, and the order-6 kernel is not of effective order 8 (Σγ⁷ ≠ 0).
static_assert(!bracket_condition_order6(bcm_processed6.gamma) && !bracket_condition_order6(bcm_processed8.gamma));
static_assert(!power_sum_is(bcm_processed6.gamma, 7, 0.0));

}  // namespace lgi::tableaus
