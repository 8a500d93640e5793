#pragma once
// GALI_k, the generalised alignment indices (Ch. Skokos, T. C. Bountis,
// Ch. Antonopoulos, "Geometrical properties of local dynamics in Hamiltonian
// systems: the Generalized Alignment Index (GALI) method", Physica D 231
// (2007) 30–54), as `lgi indicators --gali` reports them
// (experiments/INDICATORS.md, docs/atlas.md §7).
//
// k deviation vectors w₁ … w_k ∈ ℝ⁶ are advanced by the tangent flow with
// the state and normalised to |wᵢ| = 1 after every step (each on its own: no
// orthonormalisation, so they may align). GALI_k is the volume of the
// parallelepiped they span, the norm of ŵ₁ ∧ … ∧ ŵ_k, computed from the
// singular values σᵢ of the 6 × k matrix of the vectors, GALI_k = ∏ σᵢ
// (Ch. Skokos, T. Bountis, Ch. Antonopoulos, Eur. Phys. J. Special Topics 165
// (2008) 5–14, §2, which also gives the laws for s-tori below). All five
// indices (k = 2 … 6) come from one set of six vectors, GALI_k from the
// first k of them.
//
// Tangent space: the full ℝ⁶ of SO(3) × ℝ³ (ξ, δΠ; integrators/core/tangent_flow.hpp)
// or of T³ × ℝ³ (δq, δp; integrators/core/torus_tangent_flow.hpp): three
// degrees of freedom, 2N = 6. The expected laws (docs/atlas.md §7) on an
// s-torus: GALI_k ≈ const for k ≤ s, ∝ t^−(k−s) for s < k ≤ 6 − s and
// ∝ t^−2(k−3) for k > 6 − s; on a chaotic orbit
// GALI_k ∝ exp(−[(λ₁−λ₂) + … + (λ₁−λ_k)] t).
#include <array>
#include <cstdint>
#include <vector>

#include "integrators/core/tangent_flow.hpp"

namespace lgi::experiments {

constexpr int gali_orders = 5;                    // k = 2, …, 6
using GaliValues = std::array<double, gali_orders>;  // log10 GALI_k, k = 2 … 6

/// Where the curves are sampled: `samples` times, evenly spaced on [T/samples, T],
/// or (log_spacing) evenly in ln t on [dt, T]; each at the end of the first
/// step at or after it, repeats dropped, T always last.
struct GaliSampling {
  int samples = 100;
  bool log_spacing = true;
};

/// The curves of one state: log10 GALI_k (k = 2 … 6) at the times t.
struct GaliCurves {
  std::vector<double> t;
  std::vector<GaliValues> log10_gali;
};

/// log10 GALI_k of the first k columns of V (k = 2 … 6): Σ log10 σᵢ of the
/// singular values of the 6 × k block (−inf where the columns are dependent).
GaliValues log10_gali(const integrators::Mat6& V);

/// The six initial deviation vectors of state `index`: seeded draws in the
/// unit cube, a function of (seed, index) alone (normalised by the loop).
integrators::Mat6 initial_deviation_vectors(std::uint64_t seed, std::int64_t index);

/// The target times of the samples on [0, t_end] with steps dt (GaliSampling).
std::vector<double> gali_targets(double t_end, double dt, const GaliSampling& g);

}  // namespace lgi::experiments
