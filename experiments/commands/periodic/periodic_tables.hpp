#pragma once
// The tables of `lgi periodic` (experiments/PERIODIC.md "Output"): /periodic,
// one row per orbit, and /manifolds, the section points of the stable and
// unstable manifolds of hyperbolic orbits.
#include <optional>
#include <vector>

#include "experiments/analysis/periodic/family_continuation.hpp"
#include "experiments/analysis/periodic/orbit_manifolds.hpp"
#include "experiments/io/table_file.hpp"

namespace lgi::experiments {

/// The /periodic columns; with a section, section_phi, section_theta and
/// section_sheet are the coordinates of each orbit's point (NaN, 0 without).
/// A Cardan top (flow.cardan): angular_momentum and gamma are the body's
/// Π = J E(q) q̇ and Γ = R(q)ᵀ e3 at the orbit's point, the Kovalevskaya
/// columns NaN (−1), and three columns follow: cardan_angles (q, q1 = 0),
/// cardan_momenta (p) and cardan_drift (q1's turn over one period).
std::vector<TableColumn> periodic_columns(const PeriodicFlow& flow, const std::vector<FamilyOrbit>& rows,
                                          const std::optional<PhaseSection>& section);

/// The manifolds of the orbit of /periodic row (family, index).
struct RowManifolds {
  int family = 0, index = 0;
  OrbitManifolds m;
};
/// On a Cardan top (flow.cardan) angular_momentum and gamma are the body's Π, Γ, and cardan_angles and
/// cardan_momenta follow (the state q, p), as in /periodic.
TableGroup manifold_group(const PeriodicFlow& flow, const std::vector<RowManifolds>& all);

}  // namespace lgi::experiments
