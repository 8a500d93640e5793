#pragma once
// The stable and unstable manifolds of a hyperbolic periodic orbit on a
// Poincaré section (experiments/PERIODIC.md "Manifolds").
//
// The orbit's point x0 lies on the section S = 0 (section_crossings.hpp; on a
// Cardan top, on the factor of S that vanishes there, which the domain's
// points are put on too) and
// returns to it after m crossings (both directions), i.e. one period T: the
// m-th return map F has the fixed point x0 and, in the section's plane of the
// level set, the eigenvalues λ and 1/λ of the monodromy's nontrivial pair.
// The eigenvector v of the monodromy M for λ (unstable) or 1/λ (stable) is
// tangent to the level set (∇Iᵀ M = ∇Iᵀ and λ ≠ 1 give ∇I·v = 0) and is
// moved along the flow f into the section's tangent plane, v − (∇S·v/∇S·f) f,
// which stays tangent to the manifold (a surface of orbits). The linear
// approximation x0 ± s v holds to O(s²); its fundamental domain is s from ε to
// ε|λ|^k (k = 1, or 2 for λ < 0, where F turns the sides over): N points at
// s_j = ε|λ|^(kj/N), each projected onto the level and the section (an
// O(s²) move), then integrated forwards (unstable) or backwards (stable) for
// `periods` periods, every crossing of the section recorded. The images of
// the fundamental domain under F, F², … cover the branch out to ε|λ|^(k·periods);
// the other crossings are its images at the orbit's other crossings.
// (J. Guckenheimer, P. Holmes, Nonlinear Oscillations, Dynamical Systems and
// Bifurcations of Vector Fields, Springer 1983, §1.3 and §5.2; B. Krauskopf et
// al., Int. J. Bifurcation Chaos 15 (2005) 763–791, on growing manifolds from
// fundamental domains.)
#include <string>
#include <vector>

#include "experiments/analysis/periodic/periodic_orbit.hpp"

namespace lgi::experiments {

struct ManifoldSettings {
  int points = 50;            // N, points of the fundamental domain per branch and side
  double periods = 4.0;       // integrate each point for this many periods
  double epsilon = 1e-5;      // the domain's inner end, relative to |x0|
  double dt = 2e-3;           // the step of the integration
  std::size_t max_crossings = 100000;  // per point
};

struct ManifoldPoint {
  int branch = 0;     // 0 unstable, 1 stable
  int side = 1;       // ±1: x0 ± s v
  int point = 0;      // j, the point of the fundamental domain
  double s = 0.0;     // its distance from x0 along v (absolute)
  int crossing = 0;   // 0: the start on the section; c: the c-th crossing after (before, stable) it
  double t = 0.0;     // the time of the crossing (negative on the stable branch)
  Vec6 x = Vec6::Zero();
  SectionPoint at{};  // (φ, ϑ, sheet) of x
};

struct OrbitManifolds {
  std::vector<ManifoldPoint> points;
  double lambda = 0.0;     // the unstable multiplier (its sign: hyperbolic or inverse hyperbolic)
  int returns = 0;         // m: crossings of the section per period
  Vec6 unstable = Vec6::Zero(), stable = Vec6::Zero();  // the directions v in the section (unit)
  std::string why_not;     // non-empty: no manifolds (not hyperbolic, x0 off the section, a step failed)
};

/// The crossings of the orbit from x0 over one period (the last at T is x0 again).
std::vector<SectionCrossing> orbit_crossings(const PeriodicFlow& body, const PhaseSection& section,
                                             const PeriodicOrbit& o, double dt, bool& ok);

OrbitManifolds orbit_manifolds(const PeriodicFlow& body, const PhaseSection& section, const PeriodicOrbit& o,
                               const ManifoldSettings& s);

}  // namespace lgi::experiments
