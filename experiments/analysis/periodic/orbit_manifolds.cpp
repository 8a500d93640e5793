#include "experiments/analysis/periodic/orbit_manifolds.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace lgi::experiments {

namespace {

/// The real eigenvector of M for the real eigenvalue nearest mu, unit length.
Vec6 eigenvector_near(const Mat6& M, double mu) {
  const Eigen::EigenSolver<Mat6> es(M);
  int best = 0;
  for (int k = 1; k < 6; ++k)
    if (std::abs(es.eigenvalues()(k) - mu) < std::abs(es.eigenvalues()(best) - mu)) best = k;
  return es.eigenvectors().col(best).real().normalized();
}

/// v moved along the flow into the tangent plane of the section at x0, unit length.
Vec6 into_section(const PeriodicFlow& body, const PhaseSection& sec, const Vec6& x0, const Vec6& v) {
  const Vec6 f = flow_field(body, x0), g = section_gradient(body, sec, x0);
  return (v - (g.dot(v) / g.dot(f)) * f).normalized();
}

/// The crossings of one branch (sign = +1 forwards, −1 backwards) from the fundamental domain.
bool grow(const PeriodicFlow& body, const PhaseSection& sec, const PeriodicOrbit& o, const ManifoldSettings& s,
          int branch, const Vec6& v, double span, double k, OrbitManifolds& out) {
  const double lam = std::abs(out.lambda), eps = s.epsilon * o.x0.norm();
  for (const int side : {1, -1})
    for (int j = 0; j < s.points; ++j) {
      ManifoldPoint p;
      p.branch = branch, p.side = side, p.point = j;
      p.s = eps * std::pow(lam, k * j / s.points);
      p.x = o.x0 + side * p.s * v;
      if (!project_to_level(body, p.x, o.h, o.l, &sec)) return false;
      p.at = section_coordinates(body, sec, p.x);
      out.points.push_back(p);
      bool ok = true;
      const auto cs = section_crossings(body, sec, p.x, span, s.dt, s.max_crossings, 0, ok);
      for (std::size_t c = 0; c < cs.size(); ++c) {
        ManifoldPoint q = p;
        q.crossing = static_cast<int>(c) + 1, q.t = cs[c].t, q.x = cs[c].x;
        q.at = section_coordinates(body, sec, q.x);
        out.points.push_back(q);
      }
      // A point that blew up keeps the crossings before (chaotic orbits wander off; none blows up on a level set).
      (void)ok;
    }
  return true;
}

}  // namespace

std::vector<SectionCrossing> orbit_crossings(const PeriodicFlow& body, const PhaseSection& section,
                                             const PeriodicOrbit& o, double dt, bool& ok) {
  // Half a step past T, so the crossing at T (x0 again) is among them.
  auto cs = section_crossings(body, section, o.x0, o.period + 0.5 * dt, dt, 1000000, 0, ok);
  while (!cs.empty() && cs.back().t > o.period + 1e-6 * dt) cs.pop_back();
  return cs;
}

OrbitManifolds orbit_manifolds(const PeriodicFlow& body, const PhaseSection& file_section, const PeriodicOrbit& o,
                               const ManifoldSettings& s) {
  // A Cardan top: the phase condition and the domain's points on the factor of S that vanishes at x0.
  const PhaseSection section = section_at(body, file_section, o.x0);
  OrbitManifolds out;
  if (o.stability != "hyperbolic" && o.stability != "inverse_hyperbolic") {
    out.why_not = "the orbit is " + o.stability + ", not hyperbolic";
    return out;
  }
  const double scale = 1.0 + o.x0.norm();
  if (std::abs(section_value(body, section, o.x0)) > 1e-10 * scale) {
    out.why_not = "the orbit's point is not on the section";
    return out;
  }
  bool ok = true;
  out.returns = static_cast<int>(orbit_crossings(body, section, o, s.dt, ok).size());
  if (!ok || out.returns == 0) {
    out.why_not = "the orbit's crossings of the section were not found";
    return out;
  }
  // λ: the nontrivial multiplier of modulus > 1 (the pair is real here).
  const double a = std::abs(o.multipliers[4].real()) >= std::abs(o.multipliers[5].real()) ? o.multipliers[4].real()
                                                                                           : o.multipliers[5].real();
  out.lambda = a;
  out.unstable = into_section(body, section, o.x0, eigenvector_near(o.monodromy, a));
  out.stable = into_section(body, section, o.x0, eigenvector_near(o.monodromy, 1.0 / a));
  const double k = a > 0.0 ? 1.0 : 2.0;  // λ < 0: F swaps the sides, F² maps each to itself
  const double span = s.periods * o.period;
  if (!grow(body, section, o, s, 0, out.unstable, span, k, out) ||
      !grow(body, section, o, s, 1, out.stable, -span, k, out)) {
    out.points.clear();
    out.why_not = "a point of the fundamental domain could not be put on the level and the section";
  }
  return out;
}

}  // namespace lgi::experiments
