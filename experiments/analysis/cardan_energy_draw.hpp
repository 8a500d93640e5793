#pragma once
// Initial states of the Cardan top drawn from the microcanonical (Liouville)
// measure of the energy surface {H = h} ⊂ T³ × ℝ³ (docs/cardan.md §9.4;
// A. I. Khinchin, *Mathematical Foundations of Statistical Mechanics*, Dover
// 1949, ch. 2–3: the measure dσ/|∇H| on the surface, invariant under the flow).
//
// For H = ½ pᵀM(q)⁻¹p + U(q) with n = 3 degrees of freedom, the measure
// δ(H − h) dq dp has the marginal density on T³
//     ρ(q) ∝ √det M(q) · (h − U(q))^((n−2)/2) = √(det M(q) (h − U(q)))   on {U ≤ h},
// and given q, p = √(2(h − U)) L y with M = L Lᵀ and y uniform on the unit
// sphere S². The draw: q uniform on T³, kept with probability ρ(q)/ρ̂ (ρ̂ a
// bound of ρ from Hadamard's inequality det M ≤ M₁₁M₂₂M₃₃ and |U| ≤ g Σ m|c|),
// then y by Archimedes' theorem (z uniform in [−1, 1], azimuth uniform).
// Seeded per orbit (seeded_random.hpp): a function of (seed, index) alone.
#include <cstdint>

#include "integrators/system/cardan.hpp"

namespace lgi::experiments {

/// The least potential U on an n³ lattice of T³ (an upper bound of min U).
double cardan_sampled_minimum_potential(const system::CardanTop& top, int n = 32);

/// The bound ρ̂ ≥ √(det M(q) (h − U(q))) for every q (header).
double cardan_energy_density_bound(const system::CardanTop& top, double h);

/// Orbit `index`'s initial state on {H = h} (header); false if no q was
/// kept in `max_tries` draws (h at or below min U, or the level a sliver).
bool draw_cardan_energy_point(const system::CardanTop& top, double h, std::uint64_t seed, std::int64_t index,
                              system::TorusState& x, std::int64_t max_tries = 1000000);

}  // namespace lgi::experiments
