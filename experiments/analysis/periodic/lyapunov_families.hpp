#pragma once
// The Lyapunov centre families of the linearly stable relative equilibria at
// ℓ, continued in h (experiments/PERIODIC.md). Lyapunov's centre theorem
// (K. R. Meyer, G. R. Hall, D. Offin, Introduction to Hamiltonian Dynamical
// Systems and the N-Body Problem, 2nd ed. (2009), §9.2): for each
// non-resonant frequency ω of an elliptic equilibrium a family of periodic
// orbits leaves it, its period tending to 2π/ω.
//
// Start: x0 = x_e + ε u, u the real part of the eigenvector of iω of the
// linearisation (tangent to the levels of H, C and |Γ|², since their
// gradients are left null vectors of it), ε = `amplitude` |x_e|, projected
// back onto Π·Γ = ℓ, |Γ| = 1; h = H(x0); period guess 2π/ω. The first row's
// period differs from 2π/ω by O(ε²).
// Continuation, events and branch switching: family_continuation.hpp.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "experiments/analysis/periodic/family_continuation.hpp"

namespace lgi::experiments {

/// The frequencies ω (ascending) of a linearly stable equilibrium, √(−μ) for
/// the roots μ of μ² + g1 μ + g2.
std::vector<double> equilibrium_frequencies(const RelativeEquilibrium& e);

/// Every family of every linearly stable equilibrium at l, in the order of
/// equilibria_at(body, l) then ascending ω, each followed by the doubled
/// families of its period doublings (s.switch_branches); numbered from 0.
/// A mode whose first orbit does not converge is listed in `failures`.
/// With s.shooting.in_l: each family's first orbit (near the equilibrium, at
/// ℓ) is followed by one natural step in h of start_h_step away from the
/// equilibrium, and from there the family is continued in ℓ at that h, its
/// first step direction · h_step in ℓ (experiments/PERIODIC.md).
/// `mode_done`, if given, is called after each mode with the modes done and
/// their number; false stops there (a signal) and drops that mode's rows and
/// failures (the signal may have cut it short: euler_poisson_flow.hpp, shoot).
std::vector<FamilyOrbit> lyapunov_families(const HeavyTopBody& body, double l, const FamilySettings& s,
                                           std::vector<std::string>& failures, double direction = 1.0,
                                           const std::function<bool(std::size_t, std::size_t)>& mode_done = {});

/// The same for a Cardan top with a cyclic outer angle (periodic_flow.hpp) at
/// p1 = l: the modes of its non-degenerate linearly stable relative
/// equilibria (cardan_equilibria_at: `equilibrium` is the row there), the
/// start amplitude relative to max(1, |x_e|), x_e = (0, q2, q3, p).
std::vector<FamilyOrbit> cardan_lyapunov_families(const system::CardanTop& top, double l, const FamilySettings& s,
                                                  std::vector<std::string>& failures, double direction = 1.0,
                                                  const std::function<bool(std::size_t, std::size_t)>& mode_done = {});

/// The state (q, p) of a Cardan relative equilibrium: q = (0, q2, q3), p = M(q)(ω, 0, 0), p1 = l.
Vec6 cardan_equilibrium_state(const system::CardanTop& top, const Vec3& q, double omega, double l);

/// One family from a start (x0, T) at h (a seed), numbered `family`, its
/// first step `direction` · h_step in h; then its doubled families.
/// A seed whose orbit does not converge is listed in `failures`.
std::vector<FamilyOrbit> continue_family(const PeriodicFlow& body, const Vec6& x0, double T, double h, double l,
                                         double direction, int family, const FamilySettings& s,
                                         std::vector<std::string>& failures);

}  // namespace lgi::experiments
