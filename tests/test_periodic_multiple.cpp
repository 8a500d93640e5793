// Multiple shooting and the Lyapunov families continued in ℓ (experiments/PERIODIC.md
// "Multiple shooting", "Continuation in ℓ"):
//  - on Richter's top at ℓ = 2.2 (the orbit of test_periodic.cpp's period
//    doubling), single shooting and multiple shooting with M = 3 and 5 segments
//    from the same seed, 5 % off the orbit, find the same orbit: period and point
//    to 1e-9, the product of the segments' monodromies equal to the single shot's
//    to 1e-7 and the same tr P; wrong matching conditions (a segment's start, its
//    T/M derivative, the order of the product) would break each;
//  - multiple shooting along a family: the continuation with M = 4 retraces the
//    family of single shooting (h and T at each step to 1e-8);
//  - --continue-in l from an equilibrium: the family of the hanging equilibrium's
//    slow mode at ℓ = 2.2, stepped to h_e + 0.02 and then continued in ℓ at that
//    h, crosses ℓ = 2.2 again at the orbit the h-family has there.
#include <catch2/catch.hpp>
#include <cmath>

#include "experiments/analysis/periodic/lyapunov_families.hpp"
#include "support/heavy_top_body.hpp"
#include "support/shipped_scene.hpp"

namespace test_periodic_multiple {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
using testing::body_of;
using experiments::HeavyTopBody;
using experiments::Vec6;

namespace {

/// The ℓ = 2.2 orbit of period ≈ 4.06 (test_periodic.cpp).
Vec6 orbit_point() {
  Vec6 x;
  x << -0.5440143623441437, -0.6150665918126653, -2.0653514662689068, -0.33283680104325525, -0.37020048866337674,
      -0.8672780765503418;
  return x;
}
constexpr double orbit_period = 4.061522325732049;

}  // namespace

TEST_CASE("Single and multiple shooting find the same orbit", "[periodic]") {
  const HeavyTopBody body = body_of(testing::shipped_scene("general_top_richter"));
  const Vec6 x = orbit_point();
  const double h = experiments::euler_poisson_invariants(body, x).value(0);
  Vec6 d;
  d << 0.3, -0.5, 0.2, 0.6, -0.1, 0.4;
  const Vec6 seed = x + 0.05 * x.norm() * d.normalized();
  experiments::ShootingSettings single;
  const auto o1 = experiments::correct_orbit(body, seed, 1.02 * orbit_period, h, 2.2, single);
  REQUIRE(o1.converged);
  CHECK(std::abs(o1.period - orbit_period) <= 1e-9);
  for (const int M : {3, 5}) {
    experiments::ShootingSettings multiple;
    multiple.shooting_points = M;
    const auto om = experiments::correct_orbit(body, seed, 1.02 * orbit_period, h, 2.2, multiple);
    INFO("M = " << M << ": T = " << om.period << ", residual " << om.residual << ", iterations " << om.iterations);
    REQUIRE(om.converged);
    CHECK(om.residual <= 1e-10);
    CHECK(std::abs(om.period - o1.period) <= 1e-9);
    CHECK((om.x0 - o1.x0).norm() <= 1e-9);
    CHECK((om.monodromy - o1.monodromy).cwiseAbs().maxCoeff() <= 1e-7);
    CHECK(std::abs(om.reduced_trace - o1.reduced_trace) <= 1e-8);
    CHECK(om.trivial_deviation <= 1e-8);
    CHECK(om.product_deviation <= 1e-8);
  }
}

TEST_CASE("Multiple shooting converges from a seed where single shooting does not", "[periodic]") {
  // 16 % of |x| off the orbit and the period guess 9 % long: single shooting
  // converges to an orbit of period ≈ 2T (measured: T + 4.0615), M = 2 … 8
  // segments to the orbit (measured: to 1e-12 in 8 to 10 iterations).
  const HeavyTopBody body = body_of(testing::shipped_scene("general_top_richter"));
  const Vec6 x = orbit_point();
  const double h = experiments::euler_poisson_invariants(body, x).value(0);
  Vec6 d;
  d << 0.5912273138884327, 0.14899518433845696, -0.4901292022938108, 0.539089491255904, 0.10816135874850549,
      -0.2927587817746517;
  const Vec6 seed = x + 0.16 * x.norm() * d;
  const auto o1 = experiments::correct_orbit(body, seed, 4.43, h, 2.2, experiments::ShootingSettings{});
  INFO("single shooting: converged " << o1.converged << ", T = " << o1.period);
  const auto exact = experiments::correct_orbit(body, x, orbit_period, h, 2.2, experiments::ShootingSettings{});
  REQUIRE(exact.converged);
  experiments::ShootingSettings multiple;
  multiple.shooting_points = 4;
  const auto o4 = experiments::correct_orbit(body, seed, 4.43, h, 2.2, multiple);
  REQUIRE(o4.converged);
  CHECK(std::abs(o4.period - orbit_period) <= 1e-9);
  // The same orbit (its point lies on the phase hyperplane through the seed,
  // elsewhere on it): it closes after T, with the same tr P.
  const auto back = experiments::shoot(body, o4.x0, orbit_period, 2e-3);
  CHECK((back.end - o4.x0).norm() <= 1e-9);
  CHECK(std::abs(o4.reduced_trace - exact.reduced_trace) <= 1e-7);
}

TEST_CASE("Multiple shooting retraces a family of single shooting", "[periodic]") {
  const HeavyTopBody body = body_of(testing::shipped_scene("general_top_richter"));
  const Vec6 x = orbit_point();
  const double h = experiments::euler_poisson_invariants(body, x).value(0);
  experiments::FamilySettings s;
  s.steps = 2, s.h_step = 0.02, s.switch_branches = false, s.locate_events = false;
  std::vector<std::string> failures;
  const auto single = experiments::continue_family(body, x, orbit_period, h, 2.2, 1.0, 0, s, failures);
  s.shooting.shooting_points = 4;
  const auto multiple = experiments::continue_family(body, x, orbit_period, h, 2.2, 1.0, 0, s, failures);
  CHECK(failures.empty());
  REQUIRE(single.size() == 3);
  REQUIRE(multiple.size() == single.size());
  for (std::size_t k = 0; k < single.size(); ++k) {
    INFO("row " << k);
    CHECK(std::abs(multiple[k].orbit.h - single[k].orbit.h) <= 1e-8);
    CHECK(std::abs(multiple[k].orbit.period - single[k].orbit.period) <= 1e-8);
  }
}

TEST_CASE("A Lyapunov family continued in l from its equilibrium", "[periodic][slow]") {
  const HeavyTopBody body = body_of(testing::shipped_scene("general_top_richter"));
  experiments::FamilySettings s;
  s.shooting.in_l = true;
  s.steps = 3, s.h_step = 0.01, s.start_h_step = 0.02, s.switch_branches = false, s.locate_events = false;
  std::vector<std::string> failures;
  const auto rows = experiments::lyapunov_families(body, 2.2, s, failures, 1.0);
  CHECK(failures.empty());
  // The slow mode of the lowest equilibrium (the hanging top): its family's rows.
  const auto eqs = experiments::equilibria_at(body, 2.2).rows;
  std::vector<experiments::FamilyOrbit> fam;
  int chosen = -1;
  for (const auto& r : rows) {
    if (r.index == 0 && (chosen < 0 || eqs[static_cast<std::size_t>(r.equilibrium)].h <
                                           eqs[static_cast<std::size_t>(rows[static_cast<std::size_t>(chosen)].equilibrium)].h))
      chosen = static_cast<int>(&r - rows.data());
  }
  REQUIRE(chosen >= 0);
  for (const auto& r : rows)
    if (r.family == rows[static_cast<std::size_t>(chosen)].family) fam.push_back(r);
  REQUIRE(fam.size() == 4);
  const auto& e = eqs[static_cast<std::size_t>(fam[0].equilibrium)];
  CHECK(std::abs(fam[0].orbit.h - e.h) <= 1e-6);
  CHECK(std::abs(fam[0].orbit.period - 2.0 * std::acos(-1.0) / fam[0].omega) <= 1e-6);
  const double h1 = fam[1].orbit.h;
  CHECK(std::abs(std::abs(h1 - fam[0].orbit.h) - 0.02) <= 1e-12);
  CHECK(std::abs(fam[1].orbit.l - 2.2) <= 1e-12);
  CHECK(std::abs(fam[2].orbit.l - 2.21) <= 1e-12);
  CHECK(fam[3].orbit.l > 2.21);
  for (std::size_t k = 1; k < fam.size(); ++k) {
    INFO("row " << k << ": l = " << fam[k].orbit.l << ", h = " << fam[k].orbit.h << ", T = " << fam[k].orbit.period);
    CHECK(fam[k].orbit.residual <= 1e-10);
    CHECK(std::abs(fam[k].orbit.h - h1) <= 1e-10);
  }
  // Independently, from the same equilibrium's family at ℓ = 2.21 continued in
  // h with a first step that lands on h1: the orbit at (2.21, h1) again.
  const auto eqs2 = experiments::equilibria_at(body, 2.21).rows;
  std::size_t near = 0;
  for (std::size_t i = 1; i < eqs2.size(); ++i)
    if ((eqs2[i].gamma - e.gamma).norm() < (eqs2[near].gamma - e.gamma).norm()) near = i;
  experiments::FamilySettings in_h;
  in_h.steps = 1, in_h.switch_branches = false, in_h.locate_events = false;
  in_h.h_step = std::abs(h1 - eqs2[near].h);
  const auto rows2 = experiments::lyapunov_families(body, 2.21, in_h, failures);
  const experiments::PeriodicOrbit* match = nullptr;
  for (const auto& r : rows2)
    if (r.index == 1 && r.equilibrium == static_cast<int>(near) && std::abs(r.omega - fam[0].omega) < 0.05) match = &r.orbit;
  REQUIRE(match != nullptr);
  INFO("at l = 2.21 from the equilibrium: h = " << match->h << ", T = " << match->period << "; in l: T = "
                                               << fam[2].orbit.period);
  CHECK(std::abs(match->h - h1) <= 1e-6);
  CHECK(std::abs(match->period - fam[2].orbit.period) <= 1e-6);
}

}  // namespace test_periodic_multiple
