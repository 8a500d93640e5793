// Relative equilibria of heavy tops (experiments/analysis/relative_equilibria.hpp):
//  - every equilibrium at a given l satisfies the equilibrium equations to
//    round-off, and their number is 2, 4 or 6;
//  - the Lagrange top's carrousels lie on the closed-form curve of
//    docs/atlas.md §5 and its sleeping top is stable iff L3^2 > 4 A m g z0;
//  - the free body (Euler) gives the principal-axis rotations, the middle
//    axis unstable;
//  - the stability class agrees with direct simulation: a 1e-6 perturbation
//    stays small at a stable equilibrium and grows at the predicted rate
//    (within 5%) at a singly unstable one;
//  - folds of the branches have g2 = 0 (a double zero eigenvalue).
#include <catch2/catch.hpp>
#include <cmath>

#include "experiments/analysis/relative_equilibria.hpp"
#include "integrators/registry/registry.hpp"
#include "lie/charts.hpp"
#include "support/heavy_top_body.hpp"
#include "support/shipped_scene.hpp"

namespace test_relative_equilibria {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
using testing::body_of;
using experiments::EquilibriumStability;
using experiments::HeavyTopBody;
using experiments::RelativeEquilibrium;

namespace {

/// The largest |Π − Π*| + |Γ − Γ*| (body quantities are constant at a relative
/// equilibrium) over samples, for a run from the equilibrium perturbed by 1e-6.
struct Growth {
  std::vector<double> t, deviation;
};

Growth perturbed_run(system::Scene scene, const RelativeEquilibrium& e, double t_end) {
  const lie::Vec3 g = e.gamma;
  scene.initial.R = lie::matrix_from_euler_zxz({0.0, std::acos(std::clamp(g.z(), -1.0, 1.0)), std::atan2(g.x(), g.y())});
  scene.initial.Pi = e.angular_momentum + lie::Vec3(1e-6, -1e-6, 1e-6);
  const system::AnyModel model = system::make_model(scene);
  struct Recorder final : integrators::Observer {
    const RelativeEquilibrium* eq = nullptr;
    Growth out;
    void observe(std::int64_t, double t, const system::State& x) override {
      const lie::Vec3 gamma = x.R.transpose() * lie::Vec3::UnitZ();
      out.t.push_back(t);
      out.deviation.push_back((x.Pi - eq->angular_momentum).norm() + (gamma - eq->gamma).norm());
    }
  } recorder;
  recorder.eq = &e;
  integrators::RunConfig cfg{0.0, t_end, 1e-3, 0.0, 10};
  system::State x = scene.initial;
  REQUIRE(integrators::find_scheme("rkmk4")->run(model, x, cfg, recorder).ok);
  return recorder.out;
}

}  // namespace

TEST_CASE("equilibria of a general top satisfy the equations to round-off", "[equilibria]") {
  const auto scene = testing::shipped_scene("general_top_richter");
  const HeavyTopBody body = body_of(scene);
  for (double l : {-3.0, 0.5, 1.0, 2.0, 2.2, 3.0, 5.0, 20.0}) {
    const auto set = experiments::equilibria_at(body, l);
    INFO("l = " << l << ": " << set.rows.size() << " equilibria");
    CHECK((set.rows.size() == 2 || set.rows.size() == 4 || set.rows.size() == 6));
    for (const auto& e : set.rows) {
      CHECK(e.residual <= 1e-14 * (1.0 + e.omega * e.omega));
      CHECK(std::abs(e.gamma.norm() - 1.0) <= 4e-16);
      CHECK(std::abs(e.l - l) <= 1e-14 * std::max(1.0, std::abs(l)));
    }
  }
  const auto at_zero = experiments::equilibria_at(body, 0.0);  // hanging and upright
  CHECK(at_zero.rows.size() >= 2);
}

TEST_CASE("folds of the branches have g2 = 0", "[equilibria]") {
  const HeavyTopBody body = body_of(testing::shipped_scene("general_top_richter"));
  const auto set = experiments::equilibrium_branches(body, 400);
  int folds = 0;
  for (const auto& e : set.rows) {
    if (!e.fold) continue;
    ++folds;
    CHECK(std::abs(e.g2) <= 1e-6 * e.g1 * e.g1);
  }
  CHECK(folds >= 2);
}

TEST_CASE("Lagrange top: carrousels on the closed-form curve, sleeping-top threshold", "[equilibria]") {
  const auto scene = testing::shipped_scene("gyroscope");  // J1 = J2, chi on e3
  const HeavyTopBody body = body_of(scene);
  const double A = body.J(0, 0), C = body.J(2, 2), mgz = body.weight.z();
  int carrousels = 0;
  for (double l : {0.01, 0.02, 0.05, 0.1}) {
    for (const auto& e : experiments::equilibria_at(body, l).rows) {
      const double u = e.gamma.z();
      if (std::abs(std::abs(u) - 1.0) < 1e-12) {
        // The sleeping top: Gamma = +-e3, L3 = l; stable iff L3^2 > 4 A m g z0 (upright).
        if (u > 0) CHECK((e.stability == EquilibriumStability::stable) == (l * l > 4.0 * A * mgz));
        continue;
      }
      ++carrousels;
      const double a = A + (C - A) * u * u;
      CHECK(e.l * e.l == Approx(mgz * a * a / ((C - A) * u)).epsilon(1e-12));
      CHECK(e.h == Approx(mgz * (a / (2.0 * (C - A) * u) + u)).epsilon(1e-12));
    }
  }
  CHECK(carrousels >= 4);
}

TEST_CASE("free body: principal-axis rotations, the middle axis unstable", "[equilibria]") {
  const HeavyTopBody body = body_of(testing::shipped_scene("free_body_hlw"));  // I = (2, 1, 2/3)
  const auto set = experiments::equilibria_at(body, 1.0);
  REQUIRE(set.rows.size() == 6);  // +-e_i for each axis
  for (const auto& e : set.rows) {
    int axis = 0;
    e.gamma.cwiseAbs().maxCoeff(&axis);
    CHECK(e.h == Approx(1.0 / (2.0 * body.J(axis, axis))).epsilon(1e-14));
    CHECK((e.stability == EquilibriumStability::stable) == (axis != 1));
  }
}

TEST_CASE("stability classes agree with direct simulation", "[equilibria]") {
  const auto scene = testing::shipped_scene("general_top_richter");
  const HeavyTopBody body = body_of(scene);
  int stable = 0, unstable = 0;
  for (const auto& e : experiments::equilibria_at(body, 3.0).rows) {
    if (e.stability == EquilibriumStability::stable) {
      const Growth g = perturbed_run(scene, e, 30.0);
      CHECK(*std::max_element(g.deviation.begin(), g.deviation.end()) < 1e-4);
      ++stable;
    } else if (e.stability == EquilibriumStability::singly_unstable) {
      // lambda^2 = z+ = (-g1 + sqrt(g1^2 - 4 g2)) / 2 > 0.
      const double rate = std::sqrt(0.5 * (-e.g1 + std::sqrt(e.g1 * e.g1 - 4.0 * e.g2)));
      const Growth g = perturbed_run(scene, e, 40.0 / rate);
      // The slope of log(deviation) while it grows from 1e-5 to 1e-2.
      std::size_t a = 0, b = 0;
      while (a < g.t.size() && g.deviation[a] < 1e-5) ++a;
      b = a;
      while (b < g.t.size() && g.deviation[b] < 1e-2) ++b;
      REQUIRE(b > a + 10);
      REQUIRE(b < g.t.size());
      const double measured = std::log(g.deviation[b] / g.deviation[a]) / (g.t[b] - g.t[a]);
      INFO("predicted rate " << rate << ", measured " << measured);
      CHECK(measured == Approx(rate).epsilon(0.05));
      ++unstable;
    }
  }
  CHECK(stable >= 1);
  CHECK(unstable >= 1);
}

// A strict minimum of the amended potential is Lyapunov stable, so it is never in an unstable
// class. The Lagrange top's carrousels have a neutral pair λ² = 0 whose g2 comes out at
// round-off of either sign (−2.3e-13 for heavy_top_trindade_1 at l = 5): that must read as 0.
TEST_CASE("an energy-Casimir-stable equilibrium is never classed unstable", "[equilibria]") {
  for (const char* name : {"heavy_top_trindade_1", "gyroscope", "general_top_richter", "kovalevskaya"})
    for (const double l : {0.5, 1.0, 2.0, 5.0, 10.0}) {
      const auto rows = experiments::equilibria_at(body_of(testing::shipped_scene(name)), l).rows;
      for (const auto& e : rows) {
        INFO(name << " l = " << l << " g1 = " << e.g1 << " g2 = " << e.g2);
        if (e.nonlinearly_stable) CHECK(e.stability == EquilibriumStability::stable);
      }
    }
}

TEST_CASE("class changes are located: the upright sleeping top at Maxwell's bound", "[equilibria]") {
  // Lagrange top A = 1, C = 2, m g chi = (0, 0, w): the upright sleeping top (Gamma = +e3) is
  // stable iff (C omega)^2 > 4 A w, so its class changes at omega^2 = 4 A w / C^2 (docs/atlas.md §5).
  for (const double w : {1.0, 0.3}) {
    HeavyTopBody body;
    body.J = lie::Vec3(1.0, 1.0, 2.0).asDiagonal();
    body.weight = lie::Vec3(0.0, 0.0, w);
    const auto set = experiments::equilibrium_branches(body, 400);
    int found = 0;
    for (const auto& e : set.rows) {
      if (!e.class_change || std::abs(e.gamma.z() - 1.0) > 1e-12) continue;
      ++found;
      CHECK(std::abs(e.omega * e.omega - 4.0 * w / 4.0) <= 1e-9 * w);
    }
    CHECK(found == 2);  // omega > 0 and omega < 0
    // The branches are named by their ends: the upright sleeping top runs from fast spin about +e3 to rest upright.
    bool upright = false, hanging = false;
    for (const auto& b : set.branches) {
      upright = upright || b.label == "+e3 - upright";
      hanging = hanging || b.label == "hanging - -e3";
    }
    CHECK(upright);
    CHECK(hanging);
  }
}

TEST_CASE("class changes of the general top lie between samples of different class", "[equilibria]") {
  const auto scene = testing::shipped_scene("general_top_richter");
  const auto set = experiments::equilibrium_branches(body_of(scene), 400);
  int changes = 0;
  for (std::size_t k = 1; k + 1 < set.rows.size(); ++k) {
    const auto& e = set.rows[k];
    if (!e.class_change) continue;
    ++changes;
    std::size_t j = k - 1;  // the sample before it on the same branch (not a fold row)
    while (j > 0 && (set.rows[j].fold || set.rows[j].class_change)) --j;
    const auto& before = set.rows[j];
    REQUIRE(before.branch == e.branch);
    CHECK(before.stability != e.stability);
    // On a boundary of Grammel's classes: g2 = 0, g1^2 = 4 g2 or g1 = 0 (to the bisection's precision).
    const double scale = e.g1 * e.g1 + std::abs(e.g2);
    const double boundary = std::min({std::abs(e.g2), std::abs(e.g1 * e.g1 - 4.0 * e.g2), e.g1 * e.g1});
    CHECK(boundary <= 1e-6 * scale);
  }
  CHECK(changes >= 2);
}

}  // namespace test_relative_equilibria
