// The critical periodic orbits of the Kovalevskaya top
// (experiments/analysis/periodic/kovalevskaya_orbits.hpp, experiments/PERIODIC.md
// "Kovalevskaya's top: critical orbits", docs/atlas.md §9):
//  - at ℓ = 0 the two Lyapunov families of the hanging top lie on the Appelrot
//    families k = h̃² and k = 1 to 1e-8 (relative), each on one family along its
//    continuation in h, and are not degenerate (isolated, unlike resonant tori);
//  - at ℓ = 1 the orbits through the critical points found at h = 1, continued
//    in h, lie on families 0, 1 and 2 (one of them hyperbolic) to 1e-8, each on
//    its own family along h, with rank gap of (dH, dK, dC, d|Γ|²) ≤ 1e-8;
//  - at ℓ = 0, h = 0.5 the critical orbits include family 3, k = 1 + h̃²;
//  - a rescaled top (J3 = 1/2, c = 6) at the same scaled (ℓ̃, h̃) has the same k
//    and periods shorter by √c, and a general top gets NaN and −1;
//  - at ℓ = 0, h = 0.9 the strongly hyperbolic critical orbit (family 1, tr P ≈ 1e4),
//    corrected with the default (single) shooting, meets the bar of issue 51: residual
//    ≤ 1e-10, the four trivial multipliers and the product of all six within 1e-8 of 1,
//    its multipliers read from more than one piece of the monodromy; its unstable
//    multiplier is the full monodromy's largest eigenvalue (to 1e-9) and multiple
//    shooting's on 4 segments (to 1e-6).
#include <catch2/catch.hpp>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <set>

#include "experiments/analysis/kovalevskaya_diagram.hpp"
#include "experiments/analysis/periodic/kovalevskaya_orbits.hpp"
#include "experiments/analysis/periodic/lyapunov_families.hpp"
#include "support/heavy_top_body.hpp"
#include "support/shipped_scene.hpp"

namespace test_kovalevskaya_periodic {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
using experiments::FamilyOrbit;
using experiments::HeavyTopBody;

namespace {

HeavyTopBody shipped_kovalevskaya() { return testing::body_of(testing::shipped_scene("kovalevskaya")); }

/// Every row converged, not degenerate, within 1e-8 of one Appelrot family (the
/// same along each family from its second row: its first may sit where two meet);
/// returns the families met.
std::set<int> check_on_curves(const HeavyTopBody& body, const std::vector<FamilyOrbit>& rows) {
  std::set<int> met;
  int family = -1, current = -1;
  for (const FamilyOrbit& r : rows) {
    INFO("family " << r.family << " index " << r.index << " h = " << r.orbit.h << " T = " << r.orbit.period);
    REQUIRE(r.orbit.converged);
    CHECK_FALSE(r.orbit.degenerate);
    const experiments::AppelrotCheck a = experiments::appelrot_check(body, r.orbit.x0, r.orbit.l, r.orbit.h);
    CHECK(a.distance <= 1e-8);
    CHECK(a.rank_gap <= 1e-8);
    REQUIRE(a.family >= 0);
    if (r.family != current) current = r.family, family = -1;
    if (r.index >= 1) {
      if (family < 0) family = a.family;
      CHECK(a.family == family);
    }
    met.insert(a.family);
  }
  return met;
}

experiments::FamilySettings settings(int steps) {
  experiments::FamilySettings s;
  s.steps = steps, s.h_step = 0.05, s.switch_branches = false;
  return s;
}

}  // namespace

TEST_CASE("Kovalevskaya, l = 0: the Lyapunov families lie on the Appelrot curves", "[periodic][kovalevskaya]") {
  const HeavyTopBody body = shipped_kovalevskaya();
  std::vector<std::string> failures;
  const auto rows = experiments::lyapunov_families(body, 0.0, settings(2), failures);
  CHECK(failures.empty());
  REQUIRE(rows.size() == 6);  // two families (ω = 1/√2, 1), 1 + 2 orbits each
  CHECK(rows.back().orbit.h > -0.85);  // continued along h from the hanging top's h = −1
  CHECK(check_on_curves(body, rows) == std::set<int>{1, 2});  // k = h̃², k = 1
}

TEST_CASE("Kovalevskaya, l = 1: critical orbits from critical points, continued in h", "[periodic][kovalevskaya]") {
  const HeavyTopBody body = shipped_kovalevskaya();
  const auto seeds = experiments::kovalevskaya_critical_seeds(body, 1.0, 1.0, 2e-3);
  REQUIRE(seeds.size() >= 3);
  std::vector<FamilyOrbit> rows;
  std::vector<std::string> failures;
  int family = 0;
  for (const auto& seed : seeds) {
    INFO("seed k = " << seed.k << ": " << seed.failure);
    REQUIRE(seed.failure.empty());
    const auto f = experiments::continue_family(body, seed.x, seed.period, seed.h, 1.0, 1.0, family++, settings(2), failures);
    rows.insert(rows.end(), f.begin(), f.end());
  }
  CHECK(failures.empty());
  CHECK(rows.size() == 3 * seeds.size());
  CHECK(check_on_curves(body, rows) == std::set<int>{0, 1, 2});
  CHECK(std::any_of(rows.begin(), rows.end(), [](const FamilyOrbit& r) { return r.orbit.stability == "hyperbolic"; }));
}

TEST_CASE("Kovalevskaya, l = 0: family 3 (k = 1 + h^2) is met at h = 0.5", "[periodic][kovalevskaya]") {
  const HeavyTopBody body = shipped_kovalevskaya();
  std::vector<FamilyOrbit> rows;
  for (const auto& seed : experiments::kovalevskaya_critical_seeds(body, 0.0, 0.5, 2e-3)) {
    REQUIRE(seed.failure.empty());
    FamilyOrbit r;
    r.family = static_cast<int>(rows.size());
    r.orbit = experiments::correct_orbit(body, seed.x, seed.period, 0.5, 0.0, {});
    rows.push_back(r);
  }
  CHECK(check_on_curves(body, rows).count(3) == 1);
}

TEST_CASE("Kovalevskaya: a rescaled top's critical orbits, and a general top", "[periodic][kovalevskaya]") {
  HeavyTopBody scaled;  // J3 = 1/2, m g d = 3: c = 6; at l = J3 sqrt(c), H = 3 its scaled level is the shipped (1, 1)
  scaled.J = lie::Vec3(1.0, 1.0, 0.5).asDiagonal();
  scaled.weight = lie::Vec3(3.0, 0.0, 0.0);
  const double l = 0.5 * std::sqrt(6.0);
  const HeavyTopBody body = shipped_kovalevskaya();
  const auto a = experiments::kovalevskaya_critical_seeds(body, 1.0, 1.0, 2e-3);
  const auto b = experiments::kovalevskaya_critical_seeds(scaled, l, 3.0, 2e-3 / std::sqrt(6.0));
  REQUIRE(a.size() == b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    CHECK(b[i].k == Approx(a[i].k).margin(1e-9));
    const auto oa = experiments::correct_orbit(body, a[i].x, a[i].period, 1.0, 1.0, {});
    experiments::ShootingSettings fine;
    fine.dt = 2e-3 / std::sqrt(6.0);
    const auto ob = experiments::correct_orbit(scaled, b[i].x, b[i].period, 3.0, l, fine);
    REQUIRE((oa.converged && ob.converged));
    CHECK(ob.period * std::sqrt(6.0) == Approx(oa.period).epsilon(1e-9));
    const auto check = experiments::appelrot_check(scaled, ob.x0, l, 3.0);
    CHECK(check.distance <= 1e-8);
    CHECK(check.family == experiments::appelrot_check(body, oa.x0, 1.0, 1.0).family);
  }
  const auto general = experiments::appelrot_check(testing::body_of(testing::shipped_scene("general_top_richter")),
                                                    experiments::Vec6::Ones());
  CHECK(std::isnan(general.k));
  CHECK(general.family == -1);
  CHECK(experiments::kovalevskaya_critical_seeds(testing::body_of(testing::shipped_scene("general_top_richter")), 1.0,
                                                 1.0, 2e-3)
            .empty());
}

TEST_CASE("Kovalevskaya, l = 0, h = 0.9: the hyperbolic critical orbits meet the multiplier bar", "[periodic][kovalevskaya]") {
  const HeavyTopBody body = shipped_kovalevskaya();
  int strong = 0;
  for (const auto& seed : experiments::kovalevskaya_critical_seeds(body, 0.0, 0.9, 2e-3)) {
    REQUIRE(seed.failure.empty());
    const auto o = experiments::correct_orbit(body, seed.x, seed.period, 0.9, 0.0, {});
    INFO("k = " << seed.k << " T = " << o.period << " tr P = " << o.reduced_trace << " pieces " << o.pieces.size());
    REQUIRE(o.converged);
    CHECK(o.residual <= 1e-10);
    if (o.stability != "hyperbolic") continue;
    std::complex<double> product = 1.0;
    for (const auto& mu : o.multipliers) product *= mu;
    CHECK(std::abs(product - 1.0) <= 1e-8);
    for (std::size_t k = 0; k < 4; ++k) CHECK(std::abs(o.multipliers[k] - 1.0) <= 1e-8);
    if (std::abs(o.reduced_trace) < 800.0) continue;
    ++strong;
    CHECK(o.pieces.size() > 1);
    const double lambda = std::max(o.multipliers[4].real(), o.multipliers[5].real());
    const Eigen::EigenSolver<experiments::Mat6> full(o.monodromy, false);
    double largest = 0.0;
    for (int k = 0; k < 6; ++k) largest = std::max(largest, std::abs(full.eigenvalues()(k)));
    CHECK(lambda == Approx(largest).epsilon(1e-9));
    experiments::ShootingSettings four;
    four.shooting_points = 4;
    const auto m = experiments::correct_orbit(body, o.x0, o.period, 0.9, 0.0, four);
    REQUIRE(m.converged);
    CHECK(std::max(m.multipliers[4].real(), m.multipliers[5].real()) == Approx(lambda).epsilon(1e-6));
  }
  CHECK(strong >= 1);
}
}  // namespace test_kovalevskaya_periodic
