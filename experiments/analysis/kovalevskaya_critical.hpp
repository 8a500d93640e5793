#pragma once
// The critical values of the Kovalevskaya top's energy-momentum map (H, K) on a
// symplectic leaf {Π·Γ = ℓ, |Γ| = 1}, found by solving for the critical points,
// and which sampled points of the Appelrot families they realise (docs/atlas.md §9;
// experiments/EQUILIBRIA.md, "The Kovalevskaya top's (h, k) diagram").
//
// A state is critical when dH, dK, dC, d|Γ|² are linearly dependent (the 4×6
// Jacobian has rank < 4). Away from the equilibria of H on the leaf that is the
// Lagrange condition ∇K = α∇H + β∇C + γ∇|Γ|² with H = h, C = ℓ, |Γ|² = 1: nine
// equations in (Γ, Π, α, β, γ), solved by Newton's method (minimum-norm steps,
// since the solutions at fixed h are circles) from a lattice of states on the
// energy surface and from the critical states found at the previous h. The
// values (h, k) found lie on the Appelrot families (M. P. Kharlamov, Regul.
// Chaotic Dyn. 10 (2005) 381; A. V. Bolsinov, P. H. Richter and A. T. Fomenko,
// Sb. Math. 191 (2000) 151); only arcs of the families are met.
// All in the scaled top J = diag(2, 2, 1), m g χ = (±1, 0, 0) (kovalevskaya_diagram.hpp).
#include <functional>
#include <vector>

#include "experiments/analysis/kovalevskaya_diagram.hpp"
#include "experiments/analysis/level_set_components.hpp"

namespace lgi::experiments {

/// A critical point of (H, K) on the leaf: scaled h̃ and k, the scaled state, the
/// Appelrot family and arc (`piece`) it lies on (−1: none within 1e-6), its distance
/// to it, and rank_gap = σ_min/σ_max of the 4×6 Jacobian (0 to round-off when rank < 4).
struct CriticalValue {
  double h = 0.0, k = 0.0;
  Vec3 gamma = Vec3::Zero(), Pi = Vec3::Zero();
  int family = -1, piece = 0;
  double distance = INFINITY, rank_gap = 1.0;
};

/// k of the scaled top with its gradient in (Γ, Π), for level_set_components.
SecondIntegral kovalevskaya_integral(const HeavyTopBody& scaled);

/// The scaled Kovalevskaya top (J3 = 1, c = 1) with the sign of m g χ1 of `body`.
HeavyTopBody scaled_kovalevskaya(const HeavyTopBody& body);

/// σ_min/σ_max of the rows dH, dk, dC, d|Γ|² of the scaled top at (Γ, Π).
double critical_rank_gap(const HeavyTopBody& scaled, const Vec3& gamma, const Vec3& Pi);

/// The arc of an Appelrot family a point belongs to: 0 for families 0, 1, 3; for
/// family 2, 0 for s < 0, and for s > 0 the sides 1, 2 of the cusp s³ = G (at G = 0:
/// 0 for h̃ < 0, 1 for h̃ > 0). Along one arc h̃ is monotone.
int appelrot_piece(int family, double s, double h, double G);

/// The distinct critical values at scaled ℓ̃ for each scaled h̃ of `hs` (ascending),
/// from `seeds` lattice states per h̃ (h̃ below the least energy gives none).
/// `keep_going`, if given, is called before each h̃; false stops: the energies done so far.
std::vector<std::vector<CriticalValue>> kovalevskaya_critical_values(const HeavyTopBody& scaled, double l_scaled,
                                                                      const std::vector<double>& hs, int seeds,
                                                                      const std::function<bool()>& keep_going = {});

/// Per point of `curve` (families at l_scaled): 1 if the critical values found at the
/// grid energies hs bracketing its h̃ (or at its h̃) both lie on its family and arc, else 0.
std::vector<int> appelrot_realised(const std::vector<AppelrotPoint>& curve, double l_scaled,
                                   const std::vector<double>& hs,
                                   const std::vector<std::vector<CriticalValue>>& critical);

}  // namespace lgi::experiments
