#pragma once
// The corrector of periodic_orbit.hpp by multiple shooting (experiments/PERIODIC.md
// "Multiple shooting"; R. Seydel, Practical Bifurcation and Stability Analysis,
// 3rd ed. (2010), §7.3; J. Stoer, R. Bulirsch, Introduction to Numerical
// Analysis, 3rd ed. (2002), §7.3.5).
//
// The period is cut into M segments of length T/M. Unknowns: the segments'
// starts x_0 … x_{M−1}, T and p (h, or ℓ at fixed h): 6M + 2. Equations
// (6M + 5):
//   φ_{T/M}(x_k) − x_{k+1} = 0, k = 0 … M−1, x_M ≡ x_0   (matching; 6M)
//   the phase condition, H = h, Π·Γ = ℓ, |Γ|² = 1 at x_0,  (4)
//   ⟨t, (x_0, T, p) − z_p⟩ = 0                            (continuation)
// with the Jacobian blocks ∂/∂x_k = M_k (the segment's tangent flow),
// ∂/∂x_{k+1} = −I, ∂/∂T = f(φ_{T/M}(x_k))/M. Each Newton step is the
// minimum-norm least-squares solution, as in single shooting. A segment
// integrates only over T/M, so the linearisation holds in a basin that grows
// as the segment's expansion exp(λT/M) shrinks: unstable and long orbits.
// The starts are first the predictor's orbit at kT/M. The monodromy is the
// product M_{M−1} ⋯ M_0; the orbit's checks, multipliers, tangent and
// degeneracy come from the condensed eleven equations (periodic_orbit.hpp)
// with that product, so they mean what they mean for single shooting.
#include "experiments/analysis/periodic/periodic_orbit.hpp"

namespace lgi::experiments {

/// correct_on_family with s.shooting_points = M > 1 segments.
PeriodicOrbit correct_multiple(const PeriodicFlow& body, const FamilyPoint& z_p, const FamilyPoint& t, double fixed,
                               const ShootingSettings& s);

}  // namespace lgi::experiments
