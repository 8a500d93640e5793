#pragma once
// EBK levels of the Lagrange top from lgi's closed-form actions
// (analysis/actions.hpp, docs/actions.md §1; docs/quantum.md §7).
// At ℓ = mħ and L3 = kħ (both conserved) the nutation action is quantised
// with Maslov index 2 (two turning points of the θ libration; J. B. Keller,
// Ann. Phys. 4 (1958) 180):
//   I_θ(E; ℓ, L3) = ħ(n + 1/2),  n = 0, 1, ...
// and E_n(m, k) is the root in E of this monotone equation (∂I_θ/∂h =
// J0/π > 0). The error against the exact levels is O(ħ²) at fixed (n, m, k):
// for the free symmetric top the rule gives ħ²(j + 1/2)²/(2A) + ..., i.e. the
// exact level plus the constant ħ²/(8A) (docs/quantum.md §7).
#include <optional>
#include <vector>

#include "experiments/analysis/actions.hpp"
#include "experiments/analysis/quantum/quantum_spectrum.hpp"

namespace lgi::experiments::quantum {

/// The energy at which I_θ(E; ℓ = mħ, L3 = kħ) = ħ(n + 1/2) for the Lagrange
/// body (J = diag(A, A, C), c = (0, 0, w), w ≠ 0), found by bisection to
/// round-off; nothing if no torus at (ℓ, L3) reaches that action below
/// `energy_cap` (e.g. a finite basis' energy range).
std::optional<double> ebk_lagrange_level(const LagrangeBody& body, double hbar, int n, int m, int k,
                                         double energy_cap = 1e6);

/// One exact level beside its EBK level: n is its rank in its k block (a free
/// body: ebk_free_rotor.hpp).
struct EbkRow {
  int n = 0, m = 0, k = 0;
  int j = -1;     // a free body: the level's j; −1 otherwise
  int axis = -1;  // a free asymmetric body: the frame axis (0, 1, 2) its torus circulates about; −1 otherwise
  int n_fast = -1;  // Kovalevskaya: the fast libration's quantum number (n is the slow one's); −1 otherwise
  double energy_ebk = 0.0, energy_exact = 0.0;
  bool converged = false;  // the exact level's convergence in jmax
};

/// The EBK level of every level of a symmetric heavy top's spectrum (k
/// conserved: TopSymmetry::symmetric_heavy), in the spectrum's order.
/// Throws std::invalid_argument for another kind of top.
std::vector<EbkRow> ebk_lagrange_table(const QuantumSpectrum& spectrum, double hbar, int m);

}  // namespace lgi::experiments::quantum
