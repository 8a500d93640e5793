// The chaos indicators of chosen states (experiments/analysis/chaos_indicators.hpp,
// experiments/INDICATORS.md):
//  - started on an unstable permanent rotation of a non-integrable top (the
//    shipped general_top_richter and a second general top made up here), the
//    exponent over [T/2, T] is Grammel's rate sqrt(z+) to 1e-3 (z+ the largest
//    positive root of z² + g1 z + g2 = 0, docs/atlas.md §3), the first of the
//    spectrum too, the last is −sqrt(z+), and the spectrum sums to 0 (tr A = 0);
//  - the state goes in through the scene file's [initial] gamma (the attitude
//    of the sweep specs' initial.gamma), as `lgi indicators` reads it;
//  - λ and ⟨Y⟩ of a state equal those of `lgi poincare --lyapunov --megno` (the
//    same tangent flow and tangent vector);
//  - six tangent vectors advanced at once are the six advanced one by one, bit for bit;
//  - the convergence rule.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "experiments/analysis/chaos_indicators.hpp"
#include "experiments/analysis/poincare_section.hpp"
#include "experiments/analysis/relative_equilibria.hpp"
#include "experiments/io/scene_reader.hpp"
#include "integrators/system/model.hpp"
#include "integrators/core/tangent_flow.hpp"
#include "support/shipped_scene.hpp"

namespace test_chaos_indicators {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
using lie::Vec3;

namespace {

/// [x, y, z] with 17 significant digits (a TOML array that reads back to the same doubles).
std::string vec(const Vec3& v) {
  char b[96];
  std::snprintf(b, sizeof b, "[%.17g, %.17g, %.17g]", v.x(), v.y(), v.z());
  return b;
}

/// A general top (no integrable case): J = (1.2, 2, 2.6), χ = (0.5, −0.3, 0.7), m = g = 1.
const char* made_up_top =
    "name = \"made-up general top\"\n[body]\nmass = 1.0\ninertia = [1.2, 2.0, 2.6]\n"
    "center_of_mass = [0.5, -0.3, 0.7]\n[gravity]\ng = 1.0\n";

experiments::HeavyTopBody body_of(const system::Scene& s) {
  experiments::HeavyTopBody b;
  b.J = s.inertia;
  b.weight = *s.mass * s.declared<system::GravityTerm>()->g * *s.center_of_mass;
  return b;
}

/// The scene's body and gravity with the equilibrium as its [initial] state (gamma and angular_momentum).
system::Scene scene_at(const std::string& body_toml, const experiments::RelativeEquilibrium& e) {
  return experiments::parse_scene(body_toml + "[initial]\ngamma = " + vec(e.gamma) +
                                      "\nangular_momentum = " + vec(e.angular_momentum) + "\n",
                                  "equilibrium.toml");
}

/// Every singly or doubly unstable equilibrium at the given ℓ: λ = sqrt(z+) from the
/// indicators within 1e-3; returns how many were checked. T = 24/λ: the
/// deviation that round-off seeds (1e-16 .. 1e-14) grows like e^{λt} and stays
/// below about 1e-5, while the tangent vector aligns within e^{-λT/2} ≈ 6e-6 by T/2.
int check_unstable_equilibria(const std::string& body_toml, const std::vector<double>& ls) {
  const system::Scene top = experiments::parse_scene(body_toml, "top.toml");
  experiments::IndicatorSettings s;
  s.dt = 0.005, s.seed = 1, s.spectrum = true;
  int checked = 0;
  for (const double l : ls)
    for (const auto& e : experiments::equilibria_at(body_of(top), l).rows) {
      if (e.stability != experiments::EquilibriumStability::singly_unstable &&
          e.stability != experiments::EquilibriumStability::doubly_unstable)
        continue;
      const double rate = std::sqrt(0.5 * (-e.g1 + std::sqrt(e.g1 * e.g1 - 4.0 * e.g2)));
      s.t_end = 24.0 / rate;
      const system::Scene scene = scene_at(body_toml, e);
      const auto r = experiments::state_indicators(scene, scene.initial, s, checked);
      double sum = 0.0;
      for (const double x : r.spectrum) sum += x;
      INFO("l = " << l << ", h = " << e.h << ": sqrt(z+) = " << rate << ", lyapunov_last_half = "
                  << r.lyapunov_last_half << ", lyapunov = " << r.lyapunov << ", spectrum " << r.spectrum[0] << " .. "
                  << r.spectrum[5] << ", sum " << sum);
      CHECK(std::abs(r.lyapunov_last_half - rate) <= 1e-3);
      // Over [0, T], with the transient of the first vectors (ln of their projections, over T):
      CHECK(std::abs(r.spectrum[0] - rate) <= 5.0 / s.t_end);
      CHECK(std::abs(r.spectrum[5] + rate) <= 5.0 / s.t_end);  // the Hamiltonian pair ±sqrt(z+)
      CHECK(std::abs(sum) <= 1e-8);                    // volume preserved: tr A = 0
      CHECK(r.megno > 0.25 * rate * s.t_end);  // <Y> ≈ λT/2 on exponential growth, less the transient
      ++checked;
    }
  return checked;
}

}  // namespace

TEST_CASE("indicators on unstable permanent rotations give Grammel's rate (general_top_richter)", "[indicators]") {
  std::string toml = "name = \"general_top_richter\"\n[body]\nmass = 1.0\ninertia = [1.0, 1.5, 2.0]\n"
                     "center_of_mass = [0.8, 0.4, 0.3]\n[gravity]\ng = 1.0\n";
  // The shipped scene's body (experiments/scenes/README.md): the same J, χ, m g.
  const system::Scene shipped = testing::shipped_scene("general_top_richter");
  REQUIRE(shipped.inertia == experiments::parse_scene(toml, "x.toml").inertia);
  REQUIRE(*shipped.center_of_mass == Vec3(0.8, 0.4, 0.3));
  CHECK(check_unstable_equilibria(toml, {1.0, 3.0}) >= 2);
}

TEST_CASE("indicators on unstable permanent rotations give Grammel's rate (a made-up general top)", "[indicators]") {
  CHECK(check_unstable_equilibria(made_up_top, {0.5, 2.0, 4.0}) >= 2);
}

TEST_CASE("the indicators of a state are those of lgi poincare --lyapunov --megno", "[indicators]") {
  const system::Scene scene = testing::shipped_scene("general_top_richter");
  experiments::IndicatorSettings s;
  s.t_end = 30.0, s.dt = 0.01, s.seed = 5;
  const auto mine = experiments::state_indicators(scene, scene.initial, s, 3);
  const auto theirs = experiments::orbit_indicators(scene, scene.initial, s.t_end, s.dt, s.seed, 3);
  CHECK(mine.lyapunov == theirs.lyapunov);
  CHECK(mine.megno == theirs.megno);
  CHECK(std::isfinite(mine.lyapunov_last_half));
  CHECK(std::isnan(mine.spectrum[0]));  // not asked for
}

TEST_CASE("six tangent vectors at once are the six one by one, bit for bit", "[indicators]") {
  const system::Scene scene = experiments::parse_scene(std::string(made_up_top) +
                                                           "[initial]\ngamma = [0.48, 0.6, 0.64]\n"
                                                           "angular_velocity = [0.7, -0.4, 1.3]\n",
                                                       "top.toml");
  const auto model = std::get<system::SceneModel>(system::make_model(scene));
  integrators::Mat6 V;
  for (int k = 0; k < 6; ++k) V.col(k) = experiments::initial_tangent(9, k);
  system::State x = scene.initial;
  integrators::Mat6 all = V;
  for (int n = 0; n < 200; ++n) integrators::tangent_step(model, x, all, 0.01 * n, 0.01);
  for (int k = 0; k < 6; ++k) {
    system::State y = scene.initial;
    integrators::Vec6 v = V.col(k);
    for (int n = 0; n < 200; ++n) integrators::tangent_step(model, y, v, 0.01 * n, 0.01);
    CHECK(v == integrators::Vec6(all.col(k)));
    CHECK(y.Pi == x.Pi);
    CHECK(y.R == x.R);
  }
}

TEST_CASE("converged: the exponents over [T/2, T] and [0, T] agree to rtol", "[indicators]") {
  CHECK(experiments::lyapunov_converged(0.100, 0.104, 0.05));
  CHECK(!experiments::lyapunov_converged(0.100, 0.110, 0.05));
  CHECK(!experiments::lyapunov_converged(NAN, 0.1, 0.05));
  // A regular orbit (the free body): λ(T) ~ ln(cT)/T over [0, T] but 2 ln 2/T over [T/2, T] (linear growth
  // of the tangent vector): both tend to 0 and do not agree to 5 %, so converged = 0 and <Y> ≈ 2 tells.
  const system::Scene free = testing::shipped_scene("free_body_hlw");
  experiments::IndicatorSettings s;
  s.t_end = 200.0, s.dt = 0.01;
  const auto r = experiments::state_indicators(free, free.initial, s, 0);
  CHECK(r.megno == Approx(2.0).margin(0.3));
  CHECK(!r.converged);
}

}  // namespace test_chaos_indicators
