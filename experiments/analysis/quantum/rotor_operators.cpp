#include "experiments/analysis/quantum/rotor_operators.hpp"

#include <cmath>
#include <vector>

namespace lgi::experiments::quantum {
namespace {

using Triplets = std::vector<Eigen::Triplet<Complex>>;

ComplexSparse from_triplets(Eigen::Index n, const Triplets& t) {
  ComplexSparse a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  a.makeCompressed();
  return a;
}

/// L̂₃ = ħk; L̂± = L̂₁ ± iL̂₂ lower and raise k (the anomalous signs, Zare eq. 3.104):
/// L̂+|j,k⟩ = ħ√(j(j+1) − k(k−1)) |j,k−1⟩, L̂−|j,k⟩ = ħ√(j(j+1) − k(k+1)) |j,k+1⟩.
void angular_momentum(const WignerBasis& b, double hbar, RotorOperators& ops) {
  std::array<Triplets, 3> t;
  for (int j = b.jlo; j <= b.jhi; ++j)
    for (int k = -j; k <= j; ++k) {
      const Eigen::Index col = b.index(j, k);
      const double jj = double(j) * (j + 1);
      t[2].emplace_back(col, col, hbar * k);
      if (k > -j) {  // L̂+ component: ⟨k−1| L̂₁ |k⟩ = a/2, ⟨k−1| L̂₂ |k⟩ = a/(2i)
        const double a = hbar * std::sqrt(jj - double(k) * (k - 1));
        t[0].emplace_back(b.index(j, k - 1), col, 0.5 * a);
        t[1].emplace_back(b.index(j, k - 1), col, Complex(0.0, -0.5 * a));
      }
      if (k < j) {  // L̂− component: ⟨k+1| L̂₁ |k⟩ = a/2, ⟨k+1| L̂₂ |k⟩ = −a/(2i)
        const double a = hbar * std::sqrt(jj - double(k) * (k + 1));
        t[0].emplace_back(b.index(j, k + 1), col, 0.5 * a);
        t[1].emplace_back(b.index(j, k + 1), col, Complex(0.0, 0.5 * a));
      }
    }
  for (int i = 0; i < 3; ++i) ops.L[static_cast<std::size_t>(i)] = from_triplets(b.size(), t[static_cast<std::size_t>(i)]);
}

/// Γ̂_q = D¹_{0q}(R) (spherical body components, Γ̂_{±1} = ∓(Γ̂₁ ± iΓ̂₂)/√2).
/// With D¹_{0q} = (−1)^q D¹*_{0,−q} and Zare eq. 3.118,
///   ⟨j', k−q, m| Γ̂_q |j, k, m⟩ = (−1)^q √((2j+1)/(2j'+1)) ⟨j m 1 0|j' m⟩ ⟨j k 1 −q|j' k−q⟩:
/// Γ̂_q lowers k by q, as L̂ does (docs/quantum.md derives it).
void vertical(const WignerBasis& b, RotorOperators& ops) {
  std::array<Triplets, 3> t;
  const double r = 1.0 / std::sqrt(2.0);
  for (int j = b.jlo; j <= b.jhi; ++j)
    for (int k = -j; k <= j; ++k)
      for (int jp = j - 1; jp <= j + 1; ++jp) {
        if (jp < b.jlo || jp > b.jhi) continue;
        const double cm = clebsch_gordan_1(j, b.m, 0, jp);
        if (cm == 0.0) continue;
        const double norm = std::sqrt((2.0 * j + 1.0) / (2.0 * jp + 1.0)) * cm;
        for (int q = -1; q <= 1; ++q) {
          if (std::abs(k - q) > jp) continue;
          const double g = (q == 0 ? 1.0 : -1.0) * norm * clebsch_gordan_1(j, k, -q, jp);
          if (g == 0.0) continue;
          const Eigen::Index row = b.index(jp, k - q), col = b.index(j, k);
          if (q == 0) {
            t[2].emplace_back(row, col, g);
          } else {  // Γ̂₁ = (Γ̂₋₁ − Γ̂₊₁)/√2, Γ̂₂ = i(Γ̂₋₁ + Γ̂₊₁)/√2
            t[0].emplace_back(row, col, -q * r * g);
            t[1].emplace_back(row, col, Complex(0.0, r * g));
          }
        }
      }
  for (int i = 0; i < 3; ++i)
    ops.Gamma[static_cast<std::size_t>(i)] = from_triplets(b.size(), t[static_cast<std::size_t>(i)]);
}

}  // namespace

RotorOperators rotor_operators(const WignerBasis& basis, double hbar) {
  RotorOperators ops;
  angular_momentum(basis, hbar, ops);
  vertical(basis, ops);
  return ops;
}

ComplexSparse kinetic_energy(const RotorOperators& ops, const Eigen::Vector3d& moments) {
  ComplexSparse t = (ops.L[0] * ops.L[0]) * Complex(0.5 / moments(0));
  t += (ops.L[1] * ops.L[1]) * Complex(0.5 / moments(1));
  t += (ops.L[2] * ops.L[2]) * Complex(0.5 / moments(2));
  t.prune(Complex(0.0));
  return t;
}

ComplexSparse potential_energy(const RotorOperators& ops, const Eigen::Vector3d& c) {
  ComplexSparse v = ops.Gamma[0] * Complex(c(0));
  v += ops.Gamma[1] * Complex(c(1));
  v += ops.Gamma[2] * Complex(c(2));
  v.prune(Complex(0.0));
  return v;
}

}  // namespace lgi::experiments::quantum
