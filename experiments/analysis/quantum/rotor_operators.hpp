#pragma once
// The rotor's operators in a Wigner block (wigner_basis.hpp; docs/quantum.md):
// the body-fixed angular momentum L̂ (anomalous commutators
// [L̂ᵢ, L̂ⱼ] = −iħ ε_ijk L̂ₖ; Landau & Lifshitz, Quantum Mechanics, §103) and
// the space vertical in the body frame Γ̂ = Rᵀe3, multiplication by the D¹
// functions (Zare, Angular Momentum, eqs. 3.118 and 3.121). In this phase
// convention L̂₁, L̂₃, Γ̂₁, Γ̂₃ are real and L̂₂, Γ̂₂ imaginary.
// Γ̂ couples j to j ± 1: in a block cut at jhi, products of Γ̂'s are wrong
// in the rows and columns of j = jhi only; L̂ keeps j, so L̂'s products are exact.
#include <Eigen/Sparse>
#include <array>
#include <complex>

#include "experiments/analysis/quantum/wigner_basis.hpp"

namespace lgi::experiments::quantum {

using Complex = std::complex<double>;
using ComplexSparse = Eigen::SparseMatrix<Complex>;

struct RotorOperators {
  std::array<ComplexSparse, 3> L;      // body components of the angular momentum
  std::array<ComplexSparse, 3> Gamma;  // body components of the space vertical
};

RotorOperators rotor_operators(const WignerBasis& basis, double hbar);

/// Σᵢ L̂ᵢ²/(2Jᵢ), principal moments J.
ComplexSparse kinetic_energy(const RotorOperators& ops, const Eigen::Vector3d& moments);

/// c·Γ̂, the potential of a torque linear in Γ (gravity: c = m g χ).
ComplexSparse potential_energy(const RotorOperators& ops, const Eigen::Vector3d& c);

}  // namespace lgi::experiments::quantum
