// The Cardan top's tangent flow in lanes (integrators/ensemble/cardan_tangent_ensemble.hpp,
// docs/ensemble.md, "Cardan tangent flows"): the lanes' cos and sin (lane_sincos.hpp) are
// libm's to 3e-16 absolute; the written-out field is CardanTop::field and
// its dual part the dual-number tangent of torus_tangent_flow.hpp to round-off; the scalar
// step follows torus_tangent_step to round-off; every lane is the scalar step bit for bit
// with one and six vectors on every instruction set this CPU has, and the indicators'
// loop in lanes is the scalar loop bit for bit (a lane that blows up, a stop flag).
#include <catch2/catch.hpp>

#include <atomic>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "tests/ensemble_test_support.hpp"
#include "support/allocation_count.hpp"  // heap allocations: the global operator new counts them
#include "experiments/io/scene_suspension.hpp"
#include "integrators/ensemble/cardan_tangent_ensemble.hpp"
#include "integrators/ensemble/cardan_tangent_kernel.hpp"
#include "integrators/ensemble/lane_sincos.hpp"
#include "integrators/core/torus_tangent_flow.hpp"

namespace test_ensemble_cardan {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
namespace ensemble = lgi::integrators::ensemble;
using integrators::Mat6;
using integrators::Vec6;
using lgi::ensemble_test::same_bits;
using lgi::ensemble_test::shipped;

namespace {

// Upright and tilted frames, ring masses and inertias, a massless suspension, an asymmetric body.
constexpr const char* cardan_scenes[] = {"cardan_euler_tilted", "cardan_trindade_1_massless",
                                         "cardan_general_asymmetric_up", "cardan_general_horizontal",
                                         "cardan_lagrange_upright"};

Mat6 random_matrix(unsigned seed) {
  std::mt19937_64 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Mat6 V;
  for (int i = 0; i < 36; ++i) V.data()[i] = u(gen);
  return V;
}

/// States near the scene's initial one: angles moved by up to 1 rad, momenta scaled and shifted.
std::vector<Vec6> states_near(const system::Scene& scene, int n, unsigned seed) {
  const Vec6 base = system::stack(scene.cardan_initial);
  const double scale = std::max(1.0, base.tail<3>().norm());
  std::mt19937_64 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec6> out;
  for (int l = 0; l < n; ++l) {
    Vec6 x = base;
    for (int i = 0; i < 3; ++i) x(i) += u(gen), x(3 + i) = (1.0 + 0.3 * u(gen)) * x(3 + i) + 0.2 * scale * u(gen);
    out.push_back(x);
  }
  return out;
}

bool same_vec(const Vec6& a, const Vec6& b) { return same_bits(a.data(), b.data(), 6); }
bool same_mat(const Mat6& a, const Mat6& b) { return same_bits(a.data(), b.data(), 36); }

/// `steps` steps of n orbits (six vectors, or the first one) in lanes and by the scalar step; mismatches.
int lane_mismatches(const system::CardanTop& top, ensemble::Isa isa, int vectors, const std::vector<Vec6>& x0,
                    double h, int steps) {
  const ensemble::CardanLaneModel m = ensemble::cardan_lane_model(top);
  auto e = ensemble::CardanTangentEnsemble::make(top, isa, vectors);
  REQUIRE(e);
  const int n = static_cast<int>(x0.size());
  std::vector<Vec6> x = x0;
  std::vector<Mat6> V;
  for (int l = 0; l < e->lanes(); ++l) {
    const auto u = static_cast<std::size_t>(l < n ? l : 0);
    if (l < n) V.push_back(random_matrix(100u + static_cast<unsigned>(l)));
    if (vectors == 6) e->set_lane(l, x0[u], V[u]);
    else e->set_lane(l, x0[u], Vec6(V[u].col(0)));
  }
  int mismatches = 0;
  for (int k = 0; k < steps; ++k) {
    e->step(h);
    for (int l = 0; l < n; ++l) {
      const auto u = static_cast<std::size_t>(l);
      Vec6 lane;
      Mat6 W = V[u];
      if (vectors == 6) {
        ensemble::scalar_cardan_tangent_step(m, x[u], V[u], h);
        e->get_lane(l, lane, W);
      } else {
        Vec6 v = V[u].col(0), w;
        ensemble::scalar_cardan_tangent_step(m, x[u], v, h);
        V[u].col(0) = v;
        e->get_lane(l, lane, w);
        W = V[u];
        W.col(0) = w;
      }
      mismatches += same_vec(lane, x[u]) && same_mat(W, V[u]) ? 0 : 1;
    }
  }
  return mismatches;
}

bool same_indicators(const integrators::ChaosIndicators& a, const integrators::ChaosIndicators& b) {
  const double x[4] = {a.lyapunov, a.megno, a.megno_y, a.lyapunov_last_half};
  const double y[4] = {b.lyapunov, b.megno, b.megno_y, b.lyapunov_last_half};
  return same_bits(x, y, 4) && a.steps == b.steps && a.ok == b.ok && a.stopped == b.stopped;
}

}  // namespace

TEST_CASE("the lanes' cos and sin are libm's to 3e-16 absolute", "[ensemble][cardan]") {
  std::mt19937_64 gen(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double worst = 0.0, worst_small = 0.0;
  for (int k = 0; k < 200000; ++k) {
    const double scale = k % 4 == 0 ? 0.8 : k % 4 == 1 ? 10.0 : k % 4 == 2 ? 1e4 : 2e6;
    const double x = scale * u(gen);
    double c = 0.0, s = 0.0;
    ensemble::cos_sin_poly(x, c, s);
    const double e = std::max(std::abs(c - std::cos(x)), std::abs(s - std::sin(x)));
    worst = std::max(worst, e / (3e-16 + std::abs(x) * 0x1p-75));
    if (std::abs(x) < 0.78) worst_small = std::max(worst_small, std::abs(s - std::sin(x)) / (0x1p-52 * std::abs(std::sin(x))));
  }
  CHECK(worst <= 1.0);
  CHECK(worst_small <= 1.0);  // within one ulp on [−π/4, π/4]
  // Multiples of π/2 near the reduction's edges, and what goes to libm.
  for (const double x : {0.0, -0.0, 1.5707963267948966, 3.141592653589793, 4.71238898038469, 1.5e6, -1.6e6, 1e300}) {
    double c = 0.0, s = 0.0;
    ensemble::cos_sin_poly(x, c, s);
    CHECK(std::abs(c - std::cos(x)) <= 3e-16 + std::abs(x) * 0x1p-75);
    CHECK(std::abs(s - std::sin(x)) <= 3e-16 + std::abs(x) * 0x1p-75);
  }
  double c = 0.0, s = 0.0;
  ensemble::cos_sin_poly(std::nan(""), c, s);
  CHECK((std::isnan(c) && std::isnan(s)));
}

TEST_CASE("the written-out Cardan field and its dual part are CardanTop's to round-off", "[ensemble][cardan]") {
  for (const char* name : cardan_scenes) {
    INFO(name);
    const system::CardanTop top = experiments::cardan_top(shipped(name));
    const ensemble::CardanLaneModel m = ensemble::cardan_lane_model(top);
    const std::vector<Vec6> xs = states_near(shipped(name), 20, 3u);
    for (std::size_t k = 0; k < xs.size(); ++k) {
      const Vec6 v = random_matrix(50u + static_cast<unsigned>(k)).col(0);
      ensemble::DualN<double, 1> y[6], f[6];
      for (int c = 0; c < 6; ++c) y[c].a = xs[k](c), y[c].b[0] = v(c);
      ensemble::cardan_detail::field(m, y, f);
      Vec6 value, rate;
      for (int c = 0; c < 6; ++c) value(c) = f[c].a, rate(c) = f[c].b[0];
      const Vec6 exact = top.field(system::unstack(xs[k]));
      const Vec6 tangent = integrators::torus::torus_tangent_rate(top, xs[k], v);
      CHECK((value - exact).norm() <= 1e-12 * std::max(1.0, exact.norm()));
      CHECK((rate - tangent).norm() <= 1e-11 * std::max(1.0, tangent.norm()));
    }
  }
}

TEST_CASE("the scalar Cardan tangent step follows torus_tangent_step to round-off", "[ensemble][cardan]") {
  for (const char* name : cardan_scenes) {
    INFO(name);
    const system::Scene scene = shipped(name);
    const system::CardanTop top = experiments::cardan_top(scene);
    const ensemble::CardanLaneModel m = ensemble::cardan_lane_model(top);
    Vec6 x = system::stack(scene.cardan_initial), y = x;
    Mat6 V = random_matrix(3), W = V;
    for (int k = 0; k < 100; ++k) {
      ensemble::scalar_cardan_tangent_step(m, x, V, 0.005);
      integrators::torus::torus_tangent_step(top, y, W, 0.005);
    }
    CHECK((x - y).norm() <= 1e-11 * std::max(1.0, y.norm()));
    CHECK((V - W).norm() <= 1e-9 * W.norm());
  }
}

TEST_CASE("Cardan tangent lanes are the scalar step bit for bit on every instruction set", "[ensemble][cardan]") {
  for (const char* name : cardan_scenes) {
    const system::Scene scene = shipped(name);
    const system::CardanTop top = experiments::cardan_top(scene);
    for (const ensemble::Isa isa : ensemble::available_isas()) {
      const int lanes = ensemble::isa_lanes(isa);
      for (const int vectors : {1, 6})
        for (const int n : {3, lanes}) {
          INFO(name << ", " << ensemble::isa_name(isa) << ", " << vectors << " vectors, " << n << " lanes");
          CHECK(lane_mismatches(top, isa, vectors, states_near(scene, n, 7u), 0.005, vectors == 6 ? 20 : 60) == 0);
        }
    }
  }
}

TEST_CASE("the Cardan chaos indicators in lanes are the scalar loop's bit for bit", "[ensemble][cardan]") {
  for (const char* name : {"cardan_general_horizontal", "cardan_euler_tilted"}) {
    const system::Scene scene = shipped(name);
    const system::CardanTop top = experiments::cardan_top(scene);
    const ensemble::CardanLaneModel m = ensemble::cardan_lane_model(top);
    for (const ensemble::Isa isa : ensemble::available_isas()) {
      auto e = ensemble::CardanTangentEnsemble::make(top, isa);
      REQUIRE(e);
      for (const int n : {3, e->lanes()}) {
        std::vector<Vec6> x = states_near(scene, n, 9u);
        std::vector<Vec6> v;
        for (int l = 0; l < n; ++l) v.push_back(random_matrix(40u + static_cast<unsigned>(l)).col(0));
        if (n == 3) x[1](4) = std::nan("");  // blows up at the first step
        // 300 steps and a shortened last one; the midpoint mark; a stop flag read at step 256.
        for (const bool stop_set : {false, true}) {
          std::atomic<bool> stop{stop_set};
          for (int l = 0; l < n; ++l) e->set_lane(l, x[static_cast<std::size_t>(l)], v[static_cast<std::size_t>(l)]);
          std::vector<integrators::ChaosIndicators> lanes(static_cast<std::size_t>(n));
          e->chaos_indicators(0.0, 1.5051, 0.005, &stop, lanes);
          INFO(name << ", " << ensemble::isa_name(isa) << ", " << n << " lanes, stop " << stop_set);
          for (int l = 0; l < n; ++l) {
            const auto u = static_cast<std::size_t>(l);
            Vec6 y = x[u];
            const auto scalar = ensemble::scalar_cardan_chaos_indicators(m, y, v[u], 1.5051, 0.005, &stop);
            INFO("lane " << l << ": " << lanes[u].megno << " " << scalar.megno);
            CHECK(same_indicators(lanes[u], scalar));
          }
          if (!stop_set) CHECK(std::isfinite(lanes[0].megno));
          else CHECK(lanes[0].stopped);
          if (n == 3) CHECK_FALSE(lanes[1].ok);
        }
      }
    }
  }
}

TEST_CASE("Cardan tangent lanes allocate nothing", "[ensemble][cardan][allocations]") {
  const system::Scene scene = shipped("cardan_general_horizontal");
  const system::CardanTop top = experiments::cardan_top(scene);
  const Vec6 x = system::stack(scene.cardan_initial);
  for (const ensemble::Isa isa : ensemble::available_isas()) {
    auto six = ensemble::CardanTangentEnsemble::make(top, isa, 6);
    auto one = ensemble::CardanTangentEnsemble::make(top, isa);
    REQUIRE(six);
    REQUIRE(one);
    for (int l = 0; l < six->lanes(); ++l) {
      six->set_lane(l, x, random_matrix(1));
      one->set_lane(l, x, Vec6(random_matrix(1).col(0)));
    }
    integrators::ChaosIndicators out[ensemble::max_lanes];
    const long before = lgi::testing::counted_allocations();
    for (int k = 0; k < 50; ++k) six->step(0.005);
    one->chaos_indicators(0.0, 1.0, 0.005, nullptr, {out, static_cast<std::size_t>(one->lanes())});
    CHECK(lgi::testing::counted_allocations() == before);
  }
}

}  // namespace test_ensemble_cardan
