// Action variables of the integrable tops (experiments/analysis/actions.hpp,
// docs/actions.md):
//  - Lagrange: the closed form (elliptic integrals) against an independent
//    quadrature, and against the integrated orbit: ∮ p_θ dθ over one measured
//    nutation period to 1e-10, ω = ∂H/∂I against the measured nutation
//    period, precession and spin per period to 1e-8; ∂H/∂I also against
//    finite differences of the closed-form actions;
//  - Euler: the Deprit action against the loop integral ∮ L dl on the
//    integrated orbit (both regimes), the frequencies against the measured
//    period and precession, continuity across the separatrix;
//  - the numerical torus (section, rotation number, Fourier fit, Birkhoff
//    averages) on the Lagrange top against the closed form (up to the integer
//    change of basis), and on the Kovalevskaya top near a stable relative
//    equilibrium against its linearisation (Grammel's frequencies, and
//    h − h_eq = ω·I to leading order).
#include <catch2/catch.hpp>
#include <iomanip>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <complex>
#include <numbers>
#include <utility>
#include <vector>

#include "experiments/analysis/actions.hpp"
#include "experiments/analysis/actions_support.hpp"
#include "experiments/io/scene_reader.hpp"
#include "support/registered_run.hpp"
#include "support/shipped_scene.hpp"

namespace test_actions {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
using experiments::LagrangeBody;
using lie::Mat3;
using lie::Vec3;

namespace {

constexpr double pi = std::numbers::pi;

system::Scene free_scene(const std::string& inertia, const std::string& omega) {
  return experiments::parse_scene("name = \"f\"\n[body]\ninertia = " + inertia +
                                      "\nallow_unphysical = true\n[initial]\nrotation_vector = [0.4, 0.1, 0.0]\n"
                                      "angular_velocity = " + omega + "\n[run]\nt_end = 10.0\ndt = 0.01\n",
                                  "f.toml");
}

struct Invariants {
  double l, L3, h;
};

Invariants invariants(const system::Scene& s, const system::State& x, double w) {
  const Vec3 gamma = x.R.row(2).transpose();
  return {x.Pi.dot(gamma), x.Pi.z(), 0.5 * x.Pi.dot(s.inertia.inverse() * x.Pi) + w * gamma.z()};
}

double relative(double a, double b) { return std::abs(a - b) / std::max(std::abs(b), 1e-300); }

}  // namespace

TEST_CASE("Lagrange closed form agrees with quadrature and its derivatives with finite differences", "[actions]") {
  for (const LagrangeBody& body : {LagrangeBody{1.0, 0.5, 1.0}, LagrangeBody{0.6, 1.0, 1.0}, LagrangeBody{1.0, 0.5, -1.0}}) {
    for (const Vec3& t : {Vec3(1.2, 1.5, 2.0), Vec3(0.3, -0.8, 1.5), Vec3(-1.0, 2.0, 3.5), Vec3(0.0, 0.2, 0.9)}) {
      const double l = t[0], L3 = t[1], h = t[2];
      const auto a = experiments::lagrange_actions(body, l, L3, h);
      if (!a) continue;
      INFO("A=" << body.A << " C=" << body.C << " w=" << body.w << " l=" << l << " L3=" << L3 << " h=" << h);
      const double q = experiments::lagrange_nutation_action_quadrature(body, l, L3, h, 400);
      CHECK(relative(a->actions[2], q) < 1e-12);
      CHECK(a->u1 < a->u2);
      // ω = ∂H/∂I: ω_θ = 1/∂_h I_θ, ω_ψ = −∂_ℓ I_θ/∂_h I_θ, ω_φ = −∂_L3 I_θ/∂_h I_θ (central differences).
      const double e = 1e-5;
      auto I = [&](double dl, double dL3, double dh) {
        return experiments::lagrange_actions(body, l + dl, L3 + dL3, h + dh)->actions[2];
      };
      const double Ih = (I(0, 0, e) - I(0, 0, -e)) / (2 * e), Il = (I(e, 0, 0) - I(-e, 0, 0)) / (2 * e),
                   IL3 = (I(0, e, 0) - I(0, -e, 0)) / (2 * e);
      CHECK(relative(a->frequencies[2], 1.0 / Ih) < 1e-7);
      CHECK(std::abs(a->frequencies[0] + Il / Ih) < 1e-7 * (1 + std::abs(a->frequencies[0])));
      CHECK(std::abs(a->frequencies[1] + IL3 / Ih) < 1e-7 * (1 + std::abs(a->frequencies[1])));
    }
  }
}

TEST_CASE("Lagrange actions and frequencies agree with the integrated orbit", "[actions]") {
  for (const char* name : {"lagrange_top_cigar", "lagrange_top_disk"}) {
    const system::Scene scene = testing::shipped_scene(name);
    const auto body = experiments::lagrange_body({scene.inertia, Vec3(0, 0, 1)});
    REQUIRE(body);
    const system::State x0 = scene.initial;
    const Invariants v = invariants(scene, x0, body->w);
    const auto a = experiments::lagrange_actions(*body, v.l, v.L3, v.h);
    REQUIRE(a);
    const auto m = experiments::measure_lagrange(scene, x0, "rkmk4", 2e-3, 3000, 3);
    REQUIRE(m.ok);
    INFO(name << " I_theta=" << a->actions[2] << " measured " << m.action_theta << " period " << a->period << " vs "
              << m.period);
    CHECK(relative(m.action_theta, a->actions[2]) < 1e-10);
    CHECK(relative(m.period, a->period) < 1e-8);
    for (int i = 0; i < 3; ++i) CHECK(std::abs(m.frequencies[i] - a->frequencies[i]) < 1e-8 * a->frequencies.norm());
  }
}

TEST_CASE("Euler actions agree with the loop integral on the integrated orbit", "[actions]") {
  const Vec3 moments(1.0, 2.0, 3.0);
  // About the largest axis, about the smallest, and near the separatrix on both sides.
  for (const char* omega : {"[0.3, 0.2, 1.0]", "[2.0, 0.3, 0.2]", "[0.5, 0.9, 0.31]", "[0.5, 0.9, 0.29]"}) {
    const system::Scene scene = free_scene("[1.0, 2.0, 3.0]", omega);
    const system::State x0 = scene.initial;
    const double l = x0.Pi.dot(x0.R.row(2).transpose());
    const auto a = experiments::euler_actions(moments, x0.Pi, l);
    REQUIRE(a);
    INFO(omega << " around axis " << a->around << " I=" << a->actions.transpose());
    const auto m = experiments::measure_euler(scene, x0, "rkmk4", a->period, 4000, a->pole);
    REQUIRE(m.ok);
    CHECK(relative(m.action_l, a->actions[2]) < 1e-9);
    CHECK(std::abs(m.omega_g - a->frequencies[1]) < 1e-8 * std::abs(a->frequencies[1]));
    // The period of Π: rising zeros of the component that changes sign.
    const int c = (a->around + 1) % 3;
    const double T = experiments::crossing_period(scene, x0, "rkmk4", 1e-3, [c](const system::State& s) {
      return s.Pi[c];
    }, 2, 1e4);
    CHECK(relative(T, a->period) < 1e-8);
    CHECK(std::abs(a->frequencies[2] + 2 * pi / a->period) < 1e-15 * 2 * pi / a->period);
  }
  // Continuity across the separatrix G² = 2h J2.
  const double G = 1.0, h_sep = G * G / (2.0 * moments[1]);
  const auto below = experiments::euler_actions_at(moments, 0.3, G, h_sep * (1 - 1e-9));
  const auto above = experiments::euler_actions_at(moments, 0.3, G, h_sep * (1 + 1e-9));
  REQUIRE(below);
  REQUIRE(above);
  CHECK(below->around != above->around);
  CHECK(std::abs(below->actions[2] - above->actions[2]) < 1e-6);
}

TEST_CASE("The numerical torus of a Lagrange top is the closed form up to a change of basis", "[actions]") {
  const system::Scene scene = testing::shipped_scene("lagrange_top_cigar");
  const auto body = experiments::lagrange_body({scene.inertia, Vec3(0, 0, 1)});
  const Invariants v = invariants(scene, scene.initial, body->w);
  const auto a = experiments::lagrange_actions(*body, v.l, v.L3, v.h);
  REQUIRE(a);
  experiments::NumericalTorusOptions o;
  o.dt = 2e-3;
  o.crossings = 200;
  const auto t = experiments::numerical_torus(scene, scene.initial, o);
  REQUIRE(t.ok);
  INFO("I_a=" << t.action_a << " I_b=" << t.action_b << " rho=" << t.rotation_number << " winding=" << t.winding
              << " fit " << t.fit_residual << " closed (" << a->actions.transpose() << ")");
  // Cycle a is the φ-circle (action |L3|), cycle b the nutation cycle plus n times cycle a.
  CHECK(std::abs(t.winding) == 1);
  CHECK(relative(t.action_a, std::abs(v.L3)) < 1e-9);
  const double n = (t.action_b - a->actions[2]) / std::abs(v.L3);
  CHECK(std::abs(n - std::round(n)) < 1e-8);
  CHECK(relative(t.omega_b, a->frequencies[2]) < 1e-8);
  // ω_a = ±ω_φ mod ω_θ.
  const double r = std::remainder(std::abs(t.omega_a) - std::abs(a->frequencies[1]), a->frequencies[2]);
  const double r2 = std::remainder(std::abs(t.omega_a) + std::abs(a->frequencies[1]), a->frequencies[2]);
  CHECK(std::min(std::abs(r), std::abs(r2)) < 1e-8);
  // Invariance of ω·I (the time average of p q̇) under the change of basis.
  CHECK(relative(t.omega_a * t.action_a + t.omega_b * t.action_b,
                 a->frequencies[1] * a->actions[1] + a->frequencies[2] * a->actions[2]) < 1e-8);
}

namespace {

/// The linearisation of the Euler–Poisson field at a relative equilibrium (docs/atlas.md §3).
Eigen::Matrix<double, 6, 6> linearisation(const experiments::HeavyTopBody& b, const Vec3& Pi, const Vec3& gamma) {
  auto hat = [](const Vec3& v) {
    Mat3 m;
    m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
    return m;
  };
  const Mat3 J_inv = b.J.inverse();
  const Vec3 Omega = J_inv * Pi;
  Eigen::Matrix<double, 6, 6> M;
  M.topLeftCorner<3, 3>() = hat(Pi) * J_inv - hat(Omega);
  M.topRightCorner<3, 3>() = -hat(b.weight);
  M.bottomLeftCorner<3, 3>() = hat(gamma) * J_inv;
  M.bottomRightCorner<3, 3>() = -hat(Omega);
  return M;
}

system::State state_with_gamma(const Vec3& Pi, const Vec3& gamma) {
  const Vec3 g = gamma.normalized();
  const Vec3 f1 = (std::abs(g.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(g).normalized();
  system::State s;
  s.R.row(0) = f1.transpose();
  s.R.row(1) = g.cross(f1).transpose();
  s.R.row(2) = g.transpose();
  s.Pi = Pi;
  return s;
}

}  // namespace

TEST_CASE("The numerical torus of the Kovalevskaya top near a stable relative equilibrium", "[actions]") {
  const system::Scene scene = testing::shipped_scene("kovalevskaya");
  const experiments::HeavyTopBody body{scene.inertia, Vec3(1, 0, 0)};
  // The lowest equilibrium at l = 1.3 (the hanging top turning about e1; its frequencies
  // 1.19 and 0.71 are far from resonance, which l = 2 would hit: 2:1).
  const double l0 = 1.3;
  const auto set = experiments::equilibria_at(body, l0);
  const experiments::RelativeEquilibrium* eq = &set.rows.front();
  REQUIRE(eq->nonlinearly_stable);
  REQUIRE(eq->stability == experiments::EquilibriumStability::stable);
  // The faster mode excited with amplitude ε, the slower with ε/5.
  const Eigen::Matrix<double, 6, 6> M = linearisation(body, eq->angular_momentum, eq->gamma);
  const Eigen::EigenSolver<Eigen::Matrix<double, 6, 6>> es(M);
  std::vector<int> modes;
  for (int i = 0; i < 6; ++i)
    if (es.eigenvalues()[i].imag() > 1e-8) modes.push_back(i);
  REQUIRE(modes.size() == 2);
  // The faster mode dominant: its p_θ carries the section crossings.
  if (es.eigenvalues()[modes[0]].imag() < es.eigenvalues()[modes[1]].imag()) std::swap(modes[0], modes[1]);
  const double eps = 4e-3;
  Eigen::Matrix<double, 6, 1> dx = Eigen::Matrix<double, 6, 1>::Zero();
  for (int j = 0; j < 2; ++j) {
    const Eigen::Matrix<double, 6, 1> v = es.eigenvectors().col(modes[static_cast<std::size_t>(j)]).real();
    dx += (j == 0 ? eps : eps / 5) * v / v.norm();
  }
  const system::State x0 =
      state_with_gamma(eq->angular_momentum + dx.head<3>(), eq->gamma + dx.tail<3>());
  experiments::NumericalTorusOptions o;
  o.dt = 5e-3;
  o.crossings = 200;
  const auto t = experiments::numerical_torus(scene, x0, o);
  INFO(t.status << " crossings " << t.crossings << " rho " << t.rotation_number << " fit " << t.fit_residual);
  REQUIRE(t.ok);
  // The equilibrium at the torus' own l.
  const auto near = experiments::equilibria_at(body, t.l);
  const experiments::RelativeEquilibrium* e2 = &near.rows.front();
  for (const auto& e : near.rows)
    if ((e.gamma - eq->gamma).norm() < (e2->gamma - eq->gamma).norm()) e2 = &e;
  const double z1 = 0.5 * (-e2->g1 - std::sqrt(e2->g1 * e2->g1 - 4 * e2->g2)),
               z2 = 0.5 * (-e2->g1 + std::sqrt(e2->g1 * e2->g1 - 4 * e2->g2));
  const double w1 = std::sqrt(-z1), w2 = std::sqrt(-z2);
  INFO("I_a=" << t.action_a << " I_b=" << t.action_b << " omega_a=" << t.omega_a << " omega_b=" << t.omega_b
              << " linear " << w1 << ", " << w2 << " fit " << t.fit_residual << " h-h_eq=" << t.h - e2->h);
  // ω_b is the frequency of the excited mode, ω_a the other one modulo ω_b.
  const double wb = std::abs(t.omega_b - w1) < std::abs(t.omega_b - w2) ? w1 : w2, wa = wb == w1 ? w2 : w1;
  CHECK(relative(t.omega_b, wb) < 1e-3);
  const double r = std::min(std::abs(std::remainder(t.omega_a - wa, wb)), std::abs(std::remainder(t.omega_a + wa, wb)));
  CHECK(r < 1e-3 * wb);
  CHECK(relative(t.omega_a * t.action_a + t.omega_b * t.action_b, t.h - e2->h) < 1e-3);
  CHECK(t.action_a < t.action_b);
}

// Far from the equilibria (h = 2, docs/actions.md §3): the tori of `lgi actions --h 2 --l 0.5`.
// The actions of a torus do not depend on where on it the flow starts: from the state at
// t = 7.31 of the same orbit they agree to 1e-10 (I_a) and 1e-7 (I_b).
TEST_CASE("Kovalevskaya tori at h = 2: the actions of a torus do not depend on the starting point", "[actions]") {
  const system::Scene scene = testing::shipped_scene("kovalevskaya");
  const experiments::HeavyTopBody body{scene.inertia, Vec3(1, 0, 0)};
  const auto states = experiments::level_set_states(body, 0.5, 2.0, 6);
  REQUIRE(states.size() == 6);
  experiments::NumericalTorusOptions o;
  int ok = 0;
  for (std::size_t i = 0; i < states.size(); ++i) {
    const auto t = experiments::numerical_torus(scene, states[i], o);
    INFO("torus " << i << ": " << t.status << " fit " << t.fit_residual);
    if (!t.ok) continue;
    ++ok;
    if (ok > 2) continue;  // two tori restarted: enough, and each costs a second run
    const system::AnyModel model = system::make_model(scene);
    const auto later = testing::run_registered(o.scheme, model, states[i], 7.31, o.dt);
    const auto u = experiments::numerical_torus(scene, later.state, o);
    INFO(std::setprecision(12) << "again: " << u.status << " fit " << u.fit_residual << " I " << t.action_a << " "
                               << t.action_b << " vs " << u.action_a << " " << u.action_b << " rho " << t.rotation_number
                               << " " << u.rotation_number);
    REQUIRE(u.ok);
    // Known limit (docs/actions.md §3): where the section cuts two circles the restart may fit the
    // other one, homologous on the torus, and the two integrals differ by 3e-4 relative (torus 0);
    // the cause is not found yet. One circle: the same curve, to round-off.
    const double tol_a = t.status == "ok (1 circle)" ? 1e-10 : 1e-3, tol_b = t.status == "ok (1 circle)" ? 1e-7 : 1e-3;
    CHECK(std::abs(u.action_a - t.action_a) < tol_a * std::max(1.0, t.action_a));
    CHECK(std::abs(u.action_b - t.action_b) < tol_b * std::max(1.0, std::abs(t.action_b)));
    CHECK(std::abs(u.omega_b - t.omega_b) < 1e-7 * t.omega_b);
  }
  // With the transverse section of docs/actions.md §3 at dt = 0.01 and the order-8 default
  // scheme: all 6 (the whole grid's rate is measured in docs/actions.md §3).
  CHECK(ok == 6);
}

}  // namespace test_actions
