// The Brody density and its maximum-likelihood fit (brody_fit.hpp).
#include "experiments/analysis/spectral/brody_fit.hpp"

#include <cmath>

#include "experiments/analysis/spectral/special_functions.hpp"

namespace lgi::experiments::spectral {
namespace {

// ln b and its derivatives in c = β + 1, with a = 1 + 1/c:
// ln b = c lnΓ(a), (ln b)' = lnΓ(a) − ψ(a)/c, (ln b)'' = ψ'(a)/c³.
struct LogB {
  double value, d1, d2;
};
LogB log_b(double c) {
  const double a = 1.0 + 1.0 / c, lg = std::lgamma(a);
  return {c * lg, lg - digamma(a) / c, trigamma(a) / (c * c * c)};
}

}  // namespace

double brody_density(double s, double beta) {
  const double c = beta + 1.0, b = std::exp(log_b(c).value);
  if (s == 0.0) return beta == 0.0 ? 1.0 : (beta < 0.0 ? INFINITY : 0.0);
  return c * b * std::pow(s, beta) * std::exp(-b * std::pow(s, c));
}

BrodyLikelihood brody_log_likelihood(std::span<const double> spacings, double beta) {
  // ℓ = n ln c + n ln b + β Σ ln s − b Σ s^c
  const double c = beta + 1.0, n = static_cast<double>(spacings.size());
  const LogB lb = log_b(c);
  const double b = std::exp(lb.value), b1 = b * lb.d1, b2 = b * (lb.d2 + lb.d1 * lb.d1);
  double sum_log = 0.0, m0 = 0.0, m1 = 0.0, m2 = 0.0;  // Σ ln s, Σ s^c, Σ s^c ln s, Σ s^c ln² s
  for (double s : spacings) {
    if (s == 0.0) {
      sum_log = -INFINITY;  // s^c ln^k s → 0 for c > 0
      continue;
    }
    const double ls = std::log(s), sc = std::pow(s, c);
    sum_log += ls;
    m0 += sc;
    m1 += sc * ls;
    m2 += sc * ls * ls;
  }
  BrodyLikelihood l;
  l.value = n * (std::log(c) + lb.value) + (beta == 0.0 ? 0.0 : beta * sum_log) - b * m0;
  l.slope = n * (1.0 / c + lb.d1) + sum_log - b1 * m0 - b * m1;
  l.curvature = n * (-1.0 / (c * c) + lb.d2) - b2 * m0 - 2.0 * b1 * m1 - b * m2;
  return l;
}

BrodyFit fit_brody(std::span<const double> spacings) {
  BrodyFit fit;
  if (spacings.size() < 2) return {NAN, NAN, NAN, 0};
  const BrodyLikelihood at0 = brody_log_likelihood(spacings, 0.0), at1 = brody_log_likelihood(spacings, 1.0);
  double beta;
  if (!(at0.slope > 0)) {
    beta = 0.0;
    fit.bound = -1;
  } else if (at1.slope >= 0) {
    beta = 1.0;
    fit.bound = 1;
  } else {
    // The slope decreases strictly (concavity): bisection to round-off, then no Newton needed.
    double lo = 0.0, hi = 1.0;
    for (int it = 0; it < 60 && hi - lo > 1e-15; ++it) {
      const double mid = 0.5 * (lo + hi);
      (brody_log_likelihood(spacings, mid).slope > 0 ? lo : hi) = mid;
    }
    beta = 0.5 * (lo + hi);
  }
  const BrodyLikelihood at = brody_log_likelihood(spacings, beta);
  fit.beta = beta;
  fit.log_likelihood = at.value;
  fit.standard_error = (at.curvature < 0 && std::isfinite(at.curvature)) ? 1.0 / std::sqrt(-at.curvature) : NAN;
  return fit;
}

}  // namespace lgi::experiments::spectral
