// The Maslov indices of a numerical torus's cycles from the winding of arg det(Q + iP) of
// span(X_H, X_K) (docs/actions.md §5), on a torus whose indices are known: the Lagrange top
// with K = L3. Its section curve is the φ-circle (the spin, no turning point: μ_a = 0) and
// cycle b is the nutation cycle plus n spin cycles (a libration between two turning points of
// θ: μ_b = 2 for every n), the indices of the EBK rule of docs/quantum.md §7.
#include <catch2/catch.hpp>

#include "experiments/analysis/torus_maslov.hpp"
#include "integrators/system/terms/gravity.hpp"
#include "support/shipped_scene.hpp"

namespace test_torus_maslov {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;

TEST_CASE("The Maslov indices of a Lagrange torus are 0 (spin) and 2 (nutation)", "[actions][maslov]") {
  const system::Scene scene = testing::shipped_scene("lagrange_top_cigar");
  experiments::HeavyTopBody body;
  body.J = scene.inertia;
  body.weight = *scene.mass * scene.declared<system::GravityTerm>()->g *
                scene.center_of_mass.value_or(Eigen::Vector3d::Zero());
  experiments::NumericalTorusOptions o;
  o.dt = 2e-3;
  o.crossings = 200;
  const auto t = experiments::numerical_torus(scene, scene.initial, o);
  REQUIRE(t.ok);
  const experiments::SecondIntegralFunction L3 = [](const Eigen::Vector3d&, const Eigen::Vector3d& Pi) {
    return Pi.z();
  };
  const auto mu = experiments::torus_maslov(scene, body, scene.initial, t, L3, o, 100);
  INFO(mu.status << ": measured " << mu.mu_a_measured << ", " << mu.mu_b_measured << "; largest step "
                 << mu.largest_step);
  REQUIRE(mu.ok);
  CHECK(mu.mu_a == 0);
  CHECK(mu.mu_b == 2);
  CHECK(std::abs(mu.mu_b_measured - 2.0) < 0.01);
}

}  // namespace test_torus_maslov
