#pragma once
// The Kovalevskaya top's (h, k) diagram at fixed ℓ: the Appelrot curves and
// the range of the integral K on the energy surfaces (docs/atlas.md §9;
// experiments/EQUILIBRIA.md, "The Kovalevskaya top's (h, k) diagram").
//
// For J = J3·diag(2, 2, 1) and χ = (d, 0, 0), c = m g d/J3, the integral is
//   K = (Ω1² − Ω2² − cΓ1)² + (2Ω1Ω2 − cΓ2)²
// (S. Kovalevskaya, Acta Math. 12 (1889) 177; docs/conventions.md §6). In the
// scaled values h̃ = H/(J3 c), ℓ̃ = ℓ/(J3 √c), k = K/c², G = ℓ̃²/2, the
// critical values of (H, K) at fixed ℓ lie on the Appelrot families
// (M. P. Kharlamov, Regul. Chaotic Dyn. 10 (2005) 381; A. V. Bolsinov,
// P. H. Richter and A. T. Fomenko, Sb. Math. 191 (2000) 151):
//   family 0: k = 0;
//   family 1: k = (h̃ − G)²;
//   family 2: h̃ = s + G/(2s²), k = 1 − G/s + G²/(4s⁴), s ≠ 0;
//   family 3 (ℓ = 0 only): k = 1 + h̃², h̃ > 0, the limit s → 0 of family 2
//   (at G = 0 family 2 itself is the line k = 1).
// Only arcs of them are critical values; the range of k on an energy surface
// component (a connected 3-manifold, so an interval) is bounded by them.
#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "experiments/analysis/relative_equilibria.hpp"
#include "experiments/io/table_file.hpp"

namespace lgi::experiments {

/// J3 and c of a Kovalevskaya top (J diagonal with J1 = J2 = 2 J3 to 1e-12
/// relative, m g χ along e1); nullopt for any other body.
struct KovalevskayaScale {
  double J3 = 1.0, c = 1.0;
  double h(double H) const;  // h̃
  double l(double ell) const;  // ℓ̃
};
std::optional<KovalevskayaScale> kovalevskaya_scale(const HeavyTopBody& body);

/// k = K/c² of the state (Γ, Π).
double kovalevskaya_k(const HeavyTopBody& body, const KovalevskayaScale& scale, const Vec3& gamma, const Vec3& Pi);

/// A sampled point of an Appelrot family (scaled values; s is the parameter
/// of family 2, h̃ for the others; branch: the sign of s for family 2).
struct AppelrotPoint {
  int family = 0, branch = 0;
  double s = 0.0, h = 0.0, k = 0.0;
};
/// The families at scaled ℓ̃, for h̃ in [h_lo, h_hi], `samples` points per family and branch.
std::vector<AppelrotPoint> appelrot_curves(double l_scaled, double h_lo, double h_hi, int samples);

/// The family nearest to (h̃, k) at scaled ℓ̃, |k − k_family(h̃)|, and the
/// parameter s of that point (the root of family 2; h̃ for the others).
struct AppelrotDistance {
  int family = -1;
  double distance = INFINITY, s = 0.0;
};
AppelrotDistance appelrot_distance(double l_scaled, double h, double k);

/// The least and greatest k on each component of the energy surface (ℓ, h)
/// (unscaled ℓ and h; components as lgi region finds them on a grid of
/// `grid` rings): the largest and smallest of K over a lattice of states,
/// polished by Nelder–Mead's simplex method in a chart of the surface.
struct KRange {
  int component = 0;
  double k_min = 0.0, k_max = 0.0;
};
std::vector<KRange> kovalevskaya_k_range(const HeavyTopBody& body, const KovalevskayaScale& scale, double l, double h,
                                         int grid = 48);

/// The /appelrot, /appelrot_equilibria and /appelrot_range groups of
/// `lgi bifurcation --appelrot` at each ℓ of `ls` (unscaled), with the
/// range of k at each h of `hs` (unscaled) above the minimum energy.
/// `l_done`, if given, is called after each ℓ with the count done, and inside
/// one ℓ (with the count so far) before each energy and each level set; false
/// stops there (a signal: the groups are then incomplete, not to be published).
std::vector<TableGroup> appelrot_groups(const HeavyTopBody& body, const KovalevskayaScale& scale,
                                        const std::vector<double>& ls, const std::vector<double>& hs,
                                        const std::function<bool(std::size_t)>& l_done = {});

}  // namespace lgi::experiments
