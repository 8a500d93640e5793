// The component count of common level sets (experiments/analysis/level_set_components.hpp)
// on tops whose Liouville tori are known in closed form:
// - Euler (no weight), K = |Π|²: Π runs on a polhode, the intersection of the sphere
//   |Π| = m with the energy ellipsoid, two closed curves away from the separatrix, and Γ
//   on a circle {Π·Γ = ℓ, |Γ| = 1} over each Π; so two tori (Arnold, Mathematical
//   Methods of Classical Mechanics, §29);
// - Lagrange (J1 = J2, χ on e3), K = Π3: θ librates in one interval between the
//   roots of the cubic, so one torus (docs/actions.md §2);
// - Kovalevskaya near the least energy of a leaf (a non-degenerate minimum): one torus.
#include <catch2/catch.hpp>

#include "experiments/analysis/kovalevskaya_critical.hpp"
#include "experiments/analysis/level_set_components.hpp"

namespace test_level_set_components {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
using experiments::HeavyTopBody;
using experiments::IntegralValue;
using experiments::StateVec6;

TEST_CASE("the free asymmetric body's level sets are two tori", "[level_set]") {
  HeavyTopBody euler;
  euler.J = lie::Vec3(1.0, 2.0, 3.0).asDiagonal();
  const experiments::SecondIntegral K = [](const StateVec6& x) {
    IntegralValue q;
    q.value = x.tail<3>().squaredNorm();
    q.gradient << 0.0, 0.0, 0.0, 2.0 * x.tail<3>();
    return q;
  };
  // |Π|² = 2 h J_i at the permanent rotations: m² between 2h·1 and 2h·3, off 2h·2.
  for (const double l : {0.0, 0.4}) {
    for (const double m2 : {2.4, 3.2, 4.8, 5.6}) {
      const auto n = experiments::level_set_components(euler, l, 1.0, m2, K, 600);
      INFO("l = " << l << ", |Pi|^2 = " << m2 << ", points " << n.points << ", gap " << n.gap << " e " << n.longest[0] << " " << n.longest[1] << " " << n.longest[2] << " " << n.longest[3]);
      CHECK(n.components == 2);
    }
  }
}

TEST_CASE("the Lagrange top's level sets are one torus", "[level_set]") {
  HeavyTopBody lagrange;
  lagrange.J = lie::Vec3(1.0, 1.0, 0.6).asDiagonal();
  lagrange.weight = lie::Vec3(0.0, 0.0, 1.0);
  const experiments::SecondIntegral K = [](const StateVec6& x) {
    IntegralValue q;
    q.value = x(5);
    q.gradient << 0.0, 0.0, 0.0, 0.0, 0.0, 1.0;
    return q;
  };
  for (const double l : {0.0, 0.5})
    for (const double L3 : {-0.6, 0.2, 0.9}) {
      const auto n = experiments::level_set_components(lagrange, l, 2.0, L3, K, 600);
      INFO("l = " << l << ", L3 = " << L3 << ", points " << n.points << ", gap " << n.gap << " e " << n.longest[0] << " " << n.longest[1] << " " << n.longest[2] << " " << n.longest[3]);
      CHECK(n.components == 1);
    }
}

TEST_CASE("near the least energy of a Kovalevskaya leaf the level set is one torus", "[level_set]") {
  HeavyTopBody body;
  body.weight = lie::Vec3(1.0, 0.0, 0.0);
  const HeavyTopBody scaled = experiments::scaled_kovalevskaya(body);
  // l = 0: the least energy is h = -1 (hanging, Γ = -e1) with k = 1; nearby regular values.
  const auto n = experiments::level_set_components(scaled, 0.0, -0.9, 0.95, experiments::kovalevskaya_integral(scaled), 800);
  INFO("points " << n.points << ", gap " << n.gap);
  CHECK(n.components == 1);
  // An empty level set (k far above the range) has no points.
  CHECK(experiments::level_set_components(scaled, 0.0, -0.9, 50.0, experiments::kovalevskaya_integral(scaled), 200).points == 0);
}

}  // namespace test_level_set_components
