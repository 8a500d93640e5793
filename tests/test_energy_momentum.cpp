// simo-wong (integrators/schemes/simo_wong.hpp): the energy–momentum scheme.
//  - the algebra the header relies on: cay(ξ)ᵀ x = x − h x_mid × W with x_mid = (I + ξ̂/2)⁻¹x,
//    and cay(η)² = cay(ξ) for the spring's midpoint;
//  - observed order 2 on free_body_hlw (against the exact flow) and on the
//    Kovalevskaya top (against the rkf78 reference);
//  - symmetry Φ₋ₕ ∘ Φₕ = id on every kind of scene;
//  - exact conservation over 1e5 steps: H, |Π|, m (free body); H, Π·Γ (heavy
//    top); H of an undamped spring (discrete gradient); monotone energy decay
//    of the damped spring;
//  - a step that rotates by π or more fails cleanly through the registry;
//  - Newton iteration counts (printed, and bounded).
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <numbers>
#include <utility>
#include <string>

#include "experiments/io/scene_reader.hpp"
#include "integrators/registry/registry.hpp"
#include "integrators/schemes/simo_wong.hpp"
#include "integrators/system/free_body_exact.hpp"
#include "support/order_reference.hpp"
#include "support/convergence.hpp"
#include "support/reference_solution.hpp"
#include "support/shipped_scene.hpp"
#include "support/spring_scenes.hpp"

namespace test_energy_momentum {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
using lie::Mat3;
using lie::Vec3;
using testing::ConvergencePoint;

namespace {


const integrators::SchemeInfo& simo_wong() {
  const auto* s = integrators::find_scheme("simo-wong");
  REQUIRE(s);
  return *s;
}

integrators::RunStats run(const system::AnyModel& model, system::State& x, double t_end, double h) {
  integrators::RunConfig cfg;
  cfg.t_end = t_end;
  cfg.dt = h;
  cfg.save_every = 1 << 30;
  integrators::NullObserver none;
  return simo_wong().run(model, x, cfg, none);
}

system::State run_ok(const system::AnyModel& model, const system::State& x0, double t_end, double h) {
  system::State x = x0;
  const auto stats = run(model, x, t_end, h);
  INFO(stats.status);
  REQUIRE(stats.ok);
  return x;
}

double pi_dot_gamma(const system::State& s) { return s.Pi.dot(s.R.row(2).transpose()); }

/// One step that must converge; records the Newton count in `work` as the stepper loop does.
template <class Model>
void step_ok(const integrators::SimoWong& scheme, const Model& model, system::State& x, double t, double h,
             integrators::WorkCounters& work) {
  const integrators::StepStatus st = scheme.step(model, x, t, h, work);
  integrators::detail::record_solve(st, work);
  INFO("t = " << t << ": " << st.iterations << " iterations, residual " << st.residual);
  REQUIRE(st.converged);
}

}  // namespace

TEST_CASE("the Cayley identities behind simo-wong's conservation hold to round-off", "[simo-wong][algebra]") {
  const Vec3 W(0.7, -1.3, 0.4), x(0.3, 0.9, -2.0);
  for (double h : {1e-3, 0.1, 1.0}) {
    const Vec3 xi = h * W;
    const Mat3 Q = lie::cay(xi);
    const Mat3 A = 0.5 * lie::hat(xi);
    const Vec3 x1 = Q.transpose() * x;
    const Vec3 x_mid = 0.5 * (x + x1);
    // x_{n+1} = Qᵀ x_n  ⇔  x_{n+1} − x_n = h x_mid × W
    CHECK((x1 - x - h * x_mid.cross(W)).norm() <= 1e-15 * x.norm() * (1.0 + h * W.norm()));
    // x_mid = (I + A)⁻¹ x_n: the midpoint of Γ consistent with Γ_{n+1} = Qᵀ Γ_n
    CHECK((x_mid - (Mat3::Identity() + A).inverse() * x).norm() <= 1e-15 * x.norm());
    // cay(η)² = cay(ξ) for η = ξ/(1 + √(1 + |ξ|²/4)): the spring's midpoint attitude
    const Vec3 eta = xi / (1.0 + std::sqrt(1.0 + 0.25 * xi.squaredNorm()));
    CHECK((lie::cay(eta) * lie::cay(eta) - Q).norm() <= 1e-15);
  }
}

TEST_CASE("simo-wong converges at order 2", "[simo-wong][order]") {
  // Halvings of h0 while h > h_min; at least four points fitted, slope 2 ± 0.2.
  auto check_order2 = [](const char* what, const system::AnyModel& model, const system::State& x0, double T,
                         const system::State& ref, double h0, double h_min) {
    std::vector<ConvergencePoint> pts;
    for (double h = h0; h > h_min; h *= 0.5)
      pts.push_back({h, testing::global_error(run_ok(model, x0, T, h), ref)});
    const auto fit = testing::fitted_slope(pts);
    testing::report_slope("simo-wong", what, fit, pts);
    CHECK(fit.points >= 4);
    CHECK(std::abs(fit.slope - 2.0) <= 0.2);
  };
  SECTION("free_body_hlw against the exact flow") {
    const system::Scene scene = testing::shipped_scene("free_body_hlw");
    const system::AnyModel model = system::make_model(scene);
    const double T = 10.0;
    const system::State exact = testing::exact_free_body_at(model, scene, T);
    check_order2("free_body_hlw", model, scene.initial, T, exact, 0.1, 0.002);
  }
  SECTION("the Kovalevskaya top against rkf78") {
    const system::Scene scene = testing::shipped_scene("kovalevskaya");
    const system::AnyModel model = system::make_model(scene);
    const double T = 5.0;
    const system::State ref =
        testing::reference_solution(std::get<system::SceneModel>(model), scene.initial, 0.0, T, 1e-14);
    check_order2("kovalevskaya", model, scene.initial, T, ref, 0.1, 0.002);
  }
  SECTION("a heavy top with a damped spring and a drive against rkf78 (every discrete torque at once)") {
    const system::Scene scene = experiments::parse_scene(testing::kitchen_sink_toml, "kitchen_sink.toml");
    const system::AnyModel model = system::make_model(scene);
    const double T = 2.0;
    const system::State ref = testing::reference_solution(std::get<system::SceneModel>(model),
                                                          scene.initial, 0.0, T, 1e-14);
    check_order2("gravity + damped spring + drive", model, scene.initial, T, ref, 0.05, 0.001);
  }
}

TEST_CASE("simo-wong is symmetric: a step back undoes a step", "[simo-wong][symmetry]") {
  auto check = [](const system::AnyModel& any, const system::State& x0, double h, const char* what) {
    std::visit(
        [&](const auto& model) {
          integrators::SimoWong scheme;
          integrators::WorkCounters work;
          system::State x = x0;
          const double t = 0.37;
          REQUIRE(scheme.step(model, x, t, h, work).converged);
          REQUIRE(scheme.step(model, x, t + h, -h, work).converged);
          const double att = lie::geodesic_distance(x0.R, x.R);
          const double mom = (x.Pi - x0.Pi).norm() / x0.Pi.norm();
          INFO(what << " h = " << h << ": attitude " << att << ", momentum " << mom);
          CHECK(att <= 1e-13);
          CHECK(mom <= 1e-13);
        },
        any);
  };
  for (double h : {1e-3, 0.05, 0.2}) {
    for (const char* name : {"free_body_hlw", "heavy_top_trindade_1", "kovalevskaya", "general_top_richter",
                             "stiff_damped_spring"}) {
      const system::Scene scene = testing::shipped_scene(name);
      if (name == std::string("heavy_top_trindade_1") && h > 0.05) continue;  // 50 rad/s: h|Ω| ≥ π
      check(system::make_model(scene), scene.initial, h, name);
    }
    const system::Scene spring = experiments::parse_scene(testing::undamped_spring_toml, "spring.toml");
    check(system::make_model(spring), spring.initial, h, "undamped spring");
    const system::Scene all = experiments::parse_scene(testing::kitchen_sink_toml, "kitchen_sink.toml");
    check(system::make_model(all), all.initial, h, "gravity + damped spring + drive");
  }
}

TEST_CASE("simo-wong conserves H, |Pi| and m of the free body exactly over 1e5 steps", "[simo-wong][conservation]") {
  const system::Scene scene = testing::shipped_scene("free_body_hlw");
  const auto model = std::get<system::FreeBody>(system::make_model(scene));
  integrators::SimoWong scheme;
  integrators::WorkCounters work;
  system::State x = scene.initial;
  const double H0 = model.energy(x), G0 = x.Pi.norm();
  const Vec3 m0 = x.R * x.Pi;
  double dH = 0, dG = 0, dm = 0;
  const double h = 0.01;
  for (int k = 0; k < 100000; ++k) {
    step_ok(scheme, model, x, k * h, h, work);
    dH = std::max(dH, std::abs(model.energy(x) - H0) / H0);
    dG = std::max(dG, std::abs(x.Pi.norm() - G0) / G0);
    dm = std::max(dm, (x.R * x.Pi - m0).norm() / m0.norm());
  }
  std::cout << "simo-wong free_body_hlw, 1e5 steps of 0.01: max rel. drift H " << dH << ", |Pi| " << dG << ", m " << dm
            << ", Newton max " << work.newton_iterations_max << '\n';
  CHECK(dH <= 1e-12);
  CHECK(dG <= 1e-12);
  CHECK(dm <= 1e-12);
}

TEST_CASE("simo-wong conserves H and Pi.Gamma of the heavy top exactly over 1e5 steps", "[simo-wong][conservation]") {
  for (const char* name : {"heavy_top_trindade_1", "general_top_richter"}) {
    const system::Scene scene = testing::shipped_scene(name);
    const auto model = std::get<system::SceneModel>(system::make_model(scene));
    integrators::SimoWong scheme;
    integrators::WorkCounters work;
    system::State x = scene.initial;
    const double H0 = model.energy(x), L0 = pi_dot_gamma(x);
    double dH = 0, dL = 0;
    const double h = 1e-3;
    for (int k = 0; k < 100000; ++k) {
      step_ok(scheme, model, x, k * h, h, work);
      dH = std::max(dH, std::abs(model.energy(x) - H0) / std::abs(H0));
      dL = std::max(dL, std::abs(pi_dot_gamma(x) - L0) / std::abs(L0));
    }
    std::cout << "simo-wong " << name << ", 1e5 steps of 1e-3: max rel. drift H " << dH << ", Pi.Gamma " << dL
              << ", Newton max " << work.newton_iterations_max << '\n';
    INFO(name);
    CHECK(dH <= 1e-12);
    CHECK(dL <= 1e-12);
  }
}

TEST_CASE("simo-wong conserves the energy of an undamped spring exactly (discrete gradient)",
          "[simo-wong][conservation][spring]") {
  const system::Scene scene = experiments::parse_scene(testing::undamped_spring_toml, "spring.toml");
  const auto model = std::get<system::SceneModel>(system::make_model(scene));
  integrators::SimoWong scheme;
  integrators::WorkCounters work;
  system::State x = scene.initial;
  const double H0 = model.energy(x);
  double dH = 0, max_angle = 0;
  const double h = 1e-3;
  for (int k = 0; k < 100000; ++k) {
    step_ok(scheme, model, x, k * h, h, work);
    dH = std::max(dH, std::abs(model.energy(x) - H0) / H0);
    max_angle = std::max(max_angle, lie::log_so3(x.R).norm());
  }
  std::cout << "simo-wong undamped spring, 1e5 steps of 1e-3: max rel. energy drift " << dH << " (deflection up to "
            << max_angle << " rad), Newton max " << work.newton_iterations_max << '\n';
  CHECK(dH <= 1e-12);
  CHECK(max_angle > 1.0);  // the potential is far from quadratic in Γ: a real test of the discrete gradient
  // Without the discrete-gradient correction (the midpoint torque alone) the
  // energy would not be conserved: the bracket σ|ξ|² is O(h³) per step, so a
  // coarse step shows it. The same run at h = 0.05 still conserves H.
  x = scene.initial;
  double dH_coarse = 0;
  for (int k = 0; k < 2000; ++k) {
    step_ok(scheme, model, x, k * 0.05, 0.05, work);
    dH_coarse = std::max(dH_coarse, std::abs(model.energy(x) - H0) / H0);
  }
  CHECK(dH_coarse <= 1e-12);
}

TEST_CASE("simo-wong's energy decays monotonically on the stiff damped spring", "[simo-wong][damping]") {
  const system::Scene scene = testing::shipped_scene("stiff_damped_spring");
  const auto model = std::get<system::SceneModel>(system::make_model(scene));
  for (double h : {1e-3, 0.1}) {  // 0.1: 100x the explicit stability limit
    integrators::SimoWong scheme;
    integrators::WorkCounters work;
    system::State x = scene.initial;
    double H = model.energy(x);
    const double H0 = H;
    int increases = 0;
    const int n = static_cast<int>(std::lround(5.0 / h));
    for (int k = 0; k < n; ++k) {
      step_ok(scheme, model, x, k * h, h, work);
      const double H1 = model.energy(x);
      if (H1 > H + 4.0 * std::numeric_limits<double>::epsilon() * H) ++increases;
      H = H1;
    }
    INFO("h = " << h << ": H " << H0 << " -> " << H);
    CHECK(increases == 0);
    CHECK(H < 0.8 * H0);
  }
}

TEST_CASE("a simo-wong step that rotates by pi or more stops the run with a message", "[simo-wong][failure]") {
  for (const auto& [name, h] : {std::pair{"free_body_hlw", 5.0}, std::pair{"heavy_top_trindade_1", 0.1}}) {
    const system::Scene scene = testing::shipped_scene(name);
    const system::AnyModel model = system::make_model(scene);
    system::State x = scene.initial;
    const auto stats = run(model, x, 10.0 * h, h);
    INFO(name << ": " << stats.status);
    CHECK_FALSE(stats.ok);
    CHECK(stats.status.rfind("step refused: the midpoint rotation h|W| reaches pi", 0) == 0);
    CHECK(stats.status.find("iterations, residual") != std::string::npos);
    CHECK(stats.steps == 1);
    CHECK(stats.work.newton_failures == 1);
  }
}

TEST_CASE("simo-wong's Newton iterations stay few", "[simo-wong][newton]") {
  // Printed for the record; bounded loosely.
  auto max_iterations = [](const char* name, double h, double T, double max_rotation) {
    const system::Scene scene = testing::shipped_scene(name);
    const system::AnyModel model = system::make_model(scene);
    return std::visit(
        [&](const auto& m) {
          integrators::SimoWong scheme;
          scheme.max_step_rotation = max_rotation;
          integrators::WorkCounters work;
          system::State x = scene.initial;
          const auto n = static_cast<int>(std::lround(T / h));
          int failures = 0;
          for (int k = 0; k < n && failures == 0; ++k) {
            const integrators::StepStatus st = scheme.step(m, x, k * h, h, work);
            integrators::detail::record_solve(st, work);
            failures += !st.converged;
          }
          return std::pair{work.newton_iterations_max, failures};
        },
        model);
  };
  const double inf = std::numeric_limits<double>::infinity();
  const auto fb3 = max_iterations("free_body_hlw", 1e-3, 10.0, std::numbers::pi);
  const auto fb1 = max_iterations("free_body_hlw", 0.1, 100.0, std::numbers::pi);
  const auto ht3 = max_iterations("heavy_top_trindade_1", 1e-3, 10.0, std::numbers::pi);
  const auto ht1 = max_iterations("heavy_top_trindade_1", 0.1, 10.0, inf);  // 5 rad a step: guard off
  std::cout << "simo-wong Newton max: free_body_hlw h=1e-3 " << fb3.first << ", h=0.1 " << fb1.first
            << "; heavy_top_trindade_1 h=1e-3 " << ht3.first << ", h=0.1 (rotation guard off) " << ht1.first
            << " (failures " << ht1.second << ")\n";
  CHECK(fb3.first <= 3);
  CHECK(fb1.first <= 6);
  CHECK(ht3.first <= 3);
  CHECK(fb3.second + fb1.second + ht3.second == 0);
}

}  // namespace test_energy_momentum
