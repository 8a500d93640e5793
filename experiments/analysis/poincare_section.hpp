#pragma once
// Richter's Poincaré section of a heavy top and what `lgi poincare` needs
// around it (experiments/POINCARE.md; formulas in docs/atlas.md §6–§7):
// the section axis, the coordinates of a crossing, the lowest energy at a
// given ℓ (an empty level set is refused), and the chaos indicators of one
// initial state (integrators/core/tangent_flow.hpp).
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "experiments/analysis/relative_equilibria.hpp"
#include "integrators/ensemble/ensemble.hpp"
#include "integrators/system/rigid_body.hpp"
#include "integrators/system/scene.hpp"

namespace lgi::experiments {

/// Which surface is crossed: Richter's S = d(Γ·e)/dt = 0, or Γ·e = 0.
enum class SectionKind { richter, gamma };

/// The default section axis of a scene (docs/atlas.md §6): e3 for the free
/// body and for a Lagrange top (χ on a principal axis e_k whose other two
/// moments are equal: then e_k), χ/|χ| otherwise.
Vec3 default_section_axis(const system::Scene& scene);

/// --axis: e1, e2, e3, com (χ/|χ|) or x,y,z (normalised). UsageError naming
/// --axis on anything else (a zero vector, com of a body with χ = 0).
Vec3 parse_section_axis(const std::string& text, const system::Scene& scene);

/// The section coordinates of a crossing (docs/atlas.md §6).
struct SectionPoint {
  double phi = 0.0;    // in [0, 2π)
  double theta = 0.0;  // in [0, π]
  int sheet = 1;       // ±1
};

/// The orthonormal frame (f1, f2, e) in which φ and ϑ are measured: f1 is
/// the body axis least aligned with e (the first on ties) made orthogonal to e.
void section_frame(const Vec3& e, Vec3& f1, Vec3& f2);

/// Richter's section: (φ, ϑ) are the spherical angles of Γ about e (ϑ from e,
/// φ from f1 towards f2) and the sheet is the sign of φ̇, i.e. of
/// e·(Γ × Γ̇) = (Γ·e)(Γ·Ω) − Ω·e (+1 where it vanishes). The Γ·e = 0
/// section: φ the azimuth of Γ, ϑ the angle of Π from e, the sheet the sign
/// of d(Γ·e)/dt.
SectionPoint section_point(SectionKind kind, const Vec3& e, const Vec3& gamma, const Vec3& Pi, const Mat3& J_inv);

/// The least energy on {|Γ| = 1, Π·Γ = l}: the minimum of the amended
/// potential, the lowest relative equilibrium at l (equilibria_at), checked
/// against a Fibonacci lattice of 20000 directions.
double minimum_energy(const HeavyTopBody& body, double l);

/// The chaos indicators of one initial state (integrators/core/tangent_flow.hpp):
/// the tangent vector starts along a unit vector drawn from (seed, index).
struct OrbitIndicators {
  double lyapunov = 0.0, megno = 0.0;
};
OrbitIndicators orbit_indicators(const system::Scene& scene, const system::State& x0, double t_end, double dt,
                                 std::uint64_t seed, std::int64_t index);
/// orbit_indicators of several initial states of one scene (index[k] the
/// draw of x0[k]'s tangent vector): bit for bit the same values, computed in
/// the lanes of a TangentEnsemble on `isa` where the model has tangent kernels
/// (integrators/ensemble/tangent_ensemble.hpp), else one at a time.
void orbit_indicators(const system::Scene& scene, std::span<const system::State> x0, double t_end, double dt,
                      std::uint64_t seed, std::span<const std::int64_t> index,
                      std::optional<integrators::ensemble::Isa> isa, std::span<OrbitIndicators> out);

}  // namespace lgi::experiments
