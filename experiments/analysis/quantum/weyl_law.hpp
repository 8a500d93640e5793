#pragma once
// Weyl's law for the quantum top (docs/quantum.md §8): the smooth number of
// levels below E at fixed m,
//   N̄(E) = Vol{H ≤ E at ℓ = mħ}/(2πħ)²,
// the Liouville volume of the reduced space at ℓ (T*S² with a magnetic term,
// which leaves the volume form dA(Γ) d²Π⊥ unchanged):
//   Vol = ∫_{S²} dA(Γ) 2π √(J₁J₂J₃/ΓᵀJΓ) (E − c·Γ − ℓ²/(2ΓᵀJΓ))₊,
// the area of the ellipse of Π = ℓΓ + Π⊥ with T(Π) ≤ E − c·Γ at each Γ.
// For a free body at fixed j (Ĥ commutes with L̂²) the reduced space is the
// sphere |Π| = L = ħ(j + 1/2), of symplectic area 4πL:
//   N̄_j(E) = (j + 1/2)/(2π) · Ω{n̂ ∈ S²: Σ n̂ᵢ²/(2Jᵢ) ≤ E/L²},
// which counts 2j + 1 levels in all.
#include <vector>

#include "experiments/analysis/quantum/quantum_top.hpp"

namespace lgi::experiments::quantum {

/// N̄(E) at ℓ = mħ, by a midpoint rule in (Γ₃, φ) with `nodes` × 2·`nodes`
/// points; the integrand is linear in E at each node, so one sort makes every
/// evaluation a binary search.
class WeylCounting {
 public:
  WeylCounting(const QuantumTop& top, double hbar, int m, int nodes = 400);
  double operator()(double energy) const;

 private:
  std::vector<double> threshold_;                   // ascending: c·Γ + ℓ²/(2ΓᵀJΓ) at each node
  std::vector<double> weight_sum_, weighted_sum_;   // prefix sums of w and w·threshold
  double scale_ = 0.0;                              // 1/(2πħ)²
};

/// N̄_j(E) of a free body (moments J) at total angular momentum j.
double free_rotor_weyl_count(const Eigen::Vector3d& moments, double hbar, int j, double energy, int nodes = 4000);

}  // namespace lgi::experiments::quantum
