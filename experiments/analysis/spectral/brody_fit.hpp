#pragma once
// The Brody distribution of nearest-neighbour spacings and its parameter β
// by maximum likelihood (T. A. Brody, Lett. Nuovo Cimento 7 (1973) 482;
// Haake, Quantum Signatures of Chaos, 4th ed. 2018, ch. 4; fitting by
// maximum likelihood: docs/spectral_statistics.md §3):
//   P(s) = (β + 1) b s^β exp(−b s^{β+1}),  b = Γ((β + 2)/(β + 1))^{β+1},
// which is Poisson's e^{−s} at β = 0 and Wigner's surmise at β = 1.
#include <span>

namespace lgi::experiments::spectral {

/// The Brody density at s >= 0 (mean 1 for every β > −1).
double brody_density(double s, double beta);

/// The log-likelihood Σ ln P(s_i; β) of the spacings, with its first and
/// second derivatives in β (closed forms through ψ and ψ').
struct BrodyLikelihood {
  double value = 0.0, slope = 0.0, curvature = 0.0;
};
BrodyLikelihood brody_log_likelihood(std::span<const double> spacings, double beta);

/// The estimate: β̂ maximises the likelihood over [0, 1]; the likelihood is
/// strictly concave there (docs/spectral_statistics.md §3), so β̂ is unique,
/// the root of its slope if the slope changes sign, else a bound.
/// `bound` is −1 when β̂ = 0 because the slope is already negative at 0
/// (the spacings are more clustered than Poisson, or some spacing is exactly
/// zero, whose likelihood vanishes for every β > 0), +1 when β̂ = 1 because
/// the slope is still positive at 1 (more repulsion than Wigner's surmise),
/// 0 inside. `standard_error` is 1/√(observed Fisher information) at β̂,
/// −1/ℓ''(β̂); at a bound the estimate is not asymptotically normal and this
/// number is only the likelihood's width there, not a confidence interval.
/// All NaN with fewer than 2 spacings.
struct BrodyFit {
  double beta = 0.0, standard_error = 0.0, log_likelihood = 0.0;
  int bound = 0;
};
BrodyFit fit_brody(std::span<const double> spacings);

}  // namespace lgi::experiments::spectral
