#pragma once
// The Kovalevskaya torus through a chosen level (h, ℓ, k): a point of
// {H = h, Π·Γ = ℓ, k = K/c² = k, |Γ| = 1} by minimum-norm Gauss–Newton steps
// (level_set_components.hpp), its numerical torus (docs/actions.md §3) and the
// Maslov indices of its cycles (torus_maslov.hpp, docs/actions.md §5), and the
// libration basis that EBK quantises (docs/quantum.md §10).
#include <Eigen/Core>
#include <limits>
#include <optional>
#include <string>

#include "experiments/analysis/actions.hpp"
#include "experiments/analysis/level_set_components.hpp"
#include "experiments/analysis/torus_maslov.hpp"

namespace lgi::experiments {

/// k = K/c² of a Kovalevskaya body (kovalevskaya_diagram.hpp) as a function of (Γ, Π), and as
/// a SecondIntegral with its gradient (central differences).
SecondIntegralFunction kovalevskaya_k_function(const HeavyTopBody& body);
SecondIntegral kovalevskaya_k_integral(const HeavyTopBody& body);

/// A point (Γ, Π) of {H = h, Π·Γ = ℓ, k, |Γ| = 1}: moved there from `start` if given, else from
/// the first of `seeds` lattice states of the energy surface that reaches it; nothing if none
/// does. Where the level set has several tori, the start (or the lattice order) picks one.
std::optional<StateVec6> kovalevskaya_level_point(const HeavyTopBody& body, double l, double h, double k,
                                                  const std::optional<StateVec6>& start, int seeds = 400);

/// The state with attitude R (any with Rᵀe3 = Γ) and momentum Π.
system::State state_at(const StateVec6& x);

/// The basis of a torus's cycles in which both have Maslov index 2 and both frequencies are
/// positive (the basis of two librations; unique where it exists, docs/quantum.md §10),
/// the slower cycle first.
struct LibrationBasis {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  bool ok = false;
  double action_slow = nan, action_fast = nan, omega_slow = nan, omega_fast = nan;
  Eigen::Matrix2i change = Eigen::Matrix2i::Zero();  // rows: the slow and fast cycle in terms of (a, b)
};
LibrationBasis libration_basis(const NumericalTorus& torus, const TorusMaslov& maslov);

/// The numerical torus through x0 with its Maslov indices and libration basis.
struct KovalevskayaTorus {
  double k = std::numeric_limits<double>::quiet_NaN();
  NumericalTorus torus;
  TorusMaslov maslov;
  LibrationBasis basis;
};
KovalevskayaTorus kovalevskaya_torus(const system::Scene& scene, const HeavyTopBody& body, const system::State& x0,
                                     const NumericalTorusOptions& options, int maslov_returns = 200);

}  // namespace lgi::experiments
