#pragma once
// EBK levels of the free rotor at fixed j from lgi's closed-form Euler
// actions (analysis/actions.hpp, docs/actions.md §2; docs/quantum.md §9).
// Ĥ commutes with L̂², so |Π| = G is quantised with the Langer-type
// G = ħ(j + 1/2) (the sphere |Π| = G of area 4πG then holds 2j + 1 states),
// and on that sphere the orbit of Π, a closed curve about the axis of the
// largest or of the smallest moment (away from the separatrix), encloses a cap
// whose area over 2π is the action I_cap. With Maslov index 2 (the libration
// of the Andoyer angle, two turning points; Colwell, Handy & Miller,
// J. Chem. Phys. 66 (1977) 3063; M. S. Child, Semiclassical Mechanics with
// Molecular Applications, 2nd ed. 2014, ch. 6):
//   I_cap(E; G) = ħ(n + 1/2),  n = 0, 1, ...
// Each torus has a mirror image about −axis: EBK levels are doublets (the
// exact pairs are split by tunnelling, exponentially small away from the
// separatrix). The error is O(ħ²) relative at a fixed torus.
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "experiments/analysis/quantum/ebk_lagrange.hpp"

namespace lgi::experiments::quantum {

/// The cap action (area of the cap of the orbit about its axis, over 2π) of the
/// Euler torus of energy h on |Π| = G, and the axis it circulates about;
/// nothing on a separatrix or outside the energy range (distinct moments).
struct EulerCap {
  double action = 0.0;
  int around = 0;  // index into moments
};
std::optional<EulerCap> euler_cap_action(const Eigen::Vector3d& moments, double G, double h);

/// The EBK level I_cap(E; G = ħ(j + 1/2)) = ħ(n + 1/2) about the axis of the
/// largest moment (about_largest) or of the smallest; nothing if n lies
/// beyond the separatrix. Distinct moments.
std::optional<double> ebk_euler_level(const Eigen::Vector3d& moments, double hbar, int j, int n, bool about_largest);

/// The EBK level of every level of a free body's spectrum, in its order.
/// Asymmetric: within each j the levels below the separatrix energy
/// G²/(2J_mid) are the doublets n = 0, 0, 1, 1, ... about the largest axis from
/// the bottom, those above it the doublets about the smallest axis from the
/// top. Symmetric (J1 = J2 = A, J3 = C): E = ħ²(j + ½)²/(2A) +
/// ħ²k²(1/(2C) − 1/(2A)), n = j − |k|, i.e. the exact level + ħ²/(8A).
/// Throws std::invalid_argument for a heavy top.
std::vector<EbkRow> ebk_free_rotor_table(const QuantumSpectrum& spectrum, double hbar, int m);

/// The EBK table of any top that has one: a free body or a Lagrange top.
std::vector<EbkRow> ebk_table(const QuantumSpectrum& spectrum, double hbar, int m);

}  // namespace lgi::experiments::quantum
