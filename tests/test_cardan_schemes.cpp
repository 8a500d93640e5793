// Every scheme on T³ × ℝ³ (integrators/registry/registry_cardan.cpp) conserves what
// its facts claim (its order: tests/test_stated_orders.cpp), on the Cardan top of
// tests/support/cardan_problems.hpp (massive rings, off-axis centres: H is
// not separable). As test_stated_orders.cpp and test_scheme_properties.cpp
// do for the SO(3) registry:
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

namespace test_cardan_schemes {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
using integrators::cardan_scheme_registry;
using integrators::SchemeInfo;

namespace {

system::TorusState one_step(const SchemeInfo& s, const system::CardanTop& top, system::TorusState x, double h) {
  integrators::TorusRunConfig cfg;
  cfg.t_end = h;
  cfg.dt = std::abs(h);
  if (h < 0.0) cfg.t_end = h;
  cfg.cpu_clock = false;
  testing::KeepSamples keep;
  s.run_cardan_fixed(top, x, cfg, keep);
  return x;
}

}  // namespace

TEST_CASE("every symmetric T^3 scheme is symmetric and every symplectic one symplectic", "[cardan][generic]") {
  const system::CardanTop top = testing::cardan_test_top(0.5);
  const system::TorusState x0 = testing::cardan_test_initial(top);
  const double h = 0.05;
  for (const SchemeInfo& s : cardan_scheme_registry()) {
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
  for (const SchemeInfo& s : cardan_scheme_registry()) {
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
  const system::TorusState ref = testing::cardan_reference(top, 2.0);
  const SchemeInfo& s = *integrators::find_cardan_scheme("cardan-dp54");
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

namespace {

/// p2 = 0: the turning points of the inner ring (both directions).
class InnerTurns final : public integrators::BasicEventFunctions<system::TorusState> {
 public:
  int count() const override { return 1; }
  double value(int, double, const system::TorusState& x) const override { return x.p(1); }
  int direction(int) const override { return 0; }
};

class KeepHits final : public integrators::TorusObserver {
 public:
  void observe(std::int64_t, double, const system::TorusState& x) override { last = x; }
  void on_event(const integrators::BasicEventHit<system::TorusState>& hit) override { hits.push_back(hit); }
  system::TorusState last;
  std::vector<integrators::BasicEventHit<system::TorusState>> hits;
};

}  // namespace

TEST_CASE("every T^3 scheme runs events on the one loop: crossings located, the run unchanged", "[cardan][events]") {
  const system::CardanTop top = testing::cardan_test_top(0.5);
  const InnerTurns turns;
  for (const SchemeInfo& s : cardan_scheme_registry()) {
    INFO(s.name);
    integrators::TorusRunConfig cfg;
    cfg.t_end = 5.0;
    cfg.dt = 0.01;
    cfg.tol = 1e-10;
    cfg.cpu_clock = false;
    system::TorusState plain = testing::cardan_test_initial(top), with = plain;
    KeepHits none, kept;
    const integrators::RunStats a = s.run_cardan(top, plain, cfg, none);
    cfg.events = &turns;
    const integrators::RunStats b = s.run_cardan(top, with, cfg, kept);
    REQUIRE(a.ok);
    REQUIRE(b.ok);
    CHECK(a.steps == b.steps);
    CHECK(system::stack(plain) == system::stack(with));  // bit for bit: events only look
    REQUIRE(!kept.hits.empty());
    double t_before = 0.0;
    for (const auto& hit : kept.hits) {
      CHECK(std::abs(hit.state.p(1)) <= 1e-9 * (1.0 + hit.state.p.norm()));
      CHECK(hit.residual == std::abs(hit.state.p(1)));
      CHECK(hit.t > t_before);
      t_before = hit.t;
    }
  }
}

}  // namespace test_cardan_schemes
