// The Kovalevskaya top's (h, k) diagram (experiments/analysis/kovalevskaya_diagram.hpp,
// docs/atlas.md §9):
//  - k of a state is the scene's invariant K over c² (integrators/system/invariants.hpp);
//  - the relative equilibria at l (the critical points of rank 0) evaluate to
//    (h, k) on the Appelrot families to round-off, for the shipped scene and
//    for a rescaled one (J3 = 0.5, m g d = 3: the scaling of h, l and k);
//  - the least and greatest k on an energy surface lie on the families (the
//    curves bound where orbits exist), to 1e-7;
//  - states drawn on the energy surface have k inside that range.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <set>

#include "experiments/analysis/accessible_region.hpp"
#include "experiments/analysis/kovalevskaya_critical.hpp"
#include "experiments/analysis/kovalevskaya_diagram.hpp"
#include "experiments/analysis/poincare_section.hpp"
#include "integrators/system/invariants.hpp"
#include "lie/charts.hpp"
#include "support/shipped_scene.hpp"

namespace test_kovalevskaya_diagram {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
using experiments::HeavyTopBody;

namespace {

HeavyTopBody rescaled_kovalevskaya() {
  HeavyTopBody b;
  b.J = lie::Vec3(1.0, 1.0, 0.5).asDiagonal();
  b.weight = lie::Vec3(3.0, 0.0, 0.0);  // c = 6
  return b;
}

/// A uniformly drawn state of {H = h, Pi.Gamma = l} (rejection on gamma, then the ellipse).
bool draw_state(const HeavyTopBody& body, double l, double h, std::mt19937_64& rng, lie::Vec3& gamma, lie::Vec3& Pi) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int attempt = 0; attempt < 100000; ++attempt) {
    lie::Vec3 g(u(rng), u(rng), u(rng));
    if (g.norm() > 1.0 || g.norm() < 1e-3) continue;
    g.normalize();
    const double q = g.dot(body.J * g), excess = h - experiments::amended_potential(body, l, g);
    if (excess < 0.0) continue;
    const lie::Vec3 ea = g.unitOrthogonal(), eb = g.cross(ea);
    const double a = M_PI * u(rng);
    lie::Vec3 d = std::cos(a) * ea + std::sin(a) * eb;
    d *= std::sqrt(2.0 * excess / d.dot(body.J.inverse() * d));
    gamma = g, Pi = (l / q) * (body.J * g) + d;
    return true;
  }
  return false;
}

}  // namespace

TEST_CASE("k is the scene's Kovalevskaya invariant over c^2", "[kovalevskaya]") {
  const auto scene = testing::shipped_scene("kovalevskaya");
  const HeavyTopBody body = experiments::heavy_top_of(scene, "bifurcation");
  const auto scale = experiments::kovalevskaya_scale(body);
  REQUIRE(scale);
  CHECK(scale->J3 == 1.0);
  CHECK(scale->c == 1.0);
  const system::AnyModel model = system::make_model(scene);
  const system::SceneInvariants inv(scene, model);
  REQUIRE(inv.kovalevskaya_top());
  const auto values = inv.evaluate(scene.initial);
  const lie::Vec3 gamma = scene.initial.R.transpose() * lie::Vec3::UnitZ();
  CHECK(experiments::kovalevskaya_k(body, *scale, gamma, scene.initial.Pi) ==
        Approx(values.scalars[1]).epsilon(1e-14));  // after casimir_vertical_momentum
  CHECK(!experiments::kovalevskaya_scale(experiments::heavy_top_of(testing::shipped_scene("general_top_richter"), "x")));
}

TEST_CASE("the relative equilibria lie on the Appelrot families", "[kovalevskaya]") {
  const HeavyTopBody shipped = experiments::heavy_top_of(testing::shipped_scene("kovalevskaya"), "bifurcation");
  for (const HeavyTopBody& body : {shipped, rescaled_kovalevskaya()}) {
    const auto scale = experiments::kovalevskaya_scale(body);
    REQUIRE(scale);
    std::set<int> families;
    for (const double l : {0.0, 0.4, 1.0, 1.6, 2.0, 2.5, 3.5}) {
      const double ls = scale->l(l);
      for (const auto& e : experiments::equilibria_at(body, l * std::sqrt(scale->c) * scale->J3).rows) {
        const double k = experiments::kovalevskaya_k(body, *scale, e.gamma, e.angular_momentum);
        const auto d = experiments::appelrot_distance(scale->l(e.l), scale->h(e.h), k);
        INFO("l = " << l << " (scaled " << ls << "), h = " << scale->h(e.h) << ", k = " << k);
        CHECK(d.distance <= 1e-12 * (1.0 + k));
        families.insert(d.family);
      }
    }
    CHECK(families.count(0));  // the equilibria with Gamma_2 = 0, Gamma_3 != 0
    CHECK(families.count(1));  // rotations about e1 (also on family 2)
  }
}

TEST_CASE("the range of k on an energy surface is bounded by the Appelrot families", "[kovalevskaya]") {
  for (const HeavyTopBody& body :
       {experiments::heavy_top_of(testing::shipped_scene("kovalevskaya"), "bifurcation"), rescaled_kovalevskaya()}) {
    const auto scale = experiments::kovalevskaya_scale(body);
    REQUIRE(scale);
    std::mt19937_64 rng(12345);
    for (const double ls : {0.0, 0.5, 1.0, 2.0}) {
      const double l = ls * scale->J3 * std::sqrt(scale->c);
      const double lowest = experiments::minimum_energy(body, l);
      for (const double dh : {0.3, 1.0, 2.5, 4.5}) {
        const double h = lowest + dh * scale->J3 * scale->c;
        const auto range = experiments::kovalevskaya_k_range(body, *scale, l, h);
        REQUIRE(!range.empty());
        INFO("l = " << ls << ", h = " << scale->h(h));
        double lo = INFINITY, hi = -INFINITY;
        for (const auto& r : range) {
          INFO("k in [" << r.k_min << ", " << r.k_max << "]");
          CHECK(experiments::appelrot_distance(ls, scale->h(h), r.k_min).distance <= 1e-7 * (1.0 + r.k_min));
          CHECK(experiments::appelrot_distance(ls, scale->h(h), r.k_max).distance <= 1e-7 * (1.0 + r.k_max));
          lo = std::min(lo, r.k_min), hi = std::max(hi, r.k_max);
        }
        for (int k = 0; k < 2000; ++k) {  // every drawn state has its k in the range
          lie::Vec3 g, Pi;
          REQUIRE(draw_state(body, l, h, rng, g, Pi));
          const double kk = experiments::kovalevskaya_k(body, *scale, g, Pi);
          CHECK(kk >= lo - 1e-9 * (1.0 + lo));
          CHECK(kk <= hi + 1e-9 * (1.0 + hi));
        }
      }
    }
  }
}

TEST_CASE("the sampled Appelrot curves satisfy their equations", "[kovalevskaya]") {
  for (const double ls : {0.0, 1.0, 2.0}) {
    const auto curves = experiments::appelrot_curves(ls, -1.0, 5.0, 50);
    std::set<int> families;
    for (const auto& p : curves) {
      CHECK(p.h >= -1.0);
      CHECK(p.h <= 5.0);
      CHECK(experiments::appelrot_distance(ls, p.h, p.k).distance <= 1e-9 * (1.0 + p.k));
      families.insert(p.family);
    }
    CHECK(families.size() == (ls == 0.0 ? 4u : 3u));
  }
}

TEST_CASE("the critical-point solver realises the known Appelrot arcs at l = 0", "[kovalevskaya]") {
  // At l = 0 (Bolsinov, Richter & Fomenko, Sb. Math. 191 (2000) 151; Kharlamov 1983) the least
  // energy is h = -1; k = 0 is a critical value for h > 0, k = h^2 bounds the range for -1 < h < 0.
  const HeavyTopBody scaled = experiments::scaled_kovalevskaya(
      experiments::heavy_top_of(testing::shipped_scene("kovalevskaya"), "bifurcation"));
  std::vector<double> hs;
  for (int i = 0; i <= 40; ++i) hs.push_back(-1.5 + 0.1 * i);
  const auto critical = experiments::kovalevskaya_critical_values(scaled, 0.0, hs, 24);
  std::size_t found = 0;
  for (const auto& at : critical)
    for (const auto& v : at) {
      ++found;
      CHECK(v.rank_gap < 1e-10);
      CHECK(v.family >= 0);
    }
  CHECK(found > 40);
  const std::vector<experiments::AppelrotPoint> probe = {{0, 0, -1.25, -1.25, 0.0}, {0, 0, 1.05, 1.05, 0.0},
                                                          {1, 0, -0.55, -0.55, 0.3025}, {0, 0, -0.55, -0.55, 0.0}};
  const auto realised = experiments::appelrot_realised(probe, 0.0, hs, critical);
  CHECK(realised[0] == 0);  // below the least energy: no state at all
  CHECK(realised[1] == 1);  // k = 0 at h > 0
  CHECK(realised[2] == 1);  // k = h^2, the lower edge of the range for -1 < h < 0
  CHECK(realised[3] == 0);  // k = 0 is not reached for h < 0 at l = 0
}

}  // namespace test_kovalevskaya_diagram
