// Poincaré sections and chaos indicators (experiments/analysis/poincare_section.hpp,
// integrators/core/tangent_flow.hpp; experiments/POINCARE.md):
//  - the section coordinates (φ, ϑ, sheet) reproduce Γ and the sign of φ̇;
//  - the tangent flow agrees with central differences of two nearby
//    trajectories (the only place two trajectories are used: as a check);
//  - MEGNO → 2 and λ → 0 on the integrable tops (Euler, Lagrange,
//    Kovalevskaya), a few orbits here and 10³ per top under [slow];
//  - a chaotic orbit of the general top: ⟨Y⟩ well above 2 and growing, λ > 0;
//  - started on an unstable permanent rotation, the exponent is Grammel's rate sqrt(z+);
//  - the default section axis and the lowest energy at a given ℓ.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "experiments/analysis/poincare_section.hpp"
#include "experiments/analysis/section_seeds.hpp"
#include "experiments/analysis/sweep_plan.hpp"
#include "experiments/io/scene_reader.hpp"
#include "experiments/io/sweep_spec.hpp"
#include "integrators/system/model.hpp"
#include "integrators/core/tangent_flow.hpp"
#include "lie/so3.hpp"
#include "support/shipped_scene.hpp"

namespace test_poincare {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
using experiments::SectionKind;
using lgi::testing::shipped_scene;
using lie::Mat3;
using lie::Vec3;

namespace {

/// A Lagrange top in scaled units: A1 = A2 = 1, A3 = 0.5, χ = (0, 0, 1), m = g = 1.
system::Scene lagrange_top() {
  return experiments::parse_scene(
      "name = \"Lagrange top\"\n[body]\nmass = 1.0\ninertia = [1.0, 1.0, 0.5]\ncenter_of_mass = [0.0, 0.0, 1.0]\n"
      "[gravity]\ng = 1.0\n[initial]\nangular_velocity = [0.1, 0.2, 3.0]\n[run]\nt_end = 10.0\ndt = 0.01\n",
      "lagrange_top.toml");
}

/// Initial states i = 0 .. n−1 drawn on the level set (l, h) by the sweep engine's draw
/// (the Liouville measure unless `measure` says "uniform").
struct LevelStates {
  experiments::SweepSpec spec;
  std::unique_ptr<experiments::SweepPlan> plan;
  LevelStates(const system::Scene& scene, double l, double h, int n, const std::string& measure = "liouville")
      : spec(experiments::parse_sweep_spec("scene = \"x.toml\"\nscheme = \"rkmk4\"\nseed = 7\nsamples = " +
                                               std::to_string(n) + "\n[level_set]\nl = " + std::to_string(l) +
                                               "\nh = " + std::to_string(h) + "\nmeasure = \"" + measure + "\"\n",
                                           "test.toml")),
        plan(std::make_unique<experiments::SweepPlan>(spec, scene)) {}
  system::State state(std::int64_t i, const system::Scene& scene) const {
    std::vector<double> flat;
    plan->inputs(i, flat);
    return plan->initial_state(i, scene, flat);
  }
};

experiments::HeavyTopBody body_of(const system::Scene& s) {
  experiments::HeavyTopBody b;
  b.J = s.inertia;
  if (const auto& g = s.declared<system::GravityTerm>()) b.weight = s.mass.value_or(0.0) * g->g * s.center_of_mass.value_or(Vec3::Zero());
  return b;
}

/// The indicators of orbits 0 .. n−1 of the level set, regular orbits: with few
/// orbits each within 0.2 of 2; with many (`many`), orbits close to a stable
/// periodic orbit approach 2 slowly from below and orbits close to a separatrix
/// slowly from above (docs/atlas.md §7), so: none chaotic (0 < ⟨Y⟩ < 3, where the
/// chaotic orbits of the general top are at λt/2 ≈ 60), the median within 0.1
/// of 2 and at least 90 % within 0.2; λ < 20/t for every orbit (λ ~ ln t / t).
void check_regular(const system::Scene& scene, double l, double h, int n, double t_end, bool many = false) {
  const LevelStates draws(scene, l, h, n);
  std::vector<double> megno;
  for (int i = 0; i < n; ++i) {
    const auto r = experiments::orbit_indicators(scene, draws.state(i, scene), t_end, 0.01, 3, i);
    INFO(scene.name << " orbit " << i << ": megno " << r.megno << ", lyapunov " << r.lyapunov);
    if (many) CHECK((r.megno > 0.0 && r.megno < 3.0));  // not chaotic
    else CHECK(std::abs(r.megno - 2.0) < 0.2);
    CHECK(std::abs(r.lyapunov) < 20.0 / t_end);  // λ(t) ~ ln(t)/t on a torus
    megno.push_back(r.megno);
  }
  if (!many) return;
  const auto within = std::count_if(megno.begin(), megno.end(), [](double m) { return std::abs(m - 2.0) < 0.2; });
  std::nth_element(megno.begin(), megno.begin() + n / 2, megno.end());
  INFO(scene.name << ": median " << megno[static_cast<std::size_t>(n / 2)] << ", within 0.2 of 2: " << within);
  CHECK(std::abs(megno[static_cast<std::size_t>(n / 2)] - 2.0) < 0.1);
  CHECK(static_cast<double>(within) >= 0.9 * n);
}

}  // namespace

TEST_CASE("section coordinates reproduce Gamma and the sign of dphi/dt", "[poincare]") {
  const Vec3 e = Vec3(0.8, 0.4, 0.3).normalized();
  Vec3 f1, f2;
  experiments::section_frame(e, f1, f2);
  CHECK(std::abs(f1.dot(e)) < 1e-15);
  CHECK(std::abs(f1.norm() - 1.0) < 1e-15);
  const Mat3 J_inv = Vec3(1.0, 1.0 / 1.5, 0.5).asDiagonal();
  for (int k = 0; k < 50; ++k) {
    const Vec3 g = Vec3(std::sin(k), std::cos(2.0 * k), std::sin(3.0 * k + 1.0)).normalized();
    const Vec3 Pi(std::cos(k + 0.3), std::sin(5.0 * k), 0.7);
    const auto p = experiments::section_point(SectionKind::richter, e, g, Pi, J_inv);
    const Vec3 back = std::cos(p.theta) * e + std::sin(p.theta) * (std::cos(p.phi) * f1 + std::sin(p.phi) * f2);
    CHECK((back - g).norm() < 1e-14);
    CHECK(p.phi >= 0.0);
    CHECK(p.phi < 2.0 * std::numbers::pi);
    // φ̇ by differences along Γ̇ = Γ × Ω.
    const Vec3 g_dot = g.cross(J_inv * Pi);
    const double dt = 1e-7;
    const Vec3 g1 = (g + dt * g_dot).normalized();
    const auto p1 = experiments::section_point(SectionKind::richter, e, g1, Pi, J_inv);
    double dphi = p1.phi - p.phi;
    if (dphi > std::numbers::pi) dphi -= 2.0 * std::numbers::pi;
    if (dphi < -std::numbers::pi) dphi += 2.0 * std::numbers::pi;
    CHECK(p.sheet == (dphi < 0.0 ? -1 : 1));
  }
}

TEST_CASE("default section axis and lowest energy", "[poincare]") {
  CHECK(experiments::default_section_axis(lagrange_top()) == Vec3::UnitZ());
  CHECK(experiments::default_section_axis(shipped_scene("kovalevskaya")) == Vec3::UnitX());
  CHECK(experiments::default_section_axis(shipped_scene("free_body_hlw")) == Vec3::UnitZ());
  const Vec3 e = experiments::default_section_axis(shipped_scene("general_top_richter"));
  CHECK((e - Vec3(0.8, 0.4, 0.3).normalized()).norm() < 1e-15);
  // At l = 0 the lowest energy is the hanging top, −m g |χ|.
  CHECK(experiments::minimum_energy(body_of(shipped_scene("general_top_richter")), 0.0) ==
        Approx(-Vec3(0.8, 0.4, 0.3).norm()).epsilon(1e-14));
  // The free body: l²/(2 A_max).
  CHECK(experiments::minimum_energy(body_of(shipped_scene("free_body_hlw")), 1.5) == Approx(1.5 * 1.5 / 4.0).epsilon(1e-14));
}

TEST_CASE("the tangent flow agrees with differences of nearby trajectories", "[poincare]") {
  const system::Scene scene = shipped_scene("general_top_richter");
  const system::AnyModel any = system::make_model(scene);
  const auto& model = std::get<system::SceneModel>(any);
  // The uniform draw's first state: one whose tangent vector grows over these 500 steps.
  const LevelStates draws(scene, 1.0, 1.5, 1, "uniform");
  const system::State x0 = draws.state(0, scene);
  integrators::Vec6 v0;
  v0 << 0.3, -0.2, 0.5, 0.1, 0.4, -0.3;
  const double h = 0.01, eps = 1e-6;
  auto run = [&](const integrators::Vec6& dv, integrators::Vec6& v) {
    system::State x{x0.R * lie::exp_so3(dv.head<3>()), x0.Pi + dv.tail<3>()};
    for (int n = 0; n < 500; ++n) integrators::tangent_step(model, x, v, n * h, h);
    return x;
  };
  integrators::Vec6 v = v0, scratch = v0;
  const system::State x = run(integrators::Vec6::Zero(), v);
  const system::State xp = run(eps * v0, scratch), xm = run(-eps * v0, scratch);
  integrators::Vec6 fd;
  fd.head<3>() = (lie::log_so3(x.R.transpose() * xp.R) - lie::log_so3(x.R.transpose() * xm.R)) / (2.0 * eps);
  fd.tail<3>() = (xp.Pi - xm.Pi) / (2.0 * eps);
  INFO("tangent " << v.transpose() << "\nfinite differences " << fd.transpose());
  CHECK((fd - v).norm() < 1e-6 * v.norm());
  CHECK(v.norm() > 2.0 * v0.norm());  // the check is not trivial: the vector has changed
}

TEST_CASE("integrable tops are regular: MEGNO -> 2, Lyapunov -> 0", "[poincare]") {
  check_regular(shipped_scene("free_body_hlw"), 1.0, 0.4, 3, 2000.0);
  check_regular(lagrange_top(), 1.0, 2.5, 3, 2000.0);
  check_regular(shipped_scene("kovalevskaya"), 1.0, 2.0, 3, 2000.0);
}

TEST_CASE("integrable tops are regular over 1000 orbits each", "[poincare][slow]") {
  check_regular(shipped_scene("free_body_hlw"), 1.0, 0.4, 1000, 1000.0, true);
  check_regular(lagrange_top(), 1.0, 2.5, 1000, 1000.0, true);
  check_regular(shipped_scene("kovalevskaya"), 1.0, 2.0, 1000, 1000.0, true);
}

TEST_CASE("a chaotic orbit of the general top: MEGNO grows well above 2, Lyapunov > 0", "[poincare]") {
  // general_top_richter at (l, h) = (1, 1): every orbit sampled by `lgi poincare --megno` there is chaotic
  // (experiments/POINCARE.md).
  const system::Scene scene = shipped_scene("general_top_richter");
  const LevelStates draws(scene, 1.0, 1.0, 2);
  for (int i = 0; i < 2; ++i) {
    const system::State x0 = draws.state(i, scene);
    const auto early = experiments::orbit_indicators(scene, x0, 150.0, 0.01, 3, i);
    const auto late = experiments::orbit_indicators(scene, x0, 400.0, 0.01, 3, i);
    INFO("orbit " << i << ": megno " << early.megno << " -> " << late.megno << ", lyapunov " << late.lyapunov);
    CHECK(late.megno > 8.0);
    CHECK(late.megno > 1.5 * early.megno);
    CHECK(late.lyapunov > 0.05);
    // ⟨Y⟩ ≈ λ t / 2 for a chaotic orbit (Cincotta & Simó 2000), within a factor 2.
    CHECK(late.megno == Approx(0.5 * late.lyapunov * 400.0).epsilon(0.5));
  }
}

TEST_CASE("on an unstable permanent rotation the Lyapunov exponent is Grammel's rate", "[poincare]") {
  // A relative equilibrium of general_top_richter at l = 3 (experiments/EQUILIBRIA.md): singly unstable ones
  // have the real pair ±sqrt(z+), z+ the positive root of z² + g1 z + g2 = 0 (docs/atlas.md §3). Started on
  // the equilibrium, the tangent vector grows at that rate until round-off has pushed the state off it.
  const system::Scene scene = shipped_scene("general_top_richter");
  int checked = 0;
  for (const auto& e : experiments::equilibria_at(body_of(scene), 3.0).rows) {
    if (e.stability != experiments::EquilibriumStability::singly_unstable) continue;
    const double rate = std::sqrt(0.5 * (-e.g1 + std::sqrt(e.g1 * e.g1 - 4.0 * e.g2)));
    const Vec3 a = e.gamma.unitOrthogonal(), b = e.gamma.cross(a);
    Mat3 R;
    R.row(0) = a, R.row(1) = b, R.row(2) = e.gamma;  // Γ = Rᵀe3
    const system::State x0{R, e.angular_momentum};
    const auto r20 = experiments::orbit_indicators(scene, x0, 20.0, 0.005, 1, checked);
    const auto r40 = experiments::orbit_indicators(scene, x0, 40.0, 0.005, 1, checked);
    // The growth between t = 20 and 40 (the same tangent vector): free of the initial vector's projection.
    const double measured = (40.0 * r40.lyapunov - 20.0 * r20.lyapunov) / 20.0;
    INFO("predicted " << rate << ", measured " << measured << " (lambda(40) = " << r40.lyapunov << ")");
    CHECK(measured == Approx(rate).epsilon(1e-3));  // measured: 1e-5 and 2e-4
    ++checked;
  }
  CHECK(checked >= 2);
}

TEST_CASE("--seeds: a section point (phi, theta, sheet) becomes the state on the section at (l, h)", "[poincare]") {
  experiments::HeavyTopBody body;  // general_top_richter: A = (1, 1.5, 2), m g chi = (0.8, 0.4, 0.3)
  body.J = Vec3(1.0, 1.5, 2.0).asDiagonal();
  body.weight = Vec3(0.8, 0.4, 0.3);
  const Vec3 e = body.weight.normalized();
  const double l = 1.0, h = 2.0;
  Vec3 f1, f2;
  experiments::section_frame(e, f1, f2);
  int made = 0;
  for (int k = 0; k < 40; ++k) {
    const double phi = 0.157 * k, theta = 0.3 + 0.06 * k;
    const Vec3 g = std::sin(theta) * (std::cos(phi) * f1 + std::sin(phi) * f2) + std::cos(theta) * e;
    for (const int sheet : {1, -1}) {
      Vec3 Pi;
      if (!experiments::section_state(body, e, l, h, g, sheet, Pi)) {
        // No state there: the point is outside the accessible region U_l <= h.
        CHECK(l * l / (2.0 * g.dot(body.J * g)) + body.weight.dot(g) > h - 1e-12);
        continue;
      }
      ++made;
      const Mat3 J_inv = body.J.inverse();
      const Vec3 Omega = J_inv * Pi;
      CHECK(std::abs(Pi.dot(g) - l) <= 1e-13);
      CHECK(std::abs(0.5 * Pi.dot(Omega) + body.weight.dot(g) - h) <= 1e-13);
      CHECK(std::abs(g.cross(Omega).dot(e)) <= 1e-13);  // on Richter's section S = 0
      const auto p = experiments::section_point(SectionKind::richter, e, g, Pi, J_inv);
      CHECK(p.sheet == sheet);
      CHECK(std::abs(p.theta - theta) <= 1e-12);
    }
  }
  CHECK(made >= 20);
}

}  // namespace test_poincare
