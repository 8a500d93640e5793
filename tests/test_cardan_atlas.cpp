// The tops atlas on T³ (docs/cardan.md §9): relative equilibria of the
// Cardan top against Staude's on SO(3), the section's crossings, the level
// draws, the tangent flow, and the chaos indicators of seed 003's examples.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>

#include "experiments/analysis/cardan_equilibria.hpp"
#include "experiments/analysis/cardan_section.hpp"
#include "experiments/analysis/relative_equilibria.hpp"
#include "experiments/io/scene_reader.hpp"
#include "experiments/io/scene_suspension.hpp"
#include "integrators/registry/torus_registry.hpp"
#include "integrators/core/torus_tangent_flow.hpp"
#include "support/cardan_problems.hpp"

namespace test_cardan_atlas {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
using experiments::CardanEquilibrium;

namespace {

/// Richter's general top (general_top_richter.toml) in a gimbal: massless
/// rings (then T³ is a double cover of SO(3) off the poles) or thin rings.
system::CardanTop general_top(bool rings, double tilt = 0.0) {
  system::CardanTop top;
  top.J = lie::Vec3(1.0, 1.5, 2.0).asDiagonal();
  top.mass = 1.0, top.g = 1.0, top.chi = lie::Vec3(0.8, 0.4, 0.3);
  top.suspension.tilt = tilt;
  if (rings) top.suspension.outer_inertia = 0.3, top.suspension.inner_inertia = lie::Vec3(0.15, 0.3, 0.15);
  return top;
}

std::string scene_path(const std::string& name) { return std::string(LGI_SCENES_DIR) + "/" + name + ".toml"; }

}  // namespace

TEST_CASE("Cardan equilibria with massless rings are Staude's permanent rotations, each twice", "[cardan][atlas]") {
  const system::CardanTop top = general_top(false);
  experiments::HeavyTopBody body;
  body.J = top.J, body.weight = top.mass * top.g * top.chi;
  for (const double l : {0.5, 1.0, 2.5}) {
    const auto so3 = experiments::equilibria_at(body, l).rows;
    const auto t3 = experiments::cardan_equilibria_at(top, l);
    REQUIRE(!so3.empty());
    std::size_t off_pole = 0;
    for (const auto& s : so3) {
      if (std::abs(s.gamma.z()) > 1.0 - 1e-9) continue;  // a pole of the chart: outside the massless Cardan system
      ++off_pole;
      int matches = 0;
      for (const CardanEquilibrium& c : t3)
        if ((c.gamma - s.gamma).norm() < 1e-9) {
          ++matches;
          CHECK(c.h == Approx(s.h).epsilon(1e-11));
          CHECK(c.l == Approx(l).epsilon(1e-12));
          CHECK(c.g1 == Approx(s.g1).epsilon(1e-6).margin(1e-8));
          CHECK(c.g2 == Approx(s.g2).epsilon(1e-6).margin(1e-8));
          CHECK(c.stability == s.stability);
          CHECK(c.nonlinearly_stable == s.nonlinearly_stable);
          CHECK(c.residual < 1e-10);
        }
      CHECK(matches == 2);  // (q2, q3) and (−q2, q3 + π): the ZXZ chart's two preimages
    }
    CHECK(t3.size() == 2 * off_pole);
  }
}

TEST_CASE("A Cardan relative equilibrium with massive rings turns rigidly about the vertical", "[cardan][atlas]") {
  const system::CardanTop top = general_top(true);
  const auto rows = experiments::cardan_equilibria_at(top, 1.0);
  REQUIRE(rows.size() >= 4);
  const auto& dp54 = *integrators::find_cardan_scheme("cardan-dp54");
  int checked = 0;
  for (const CardanEquilibrium& e : rows) {
    system::TorusState x{e.q, top.mass_matrix(e.q) * lie::Vec3(e.omega, 0.0, 0.0)};
    CHECK(x.p(0) == Approx(1.0).epsilon(1e-12));
    CHECK(top.energy(x) == Approx(e.h).epsilon(1e-12));
    lgi::testing::run_torus(dp54, top, x, 2.0, 0.0, 1e-12);
    // The shape stays put and the outer ring turns at ω (to the solver's tolerance).
    CHECK(std::abs(x.q(1) - e.q(1)) < 1e-7);
    CHECK(std::abs(x.q(2) - e.q(2)) < 1e-7);
    CHECK(x.q(0) == Approx(2.0 * e.omega).epsilon(1e-7));
    ++checked;
  }
  CHECK(checked == static_cast<int>(rows.size()));
}

TEST_CASE("The Lagrange top's poles in the gimbal are degenerate circles", "[cardan][atlas]") {
  const system::Scene scene = experiments::read_scene(scene_path("cardan_lagrange_upright"));
  const auto rows = experiments::cardan_equilibria_at(experiments::cardan_top(scene), 1.0);
  REQUIRE(rows.size() == 2);
  for (const CardanEquilibrium& e : rows) {
    CHECK(e.pole);
    CHECK(e.degenerate);
    CHECK(e.q(2) == 0.0);
  }
  // Hanging (q2 = π) is the lower one and stable; upright (q2 = 0) at this slow spin is not.
  const auto& hanging = rows[0].q(1) > 1.0 ? rows[0] : rows[1];
  const auto& upright = rows[0].q(1) > 1.0 ? rows[1] : rows[0];
  CHECK(hanging.h < upright.h);
  CHECK(hanging.stability == experiments::EquilibriumStability::stable);
  CHECK(upright.stability != experiments::EquilibriumStability::stable);
}

TEST_CASE("The Cardan bifurcation diagram: branches in omega, symmetric under omega -> -omega", "[cardan][atlas]") {
  const system::CardanTop top = general_top(true);
  const auto rows = experiments::cardan_equilibrium_branches(top, 40, 2.0, 48);
  REQUIRE(rows.size() > 40);
  std::map<int, int> per_branch;
  double h_plus = 0.0, h_minus = 0.0;
  for (const CardanEquilibrium& e : rows) {
    ++per_branch[e.branch];
    CHECK(e.residual < 1e-9);
    CHECK(e.l == Approx(e.omega * top.mass_matrix(e.q)(0, 0)).epsilon(1e-12));
    (e.omega > 0.0 ? h_plus : h_minus) += e.h;
  }
  CHECK(h_plus == Approx(h_minus).epsilon(1e-9));  // H is even in ω at fixed shape
  CHECK(std::any_of(per_branch.begin(), per_branch.end(), [](const auto& b) { return b.second >= 10; }));
}

TEST_CASE("Cardan level draws lie on {H = h, p1 = l}, and crossings on the section", "[cardan][atlas]") {
  const system::CardanTop top = general_top(true);
  const double l = 1.0, h = 0.5;
  experiments::CardanOrbitRequest r;
  r.t_end = 40.0, r.dt = 0.01;
  for (std::int64_t i = 0; i < 4; ++i) {
    system::TorusState x;
    REQUIRE(experiments::draw_cardan_level_point(top, l, h, 7, i, x));
    CHECK(x.q(0) == 0.0);
    CHECK(x.p(0) == l);
    CHECK(top.energy(x) == Approx(h).epsilon(1e-12));
    const auto o = experiments::cardan_orbit(top, x, r, i);
    CHECK(o.status == 0);
    REQUIRE(o.crossings.size() > 5);
    std::map<int, int> pieces;
    for (const auto& c : o.crossings) {
      ++pieces[c.piece];
      const lie::Vec3 v = top.velocity(c.x);
      if (c.piece == 1 || c.piece == -1) {
        CHECK(std::abs(v(1)) < 1e-9 * (1.0 + v.norm()));
        CHECK((v(2) >= 0.0) == (c.piece == 1));
      } else {
        CHECK(std::abs(std::sin(c.x.q(1))) < 1e-12);
        CHECK(c.y_coord == Approx(std::atan2(v(2), v(1))));
      }
      CHECK(top.energy(c.x) == Approx(h).epsilon(1e-6));
    }
    // Deterministic: the same orbit again, bit for bit.
    const auto again = experiments::cardan_orbit(top, x, r, i);
    REQUIRE(again.crossings.size() == o.crossings.size());
    CHECK(again.crossings.back().t == o.crossings.back().t);
    CHECK((again.final.q.array() == o.final.q.array()).all());
  }
}

TEST_CASE("The T^3 tangent flow matches two neighbouring trajectories", "[cardan][atlas]") {
  const system::CardanTop top = lgi::testing::cardan_test_top(0.4);
  const system::TorusState x0 = lgi::testing::cardan_test_initial(top);
  system::Vec6 v0;
  v0 << 0.3, -0.2, 0.5, 0.1, 0.4, -0.6;
  system::Vec6 x = system::stack(x0), v = v0;
  const double h = 1e-3, eps = 1e-6;
  system::Vec6 xp = x + eps * v0, xm = x - eps * v0, dummy = system::Vec6::Zero();
  for (int k = 0; k < 1000; ++k) {
    integrators::torus::torus_tangent_step(top, x, v, h);
    integrators::torus::torus_tangent_step(top, xp, dummy, h);
    integrators::torus::torus_tangent_step(top, xm, dummy, h);
  }
  const system::Vec6 fd = (xp - xm) / (2.0 * eps);
  CHECK((v - fd).norm() < 1e-6 * fd.norm());
}

namespace {

/// Max and min of MEGNO <Y> over `orbits` orbits at the scene's own (l, h).
std::pair<double, double> megno_range(const std::string& scene_name, int orbits, double t_end, double dt) {
  const system::Scene scene = experiments::read_scene(scene_path(scene_name));
  const system::CardanTop top = experiments::cardan_top(scene);
  const double l = scene.cardan_initial.p(0), h = top.energy(scene.cardan_initial);
  experiments::CardanOrbitRequest r;
  r.t_end = t_end, r.dt = dt, r.indicators = true, r.seed = 3;
  double lo = 1e300, hi = -1e300;
  for (int i = 0; i < orbits; ++i) {
    system::TorusState x;
    REQUIRE(experiments::draw_cardan_level_point(top, l, h, r.seed, i, x));
    const auto o = experiments::cardan_orbit(top, x, r, i);
    REQUIRE(o.status == 0);
    lo = std::min(lo, o.megno), hi = std::max(hi, o.megno);
  }
  return {lo, hi};
}

}  // namespace

// Seed 003, "Rigid bodies in T³": Lagrange up integrable, horizontal chaotic;
// Euler symmetric up integrable, tilted chaotic; general asymmetric up chaotic.
TEST_CASE("MEGNO separates seed 003's integrable and chaotic Cardan tops", "[cardan][atlas]") {
  const auto lagrange_up = megno_range("cardan_lagrange_upright", 2, 60.0, 1e-3);
  const auto lagrange_horizontal = megno_range("cardan_lagrange_horizontal", 2, 60.0, 1e-3);
  const auto euler_up = megno_range("cardan_euler_symmetric_up", 2, 150.0, 5e-3);
  const auto euler_tilted = megno_range("cardan_euler_tilted", 2, 150.0, 5e-3);
  const auto general_up = megno_range("cardan_general_asymmetric_up", 2, 150.0, 5e-3);
  CHECK(lagrange_up.second < 2.6);
  CHECK(euler_up.second < 2.6);
  CHECK(lagrange_horizontal.second > 10.0);
  CHECK(euler_tilted.first > 10.0);
  CHECK(general_up.first > 10.0);
}

TEST_CASE("MEGNO of seed 003's Cardan tops over 16 orbits to t = 600", "[cardan][atlas][slow]") {
  const auto lagrange_up = megno_range("cardan_lagrange_upright", 16, 300.0, 1e-3);
  const auto euler_up = megno_range("cardan_euler_symmetric_up", 16, 600.0, 5e-3);
  const auto euler_tilted = megno_range("cardan_euler_tilted", 16, 600.0, 5e-3);
  const auto general_up = megno_range("cardan_general_asymmetric_up", 16, 600.0, 5e-3);
  CHECK(lagrange_up.second < 2.6);
  CHECK(euler_up.second < 2.6);
  CHECK(euler_tilted.second > 50.0);
  CHECK(general_up.second > 50.0);
}

}  // namespace test_cardan_atlas
