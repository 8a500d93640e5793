// Every scheme on T³ × ℝ³ (integrators/torus/torus_registry.hpp) shows the
// order its facts state and conserves what they claim, on the Cardan top of
// tests/support/cardan_problems.hpp (massive rings, off-axis centres: H is
// not separable). As test_stated_orders.cpp and test_scheme_properties.cpp
// do for the SO(3) registry:
//  - order: error at t = 2 against cardan-rk4 with h = 5e-5 (an error below
//    1e-13), the step ladder of test_stated_orders.cpp, slope of the five
//    finest points above 1e-12 within ±0.2 of the stated order (an adaptive scheme through its
//    fixed step, the propagated solution);
//  - symmetric: Φ₋ₕ ∘ Φₕ = id to 1e-12;
//  - symplectic: the step map's Jacobian A (central differences, 1e-6)
//    satisfies AᵀSA = S to 1e-7;
//  - conserves_energy: |H − H0|/|H0| ≤ 1e-12 over 400 steps, tilted axis;
//  - conserves_vertical_momentum (the cyclic p1 of a vertical outer axis):
//    |p1 − p1(0)| ≤ 1e-13 over 400 steps.
#include <catch2/catch.hpp>
#include <cmath>
#include <iostream>

#include "support/cardan_problems.hpp"
#include "support/convergence.hpp"

using namespace lgi;
using integrators::torus::torus_scheme_registry;
using integrators::torus::TorusSchemeInfo;

namespace {

constexpr double floor_error = 1e-12;  // the reference's error is below 1e-13

system::TorusState reference(const system::CardanTop& top, double t_end) {
  system::TorusState x = testing::cardan_test_initial(top);
  testing::run_torus(*integrators::torus::find_torus_scheme("cardan-rk4"), top, x, t_end, 5e-5);
  return x;
}

system::TorusState one_step(const TorusSchemeInfo& s, const system::CardanTop& top, system::TorusState x, double h) {
  integrators::RunConfig cfg;
  cfg.t_end = h;
  cfg.dt = std::abs(h);
  if (h < 0.0) cfg.t_end = h;
  cfg.cpu_clock = false;
  testing::KeepSamples keep;
  s.run_fixed(top, x, cfg, keep);
  return x;
}

}  // namespace

TEST_CASE("every T^3 scheme shows its stated order on the Cardan top", "[cardan][order][generic]") {
  const system::CardanTop top = testing::cardan_test_top(0.5);
  const double t_end = 2.0;
  const system::TorusState ref = reference(top, t_end);
  REQUIRE(torus_scheme_registry().size() >= 4);
  for (const TorusSchemeInfo& s : torus_scheme_registry()) {
    // As test_stated_orders.cpp: h_k = 0.2 r^k, r = max(10^(-1/(2p)), 1/2),
    // down to the floor or h = 1e-3; the five finest points above the floor.
    const double r = std::max(std::pow(10.0, -1.0 / (2.0 * s.order)), 0.5);
    std::vector<testing::ConvergencePoint> pts;
    for (double h = 0.2; h >= 1e-3; h *= r) {
      system::TorusState x = testing::cardan_test_initial(top);
      // An adaptive scheme: its propagated solution on the fixed grid h (run_fixed).
      integrators::RunConfig cfg;
      cfg.t_end = t_end;
      cfg.dt = h;
      cfg.cpu_clock = false;
      testing::KeepSamples keep;
      REQUIRE(s.run_fixed(top, x, cfg, keep).ok);
      const double err = testing::state_distance(x, ref);
      if (err <= floor_error) break;
      pts.push_back({h, err});
    }
    if (pts.size() > 5) pts.erase(pts.begin(), pts.end() - 5);
    const testing::SlopeFit fit = testing::fitted_slope(pts, floor_error);
    testing::report_slope(s.name, "cardan top (tilt 0.5, massive rings)", fit, pts);
    INFO(s.name << " states order " << s.order);
    REQUIRE(fit.points >= 3);
    CHECK(std::abs(fit.slope - s.order) <= 0.2);
  }
}

TEST_CASE("every symmetric T^3 scheme is symmetric and every symplectic one symplectic", "[cardan][generic]") {
  const system::CardanTop top = testing::cardan_test_top(0.5);
  const system::TorusState x0 = testing::cardan_test_initial(top);
  const double h = 0.05;
  for (const TorusSchemeInfo& s : torus_scheme_registry()) {
    if (s.properties.adaptive) continue;  // an adaptive step is not a map of the state alone
    INFO(s.name);
    if (s.properties.symmetric) {
      const system::TorusState back = one_step(s, top, one_step(s, top, x0, h), -h);
      CHECK(testing::state_distance(back, x0) <= 1e-12);
    }
    if (s.properties.symplectic) {
      system::Mat6 A;
      const system::Vec6 y = system::stack(x0);
      for (int j = 0; j < 6; ++j) {
        system::Vec6 yp = y, ym = y;
        yp[j] += 1e-6;
        ym[j] -= 1e-6;
        A.col(j) = (system::stack(one_step(s, top, system::unstack(yp), h)) -
                    system::stack(one_step(s, top, system::unstack(ym), h))) / 2e-6;
      }
      system::Mat6 S = system::Mat6::Zero();
      S.topRightCorner<3, 3>().setIdentity();
      S.bottomLeftCorner<3, 3>() = -lie::Mat3::Identity();
      CHECK((A.transpose() * S * A - S).cwiseAbs().maxCoeff() <= 1e-7);
    }
  }
}

TEST_CASE("every T^3 scheme conserves what it claims", "[cardan][generic]") {
  for (const TorusSchemeInfo& s : torus_scheme_registry()) {
    INFO(s.name);
    const double tol = s.properties.adaptive ? 1e-8 : 0.0;
    {  // energy, tilted axis
      const system::CardanTop top = testing::cardan_test_top(0.5);
      system::TorusState x = testing::cardan_test_initial(top);
      const double H0 = top.energy(x);
      testing::KeepSamples all(true);
      REQUIRE(testing::run_torus(s, top, x, 20.0, 0.05, tol, &all).ok);
      double drift = 0.0;
      for (const auto& y : all.states) drift = std::max(drift, std::abs(top.energy(y) - H0) / std::abs(H0));
      std::cout << "cardan " << s.name << ": max relative energy error over t = 20 (h = 0.05): " << drift << '\n';
      if (s.properties.conserves_energy) CHECK(drift <= 1e-12);
    }
    {  // the cyclic momentum p1, vertical axis
      const system::CardanTop top = testing::cardan_test_top(0.0);
      REQUIRE(top.outer_angle_cyclic());
      system::TorusState x = testing::cardan_test_initial(top);
      const double p10 = x.p[0];
      testing::KeepSamples all(true);
      REQUIRE(testing::run_torus(s, top, x, 20.0, 0.05, tol, &all).ok);
      double drift = 0.0;
      for (const auto& y : all.states) drift = std::max(drift, std::abs(y.p[0] - p10));
      std::cout << "cardan " << s.name << ": max |p1 - p1(0)| over t = 20, vertical axis (p1(0) = " << p10
                << "): " << drift << '\n';
      if (s.properties.conserves_vertical_momentum) CHECK(drift <= 1e-13 * (1.0 + x.p.norm()));
    }
  }
}

TEST_CASE("cardan-dp54 meets its tolerance and its error falls with it", "[cardan][adaptive]") {
  const system::CardanTop top = testing::cardan_test_top(0.5);
  const system::TorusState ref = reference(top, 2.0);
  const TorusSchemeInfo& s = *integrators::torus::find_torus_scheme("cardan-dp54");
  double previous = 1.0;
  for (double tol : {1e-6, 1e-8, 1e-10}) {
    system::TorusState x = testing::cardan_test_initial(top);
    const integrators::RunStats st = testing::run_torus(s, top, x, 2.0, 0.0, tol);
    REQUIRE(st.ok);
    const double err = testing::state_distance(x, ref);
    std::cout << "cardan-dp54 tol " << tol << ": " << st.steps << " steps, " << st.work.rejected_steps
              << " rejected, error " << err << '\n';
    CHECK(err <= 100.0 * tol);
    CHECK(err < previous);
    previous = err;
  }
}
