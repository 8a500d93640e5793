// Periodic orbits continued in ℓ, and the manifolds of a hyperbolic orbit on
// a Poincaré section (experiments/analysis/periodic/, experiments/PERIODIC.md):
//  - a family continued in h at ℓ = 2.2 and a family continued in ℓ at fixed
//    h from ℓ = 2.19 through 2.2 agree where they cross: the ℓ-family
//    interpolated to ℓ = 2.2 has the h-family's period and tr P;
//  - the unstable manifold of a hyperbolic orbit of Richter's top at ℓ = 3:
//    the first return of the domain's inner point is λ times as far from x0
//    (the linear part), and a point between two points of the fundamental
//    domain maps onto the curve of their images (the manifold is invariant).
#include <catch2/catch.hpp>
#include <cmath>

#include "experiments/analysis/periodic/lyapunov_families.hpp"
#include "experiments/analysis/periodic/orbit_manifolds.hpp"
#include "support/shipped_scene.hpp"

namespace test_periodic_section {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
using experiments::HeavyTopBody;
using experiments::Vec6;

namespace {

HeavyTopBody body_of(const system::Scene& s) {
  HeavyTopBody b;
  b.J = s.inertia;
  if (s.declared<system::GravityTerm>())
    b.weight = *s.mass * s.declared<system::GravityTerm>()->g * s.center_of_mass.value_or(lie::Vec3::Zero());
  return b;
}

/// The distance from p to the polyline through pts.
double distance_to_polyline(const Vec6& p, const std::vector<Vec6>& pts) {
  double best = INFINITY;
  for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
    const Vec6 d = pts[k + 1] - pts[k];
    const double u = std::clamp((p - pts[k]).dot(d) / d.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (p - pts[k] - u * d).norm());
  }
  return best;
}

}  // namespace

TEST_CASE("A family in h and a family in l agree where they cross", "[periodic]") {
  const HeavyTopBody body = body_of(testing::shipped_scene("general_top_richter"));
  experiments::FamilySettings s;
  s.steps = 1;
  s.h_step = 0.05;
  s.switch_branches = false;
  std::vector<std::string> failures;
  const auto in_h = experiments::lyapunov_families(body, 2.2, s, failures);
  REQUIRE(in_h.size() >= 2);
  const experiments::PeriodicOrbit& a = in_h[1].orbit;  // family 0 at (2.2, h_a), h_a = h_0 + 0.05
  REQUIRE(a.converged);
  // The same family at fixed h_a, from l = 2.19 up through 2.2 (towards larger l the
  // equilibrium's energy rises towards h_a and the orbits shrink).
  experiments::FamilySettings sl = s;
  sl.shooting.in_l = true;
  sl.steps = 5;
  sl.h_step = 0.004;
  const experiments::PeriodicOrbit b0 = experiments::correct_orbit(body, a.x0, a.period, a.h, 2.19, sl.shooting);
  INFO("b0: residual " << b0.residual << " iterations " << b0.iterations);
  REQUIRE(b0.converged);
  CHECK(b0.in_l);
  const auto in_l = experiments::continue_family(body, b0.x0, b0.period, a.h, 2.19, 1.0, 0, sl, failures);
  CHECK(failures.empty());
  REQUIRE(in_l.size() >= 4);
  std::vector<double> ls, periods, traces;
  for (const auto& r : in_l) {
    INFO("l = " << r.orbit.l << " h = " << r.orbit.h << " T = " << r.orbit.period);
    CHECK(r.orbit.h == a.h);  // h is held
    CHECK(r.orbit.residual <= 1e-10);
    CHECK(r.orbit.trivial_deviation <= 1e-8);
    CHECK(r.orbit.product_deviation <= 1e-8);
    ls.push_back(r.orbit.l), periods.push_back(r.orbit.period), traces.push_back(r.orbit.reduced_trace);
  }
  REQUIRE(ls.front() < 2.2);
  REQUIRE(ls.back() > 2.2);
  // Lagrange interpolation through the four rows nearest l = 2.2 (steps of about 0.01: error ~1e-8).
  std::vector<std::size_t> near(ls.size());
  for (std::size_t k = 0; k < near.size(); ++k) near[k] = k;
  std::sort(near.begin(), near.end(), [&](auto i, auto j) { return std::abs(ls[i] - 2.2) < std::abs(ls[j] - 2.2); });
  near.resize(4);
  const auto at = [&](const std::vector<double>& y) {
    double sum = 0.0;
    for (const std::size_t i : near) {
      double w = 1.0;
      for (const std::size_t j : near)
        if (j != i) w *= (2.2 - ls[j]) / (ls[i] - ls[j]);
      sum += w * y[i];
    }
    return sum;
  };
  INFO("h-family at l = 2.2: T = " << a.period << " tr P = " << a.reduced_trace << "; l-family interpolated: T = "
                                   << at(periods) << " tr P = " << at(traces));
  CHECK(std::abs(at(periods) - a.period) <= 1e-6);
  CHECK(std::abs(at(traces) - a.reduced_trace) <= 1e-5);
  // And the corrector at (2.2, h_a) from the l-family's nearest row finds the h-family's orbit.
  const auto& nb = in_l[near[0]].orbit;
  const auto c = experiments::correct_orbit(body, nb.x0, nb.period, a.h, 2.2, s.shooting);
  REQUIRE(c.converged);
  CHECK(std::abs(c.period - a.period) <= 1e-9);
}

TEST_CASE("The unstable manifold of a hyperbolic orbit on Richter's section", "[periodic]") {
  const HeavyTopBody body = body_of(testing::shipped_scene("general_top_richter"));
  // The ℓ = 3 family of test_periodic.cpp's fold, continued past the fold into its hyperbolic part.
  Vec6 x;
  x << 2.818457906841236, 0.7805006052769844, -0.7311888712198521, 0.8999516154419804, 0.2838829693001365,
      -0.3309041396004405;
  experiments::FamilySettings s;
  s.steps = 6;
  s.h_step = 0.06;
  s.switch_branches = false;
  const double h = experiments::euler_poisson_invariants(body, x).value(0);
  std::vector<std::string> failures;
  const auto rows = experiments::continue_family(body, x, 4.3128228985108725, h, 3.0, -1.0, 0, s, failures);
  const experiments::PeriodicOrbit* hyp = nullptr;
  for (const auto& r : rows)
    if (r.orbit.stability == "hyperbolic" && (!hyp || r.orbit.reduced_trace > hyp->reduced_trace)) hyp = &r.orbit;
  REQUIRE(hyp != nullptr);
  // On Richter's section (axis χ/|χ|): the orbit again, its point on the section.
  const experiments::PhaseSection sec{experiments::SectionKind::richter, body.weight.normalized()};
  bool ok = true;
  const auto cs = experiments::section_crossings(body, sec, hyp->x0, hyp->period, 2e-3, 1, 0, ok);
  REQUIRE(cs.size() == 1);
  experiments::ShootingSettings ss;
  ss.section = sec;
  const auto o = experiments::correct_orbit(body, cs[0].x, hyp->period, hyp->h, 3.0, ss);
  REQUIRE(o.converged);
  CHECK(std::abs(o.period - hyp->period) <= 1e-9);
  CHECK(std::abs(experiments::section_value(body, sec, o.x0)) <= 1e-12);
  experiments::ManifoldSettings ms;
  ms.points = 10, ms.periods = 4.0, ms.epsilon = 1e-4, ms.dt = 5e-3;
  const auto coarse = experiments::orbit_manifolds(body, sec, o, ms);
  ms.points = 20;
  const auto fine = experiments::orbit_manifolds(body, sec, o, ms);
  REQUIRE(coarse.why_not.empty());
  REQUIRE(coarse.returns >= 1);
  const int m = coarse.returns;
  const double lambda = coarse.lambda;
  INFO("T = " << o.period << " h = " << o.h << " tr P = " << o.reduced_trace << " lambda = " << lambda << " returns "
              << m);
  REQUIRE(lambda > 1.0);
  // The points (unstable branch, side +1) by point and crossing.
  const auto pick = [](const experiments::OrbitManifolds& mf, int j, int crossing) -> const Vec6* {
    for (const auto& p : mf.points)
      if (p.branch == 0 && p.side == 1 && p.point == j && p.crossing == crossing) return &p.x;
    return nullptr;
  };
  // The linear part: the first return of the inner point is λ times as far out.
  const Vec6 *p0 = pick(coarse, 0, 0), *p1 = pick(coarse, 0, m);
  REQUIRE(p0);
  REQUIRE(p1);
  const double ratio = (*p1 - o.x0).norm() / (*p0 - o.x0).norm();
  CHECK(std::abs(ratio / lambda - 1.0) <= 1e-3);
  // Invariance: the fine domain's odd points (halfway in log s) map onto the polyline of the coarse images.
  for (int k = 2; k <= 4; ++k) {
    std::vector<Vec6> curve;
    for (int j = 0; j < 10; ++j)
      if (const Vec6* q = pick(coarse, j, k * m)) curve.push_back(*q);
    REQUIRE(curve.size() == 10);
    for (int j = 1; j < 19; j += 2) {
      const Vec6* q = pick(fine, j, k * m);
      REQUIRE(q);
      const double seg = (curve[static_cast<std::size_t>(j / 2 + 1)] - curve[static_cast<std::size_t>(j / 2)]).norm();
      INFO("k = " << k << " j = " << j << " distance " << distance_to_polyline(*q, curve) << " segment " << seg);
      CHECK(distance_to_polyline(*q, curve) <= 1e-3 * seg);
    }
  }
}

}  // namespace test_periodic_section
