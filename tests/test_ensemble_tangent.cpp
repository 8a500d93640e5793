// Tangent flows in lanes (integrators/ensemble/tangent_ensemble.hpp,
// docs/ensemble.md): the scalar step of the models with a kernel is the
// tangent flow of integrators/core/tangent_flow.hpp (to round-off) and its state
// part is rkmk4 bit for bit; every lane is that scalar step bit for bit, with
// one and six tangent vectors, on every instruction set this CPU has; the
// chaos indicators' loop in lanes gives each lane the scalar loop's values
// bit for bit, including a lane that blows up and a stop flag.
#include <catch2/catch.hpp>

#include <atomic>
#include <cmath>
#include <random>
#include <string>
#include <variant>
#include <vector>

#include "tests/ensemble_test_support.hpp"
#include "support/allocation_count.hpp"  // heap allocations: the global operator new counts them
#include "experiments/analysis/chaos_indicators.hpp"
#include "experiments/analysis/poincare_section.hpp"
#include "experiments/io/scene_reader.hpp"
#include "integrators/ensemble/tangent_ensemble.hpp"
#include "integrators/schemes/rkmk.hpp"
#include "integrators/core/tangent_flow.hpp"

namespace test_ensemble_tangent {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
namespace ensemble = lgi::integrators::ensemble;
using integrators::Mat6;
using integrators::State;
using integrators::Vec6;
using namespace lgi::ensemble_test;

namespace {

/// A heavy top that also carries a magnetic dipole and a harmonic drive: every term the kernels evaluate.
system::Scene every_kernel_term() {
  const system::Scene scene = shipped("general_top_richter");
  return experiments::parse_scene(scene.toml_text +
                                      "\n[magnetic]\ndipole_moment = [0.3, -0.2, 0.1]\nfield = [0.5, 1.0, -2.0]\n"
                                      "\n[drive]\ntorque_amplitude = [0.1, 0.2, -0.3]\nangular_frequency = 2.0\n"
                                      "phase = 0.3\n",
                                  "every_kernel_term.toml");
}

std::vector<system::Scene> scenes() {
  std::vector<system::Scene> out;
  for (const char* name : {"free_body_hlw", "kovalevskaya", "heavy_top_trindade_1", "magnetic_top"})
    out.push_back(shipped(name));
  out.push_back(every_kernel_term());
  return out;
}

Mat6 random_vectors(unsigned seed) {
  std::mt19937_64 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Mat6 V;
  for (int i = 0; i < 36; ++i) V.data()[i] = u(gen);
  return V;
}

bool same_mat(const Mat6& a, const Mat6& b) { return lgi::ensemble_test::same_bits(a.data(), b.data(), 36); }

/// `steps` steps of n trajectories (with six vectors, or the first one) in
/// lanes and by scalar_tangent_step; the number of lane steps that differ.
int lane_mismatches(const system::Scene& scene, ensemble::Isa isa, int vectors, int n, double h, int steps) {
  const system::AnyModel model = system::make_model(scene);
  const auto em = ensemble::ensemble_model(model);
  auto e = ensemble::TangentEnsemble::make(model, isa, vectors);
  REQUIRE(em);
  REQUIRE(e);
  const std::vector<State> x0 = initial_states(scene.initial, n, 5u + static_cast<unsigned>(n));
  std::vector<State> x = x0;
  std::vector<Mat6> V;
  for (int l = 0; l < e->lanes(); ++l) {
    const auto u = static_cast<std::size_t>(l < n ? l : 0);
    if (l < n) V.push_back(random_vectors(100u + static_cast<unsigned>(l)));
    if (vectors == 6) e->set_lane(l, x0[u], V[u]);
    else e->set_lane(l, x0[u], Vec6(V[u].col(0)));
  }
  int mismatches = 0;
  for (int k = 0; k < steps; ++k) {
    const double t = k * h;
    e->step(t, h);
    for (int l = 0; l < n; ++l) {
      const auto u = static_cast<std::size_t>(l);
      State lane;
      Mat6 W = Mat6::Zero();
      if (vectors == 6) {
        ensemble::scalar_tangent_step(*em, x[u], V[u], t, h);
        e->get_lane(l, lane, W);
      } else {
        Vec6 v = V[u].col(0), w;
        ensemble::scalar_tangent_step(*em, x[u], v, t, h);
        V[u].col(0) = v;
        e->get_lane(l, lane, w);
        W = V[u];
        W.col(0) = w;
      }
      mismatches += same_bits(lane, x[u]) && same_mat(W, V[u]) ? 0 : 1;
    }
  }
  return mismatches;
}

/// The scalar loop (accumulate_chaos_indicators with scalar_tangent_step) of each trajectory.
std::vector<integrators::ChaosIndicators> scalar_chaos(const ensemble::EnsembleModel& m, std::vector<State> x,
                                                       const std::vector<Vec6>& v, double t_end, double dt,
                                                       const std::atomic<bool>* stop) {
  std::vector<integrators::ChaosIndicators> out;
  for (std::size_t l = 0; l < x.size(); ++l) {
    Vec6 w = v[l];
    out.push_back(integrators::accumulate_chaos_indicators(
        [&](double t, double h, Vec6& u) { ensemble::scalar_tangent_step(m, x[l], u, t, h); },
        [&] { return x[l].Pi.allFinite(); }, w, 0.0, t_end, dt, stop));
  }
  return out;
}

bool same_indicators(const integrators::ChaosIndicators& a, const integrators::ChaosIndicators& b) {
  const double x[4] = {a.lyapunov, a.megno, a.megno_y, a.lyapunov_last_half};
  const double y[4] = {b.lyapunov, b.megno, b.megno_y, b.lyapunov_last_half};
  return lgi::ensemble_test::same_bits(x, y, 4) && a.steps == b.steps && a.ok == b.ok && a.stopped == b.stopped;
}

}  // namespace

TEST_CASE("the lanes' scalar tangent step is the tangent flow, its state rkmk4 bit for bit", "[ensemble][tangent]") {
  for (const system::Scene& scene : scenes()) {
    INFO(scene.name);
    const system::AnyModel model = system::make_model(scene);
    const auto em = ensemble::ensemble_model(model);
    REQUIRE(em);
    std::visit(
        [&](const auto& m) {
          State x = scene.initial, y = scene.initial, z = scene.initial;
          Mat6 V = random_vectors(3), W = V;
          integrators::Rkmk4 rkmk4;
          integrators::WorkCounters work;
          const double h = 0.01;
          for (int k = 0; k < 100; ++k) {
            ensemble::scalar_tangent_step(*em, x, V, k * h, h);
            integrators::tangent_step(m, y, W, k * h, h);  // the Eigen form: other roundings
            rkmk4.step(m, z, k * h, h, work);
          }
          CHECK(same_bits(x, z));
          CHECK((V - W).norm() <= 1e-11 * W.norm());
          CHECK((x.Pi - y.Pi).norm() <= 1e-12 * y.Pi.norm());
        },
        model);
  }
}

TEST_CASE("tangent lanes are the scalar tangent step bit for bit on every instruction set", "[ensemble][tangent]") {
  for (const system::Scene& scene : scenes()) {
    for (const ensemble::Isa isa : ensemble::available_isas()) {
      const int lanes = ensemble::isa_lanes(isa);
      for (const int vectors : {1, 6})
        for (const int n : {1, 3, lanes}) {
          INFO(scene.name << ", " << ensemble::isa_name(isa) << ", " << vectors << " vectors, " << n << " lanes");
          CHECK(lane_mismatches(scene, isa, vectors, n, 0.01, vectors == 6 ? 60 : 200) == 0);
        }
    }
  }
  // Steps of 1-2.5 rad at this top's spin: the closed forms of exp and dexp⁻¹ in the lanes.
  for (const ensemble::Isa isa : ensemble::available_isas())
    CHECK(lane_mismatches(shipped("heavy_top_trindade_1"), isa, 1, ensemble::isa_lanes(isa), 0.02, 100) == 0);
}

TEST_CASE("the chaos indicators in lanes are the scalar loop's bit for bit", "[ensemble][tangent]") {
  for (const char* name : {"kovalevskaya", "general_top_richter"}) {
    const system::Scene scene = shipped(name);
    const system::AnyModel model = system::make_model(scene);
    const auto em = ensemble::ensemble_model(model);
    REQUIRE(em);
    for (const ensemble::Isa isa : ensemble::available_isas()) {
      auto e = ensemble::TangentEnsemble::make(model, isa);
      REQUIRE(e);
      for (const int n : {1, 3, e->lanes()}) {
        std::vector<State> x = initial_states(scene.initial, n, 9u);
        std::vector<Vec6> v;
        for (int l = 0; l < n; ++l) v.push_back(random_vectors(40u + static_cast<unsigned>(l)).col(0));
        if (n == 3) x[1].Pi(0) = std::nan("");  // blows up at the first step
        // 300 steps and a shortened last one; the midpoint mark; a stop flag read at step 256.
        for (const bool stop_set : {false, true}) {
          std::atomic<bool> stop{stop_set};
          for (int l = 0; l < n; ++l) e->set_lane(l, x[static_cast<std::size_t>(l)], v[static_cast<std::size_t>(l)]);
          std::vector<integrators::ChaosIndicators> lanes(static_cast<std::size_t>(n));
          e->chaos_indicators(0.0, 3.0051, 0.01, &stop, lanes);
          const auto scalar = scalar_chaos(*em, x, v, 3.0051, 0.01, &stop);
          INFO(name << ", " << ensemble::isa_name(isa) << ", " << n << " lanes, stop " << stop_set);
          for (int l = 0; l < n; ++l) {
            const auto u = static_cast<std::size_t>(l);
            INFO("lane " << l << ": " << lanes[u].megno << " " << scalar[u].megno);
            CHECK(same_indicators(lanes[u], scalar[u]));
          }
          if (!stop_set) CHECK(std::isfinite(lanes[0].megno));
          else CHECK(lanes[0].stopped);
        }
      }
    }
  }
}

TEST_CASE("a spring scene has no tangent lanes and steps in the Eigen form", "[ensemble][tangent]") {
  const system::Scene scene = shipped("stiff_damped_spring");
  const system::AnyModel model = system::make_model(scene);
  std::string why;
  CHECK_FALSE(ensemble::ensemble_model(model, &why));
  CHECK(why.find("spring") != std::string::npos);
  CHECK_FALSE(ensemble::TangentEnsemble::make(model, ensemble::Isa::baseline));
  State x = scene.initial, y = scene.initial;
  Mat6 V = random_vectors(7), W = V;
  ensemble::with_tangent_step(model, [&](auto step) {
    step(x, V, 0.0, 0.01);
    return 0;
  });
  integrators::tangent_step(std::get<system::SceneModel>(model), y, W, 0.0, 0.01);
  CHECK((same_bits(x, y) && same_mat(V, W)));
}

TEST_CASE("tangent lanes allocate nothing", "[ensemble][tangent][allocations]") {
  const system::Scene scene = shipped("kovalevskaya");
  const system::AnyModel model = system::make_model(scene);
  for (const ensemble::Isa isa : ensemble::available_isas()) {
    auto e = ensemble::TangentEnsemble::make(model, isa, 6);
    auto one = ensemble::TangentEnsemble::make(model, isa);
    REQUIRE(e);
    REQUIRE(one);
    for (int l = 0; l < e->lanes(); ++l) {
      e->set_lane(l, scene.initial, random_vectors(1));
      one->set_lane(l, scene.initial, Vec6(random_vectors(1).col(0)));
    }
    integrators::ChaosIndicators out[ensemble::max_lanes];
    const long before = lgi::testing::counted_allocations();
    for (int k = 0; k < 100; ++k) e->step(k * 0.01, 0.01);
    one->chaos_indicators(0.0, 10.0, 0.01, nullptr, {out, static_cast<std::size_t>(one->lanes())});
    CHECK(lgi::testing::counted_allocations() == before);
  }
}

TEST_CASE("lgi indicators and chaos-map batches in lanes are their states one at a time", "[ensemble][tangent]") {
  const system::Scene scene = shipped("kovalevskaya");
  const std::vector<State> x0 = initial_states(scene.initial, 19, 3u);
  experiments::IndicatorSettings s;
  s.t_end = 2.0, s.dt = 0.01, s.seed = 5;
  std::vector<experiments::StateIndicators> lanes(x0.size());
  std::vector<experiments::OrbitIndicators> orbits(x0.size());
  std::vector<std::int64_t> index;
  for (std::size_t k = 0; k < x0.size(); ++k) index.push_back(static_cast<std::int64_t>(7 + k));
  for (const ensemble::Isa isa : ensemble::available_isas()) {
    INFO(ensemble::isa_name(isa));
    experiments::state_indicators(scene, x0, s, 7, isa, lanes);
    experiments::orbit_indicators(scene, x0, s.t_end, s.dt, s.seed, index, isa, orbits);
    for (std::size_t k = 0; k < x0.size(); ++k) {
      const experiments::StateIndicators one = experiments::state_indicators(scene, x0[k], s, index[k]);
      const experiments::OrbitIndicators orbit =
          experiments::orbit_indicators(scene, x0[k], s.t_end, s.dt, s.seed, index[k]);
      const double a[5] = {lanes[k].lyapunov, lanes[k].lyapunov_last_half, lanes[k].megno, orbits[k].lyapunov,
                           orbits[k].megno};
      const double b[5] = {one.lyapunov, one.lyapunov_last_half, one.megno, orbit.lyapunov, orbit.megno};
      CHECK(lgi::ensemble_test::same_bits(a, b, 5));
      CHECK(lanes[k].converged == one.converged);
    }
  }
}

}  // namespace test_ensemble_tangent
