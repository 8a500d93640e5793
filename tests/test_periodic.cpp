// Periodic orbits of the Euler–Poisson flow (experiments/analysis/periodic/,
// experiments/PERIODIC.md):
//  - the sixth-order midpoint composition keeps H, Π·Γ and |Γ|² to round-off;
//  - on Richter's general top at ℓ = 2.2 and 3, every Lyapunov family of every
//    linearly stable equilibrium starts with a period within 1e-6 of 2π/ω and
//    an energy within 1e-6 of the equilibrium's; every orbit has a residual
//    ≤ 1e-10, a product of multipliers within 1e-8 of 1, and four multipliers
//    within 1e-8 of 1 at each family's first orbit (2e-6 further on);
//  - one orbit re-integrated for one period by rkmk4 on SO(3) × ℝ³ (another
//    scheme, another state space) returns to its point to 1e-8;
//  - the general top's orbits are not reported degenerate; on a Lagrange top the
//    carrousels' families are, with periods integer multiples of T_theta to 1e-9.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "experiments/analysis/actions.hpp"
#include "experiments/analysis/periodic/lyapunov_families.hpp"
#include "experiments/io/gamma_attitude.hpp"
#include "integrators/registry.hpp"
#include "support/shipped_scene.hpp"

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

struct EndRecorder final : integrators::Observer {
  system::State last;
  void observe(std::int64_t, double, const system::State& x) override { last = x; }
};

/// (Π, Γ) after one period of rkmk4 on SO(3) × ℝ³ from x0.
Vec6 rerun(system::Scene scene, const Vec6& x0, double T, double dt) {
  scene.initial.R = experiments::attitude_from_gamma(lie::Vec3(x0.tail<3>()).normalized());
  scene.initial.Pi = x0.head<3>();
  const system::AnyModel model = system::make_model(scene);
  EndRecorder rec;
  const auto steps = static_cast<std::int64_t>(std::ceil(T / dt));
  integrators::RunConfig cfg{0.0, T, T / static_cast<double>(steps), 0.0, steps};
  system::State x = scene.initial;
  REQUIRE(integrators::find_scheme("rkmk4")->run(model, x, cfg, rec).ok);
  Vec6 out;
  out << rec.last.Pi, rec.last.R.transpose() * lie::Vec3::UnitZ();
  return out;
}

}  // namespace

TEST_CASE("the midpoint composition keeps H, C and |Gamma|^2", "[periodic]") {
  const HeavyTopBody body = body_of(testing::shipped_scene("general_top_richter"));
  Vec6 x;
  x << 0.3, -1.1, 2.0, 0.6, 0.0, 0.8;
  const auto before = experiments::euler_poisson_invariants(body, x).value;
  const auto shot = experiments::shoot(body, x, 7.3, 1e-2);
  REQUIRE(shot.ok);
  const auto after = experiments::euler_poisson_invariants(body, shot.end).value;
  CHECK((after - before).cwiseAbs().maxCoeff() <= 1e-13);
  CHECK(std::abs(shot.monodromy.determinant() - 1.0) <= 1e-12);  // a divergence-free field
}

TEST_CASE("Lyapunov families of a general top: periods, residuals, multipliers", "[periodic]") {
  const auto scene = testing::shipped_scene("general_top_richter");
  const HeavyTopBody body = body_of(scene);
  experiments::FamilySettings s;
  s.steps = 1;
  s.h_step = 0.02;
  bool rerun_done = false;
  for (const double l : {2.2, 3.0}) {
    const auto rows = experiments::lyapunov_families(body, l, s);
    const auto eqs = experiments::equilibria_at(body, l).rows;
    int stable_modes = 0;
    for (const auto& e : eqs)
      if (e.stability == experiments::EquilibriumStability::stable)
        stable_modes += static_cast<int>(experiments::equilibrium_frequencies(e).size());
    int firsts = 0;
    for (const auto& r : rows) {
      INFO("l = " << l << " family " << r.family << " index " << r.index << " T = " << r.orbit.period);
      CHECK(r.orbit.residual <= 1e-10);
      // The trivial multipliers form Jordan blocks, split by ~√(discretisation
      // error) off the equilibrium (experiments/PERIODIC.md, "Accuracy").
      CHECK(r.orbit.trivial_deviation <= (r.index == 0 ? 1e-8 : 2e-6));
      CHECK(r.orbit.product_deviation <= 1e-8);
      CHECK_FALSE(r.orbit.degenerate);
      if (r.index != 0) continue;
      ++firsts;
      CHECK(std::abs(r.orbit.period - 2.0 * std::numbers::pi / r.omega) <= 1e-6);
      CHECK(std::abs(r.orbit.h - eqs[static_cast<std::size_t>(r.equilibrium)].h) <= 1e-6);
    }
    CHECK(firsts == stable_modes);
    CHECK(stable_modes >= 2);
    if (!rerun_done && !rows.empty()) {
      const auto& o = rows.back().orbit;
      CHECK((rerun(scene, o.x0, o.period, 2e-4) - o.x0).norm() <= 1e-8);
      rerun_done = true;
    }
  }
}

TEST_CASE("Lagrange top: the carrousels' families are degenerate, periods multiples of T_theta", "[periodic]") {
  const auto scene = testing::shipped_scene("lagrange_top_cigar");
  const HeavyTopBody body = body_of(scene);
  const auto lagrange = experiments::lagrange_body(body);
  REQUIRE(lagrange);
  experiments::FamilySettings s;
  s.steps = 1;
  s.h_step = 0.02;
  int degenerate = 0;
  for (const auto& r : experiments::lyapunov_families(body, 3.0, s)) {
    CHECK(r.orbit.residual <= 1e-10);
    if (!r.orbit.degenerate) continue;
    ++degenerate;
    const auto torus = experiments::lagrange_actions(*lagrange, 3.0, r.orbit.x0(2), r.orbit.h);
    REQUIRE(torus);
    const double ratio = r.orbit.period / torus->period;
    INFO("family " << r.family << " T = " << r.orbit.period << " T_theta = " << torus->period);
    CHECK(std::abs(ratio - std::round(ratio)) * torus->period <= 1e-9);
    CHECK(std::round(ratio) >= 1.0);
  }
  CHECK(degenerate >= 2);
}
