#pragma once
// The number of connected components (Liouville tori, over a regular value) of a
// common level set {H = h, K = k, Π·Γ = ℓ, |Γ| = 1} of a heavy top with a second
// integral K: states of a lattice on the energy surface are moved onto {K = k} by
// minimum-norm Gauss–Newton steps, and the components are read off the points'
// Euclidean minimum spanning tree: n components show as n − 1 edges much longer
// than the rest (single linkage with a gap; experiments/EQUILIBRIA.md, "Region
// labels"; docs/atlas.md §9).
#include <Eigen/Core>
#include <functional>
#include <vector>

#include "experiments/analysis/relative_equilibria.hpp"

namespace lgi::experiments {

using StateVec6 = Eigen::Matrix<double, 6, 1>;  // x = (Γ, Π)

/// A first integral's value and its gradient in x = (Γ, Π).
struct IntegralValue {
  double value = 0.0;
  StateVec6 gradient = StateVec6::Zero();
};
using SecondIntegral = std::function<IntegralValue(const StateVec6&)>;

/// H = ½ Π·J⁻¹Π + m g χ·Γ at x = (Γ, Π).
double heavy_top_energy(const HeavyTopBody& body, const StateVec6& x);

/// Moves x onto {H = h, C = ℓ, |Γ|² = 1, K = k} by minimum-norm Gauss–Newton steps (the
/// least move onto the surface); false when the residual stays above 1e-11 after 30 steps.
bool project_to_level_set(const HeavyTopBody& body, double l, double h, double k, const SecondIntegral& K,
                          StateVec6& x);

/// A lattice of states (Γ, Π) on {H = h, Π·Γ = ℓ, |Γ| = 1}: Fibonacci directions Γ
/// where the energy allows, two kinetic directions each.
std::vector<StateVec6> energy_surface_lattice(const HeavyTopBody& body, double l, double h, int seeds);

struct LevelSetComponents {
  int components = 0;  // −1: not resolved (the spanning tree has long edges but no clear gap)
  int points = 0;      // lattice states moved onto the level set
  double spacing = 0.0;  // the median spanning-tree edge
  double gap = 0.0;      // the largest ratio e(m−1)/e(m) of consecutive longest edges
  std::vector<double> longest;  // the longest spanning-tree edges over the median, longest first (≤ 8)
  bool resolved() const { return points > 0 && components > 0; }
};

/// The components of {H = h, K = k, Π·Γ = ℓ, |Γ| = 1} seen by `seeds` lattice directions
/// (no points: the level set is empty, or too thin for the lattice).
LevelSetComponents level_set_components(const HeavyTopBody& body, double l, double h, double k,
                                        const SecondIntegral& K, int seeds);

}  // namespace lgi::experiments
