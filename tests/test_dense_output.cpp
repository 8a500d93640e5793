// Dense output of the adaptive RKMK pairs (integrators/schemes/rkmk_pair.hpp):
//  - the continuous extension of order q has local error O(h^(q+1)) inside
//    one step, on the free body (against the exact flow) and on a driven
//    general top (time-dependent torque, so the extra stages' times matter;
//    against an independent rkf78 solution);
//  - through the registry, output times are interpolated, not landed on: the
//    run takes the same steps to the same final state, bit for bit, and every
//    sample is as accurate as the run.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <type_traits>
#include <string>
#include <vector>

#include "integrators/registry/registry.hpp"
#include "integrators/schemes/rkmk_adaptive.hpp"
#include "integrators/system/free_body_exact.hpp"
#include "support/convergence.hpp"
#include "support/reference_solution.hpp"
#include "support/shipped_scene.hpp"

namespace test_dense_output {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
using testing::ConvergencePoint;

namespace {

system::Scene driven_general_top() {
  system::Scene scene = testing::shipped_scene("general_top_richter");
  scene.declared<system::HarmonicDriveTerm>() = system::HarmonicDriveTerm::Parameters{lie::Vec3(0.3, -0.2, 0.1), 2.0, 0.3};
  return scene;
}

/// The largest error of the interpolant at θ = 0.3 and 0.7 inside one step
/// of size h from x0, against reference(t).
template <class Scheme, class Model, class Reference>
double interpolation_error(const Model& model, const system::State& x0, double h, Reference&& reference) {
  Scheme scheme(1.0);
  system::State x = x0;
  integrators::WorkCounters work;
  scheme.attempt(model, x, 0.0, h, work, true);
  double worst = 0.0;
  for (double theta : {0.3, 0.7}) {
    system::State inside;
    scheme.interpolate(model, theta * h, inside);
    worst = std::max(worst, testing::global_error(inside, reference(theta * h)));
  }
  return worst;
}

class Samples final : public integrators::Observer {
 public:
  void observe(std::int64_t, double t, const system::State& s) override {
    times.push_back(t);
    states.push_back(s);
  }
  std::vector<double> times;
  std::vector<system::State> states;
};

}  // namespace

TEMPLATE_LIST_TEST_CASE("the dense output of every RKMK pair has its stated order", "[dense]", integrators::RkmkPairs) {
  if constexpr (TestType::dense) {
    constexpr int q = TestType::tableau.dense_order;
    auto check = [&](const char* what, auto&& error_at) {
      // From a local order of 9 on, steps of ratio 1.5 reach the floor within
      // three points (the error falls by 1.5⁹ ≈ 38 per point): ratio 1.2 there.
      const double ratio = q + 1 >= 9 ? 1.2 : 1.5;
      std::vector<ConvergencePoint> pts;
      for (double h = 0.8; h > 0.05; h /= ratio) pts.push_back({h, error_at(h)});
      // Floor 1e-12: the interpolant's round-off on the free body is 2-3e-13.
      const auto fit = testing::fitted_slope(pts, 1e-12, 1.0);
      testing::report_slope("dense output of order " + std::to_string(q) + " (local)", what, fit, pts);
      INFO(what << ": local slope " << fit.slope << ", expected " << q + 1);
      CHECK(fit.points >= 4);
      // In Cayley coordinates the chart's curvature adds terms of other orders
      // (test_stated_orders.cpp, upper_band): DOP853's order-7 interpolant
      // approaches 8 from below on the driven top, its slopes between
      // successive steps 7.46, 7.65, 7.78, 7.87, 7.90, 7.94 down to 4e-15 (fit
      // above the floor 7.70), and the 8(7) pair's order-8 interpolant fits
      // 10.8 on the free body, the 9(8) pair's 11.9 on the driven top.
      constexpr bool cayley = std::is_same_v<typename TestType::chart, integrators::CayleyChart>;
      CHECK(fit.slope >= q + 1 - (cayley ? 0.35 : 0.2));
      // The local error of the step itself is O(h^(p+1)), p ≥ q. The 9(8) pair's
      // order-9 interpolant (q = p = 9) fits 11.3 on the driven top above the
      // 1e-12 floor, the range being pre-asymptotic: 0.3 more there.
      CHECK(fit.slope <= q + (cayley ? 3.0 : q >= 9 ? 2.5 : 2.2));
    };
    {
      const system::Scene scene = testing::shipped_scene("free_body_hlw");
      const auto model = std::get<system::FreeBody>(system::make_model(scene));
      const system::FreeBodyExactFlow flow(model.inertia, scene.initial);
      check("free_body_hlw", [&](double h) {
        return interpolation_error<TestType>(model, scene.initial, h, [&](double t) { return flow.at(t); });
      });
    }
    {
      const system::Scene scene = driven_general_top();
      const auto model = std::get<system::SceneModel>(system::make_model(scene));
      check("driven general top", [&](double h) {
        return interpolation_error<TestType>(model, scene.initial, h, [&](double t) {
          return testing::reference_solution(model, scene.initial, 0.0, t, 1e-15);
        });
      });
    }
  } else {
    SUCCEED("no dense output: output times are landed on");
  }
}

TEST_CASE("output times inside the steps of a pair with dense output change nothing else", "[dense]") {
  const system::Scene scene = driven_general_top();
  const system::AnyModel model = system::make_model(scene);
  const double T = 5.0;
  std::vector<double> times;
  for (int k = 0; k <= 50; ++k) times.push_back(0.1 * k);
  int dense_pairs = 0;
  for (const auto& scheme : integrators::scheme_registry()) {
    if (!(scheme.family == "RKMK" && scheme.properties.adaptive)) continue;
    integrators::RunConfig cfg;
    cfg.t_end = T;
    cfg.tol = 1e-10;
    cfg.save_every = 1 << 30;
    integrators::NullObserver none;
    system::State plain = scene.initial;
    const auto stats_plain = scheme.run(model, plain, cfg, none);
    cfg.output_times = &times;
    Samples samples;
    system::State dense = scene.initial;
    const auto stats_dense = scheme.run(model, dense, cfg, samples);
    INFO(scheme.name);
    REQUIRE(stats_plain.ok);
    REQUIRE(stats_dense.ok);
    REQUIRE(samples.times.size() == times.size());
    if (!scheme.properties.dense_output) {  // the registry's fact: it lands on output times instead
      CHECK(stats_dense.steps > stats_plain.steps);
      continue;
    }
    ++dense_pairs;
    CHECK(stats_dense.steps == stats_plain.steps);
    CHECK(dense.R == plain.R);
    CHECK(dense.Pi == plain.Pi);
    CHECK(stats_dense.work.rhs_evaluations > stats_plain.work.rhs_evaluations);  // the extra stages are counted
    double worst = 0.0;
    for (std::size_t k = 1; k < times.size(); k += 7) {
      const system::State ref = testing::reference_solution(std::get<system::SceneModel>(model), scene.initial, 0.0,
                                                            times[k], 1e-15);
      worst = std::max(worst, testing::global_error(samples.states[k], ref));
    }
    const system::State ref_end =
        testing::reference_solution(std::get<system::SceneModel>(model), scene.initial, 0.0, T, 1e-15);
    const double at_end = testing::global_error(plain, ref_end);
    INFO("largest error at the sampled output times " << worst << ", at t_end " << at_end);
    CHECK(worst <= std::max(10.0 * at_end, 1e-10));
  }
  CHECK(dense_pairs == 8);  // DOP853 and Verner's 6(5), 8(7) and 9(8), in exponential and Cayley coordinates (rkmk_adaptive.hpp)
}

}  // namespace test_dense_output
