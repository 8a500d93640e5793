// Steps allocate nothing: for every registered scheme (the T³ schemes of the
// Cardan top on Cardan scenes), the number of heap
// allocations of a run does not depend on its number of steps (per-run
// set-up may allocate, a step may not). Counted by replacing the global
// operator new in this test executable (the verification kit's counter).
#include <catch2/catch.hpp>

#include "support/allocation_count.hpp"  // heap allocations: the global operator new counts them
#include "experiments/analysis/chaos_indicators.hpp"
#include "experiments/analysis/scheme_verification_cardan.hpp"
#include "experiments/io/scene_reader.hpp"
#include "integrators/registry/registry.hpp"
#include "integrators/core/torus_tangent_flow.hpp"
#include "support/cardan_problems.hpp"

namespace test_allocations {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;

namespace {
long allocations_of_run(const integrators::SchemeInfo& scheme, const system::AnyModel& model,
                        const system::Scene& scene, std::int64_t steps, double h) {
  system::State x = scene.initial;
  integrators::NullObserver none;
  integrators::RunConfig cfg{0.0, static_cast<double>(steps) * h, h, 1e-8, 1};
  const long before = lgi::testing::counted_allocations();
  const auto stats = scheme.run(model, x, cfg, none);
  const long after = lgi::testing::counted_allocations();
  INFO(scheme.name << ": " << stats.status);
  REQUIRE(stats.ok);
  return after - before;
}
}  // namespace

TEST_CASE("no scheme allocates per step", "[allocations]") {
  for (const char* file : {"free_body_hlw.toml", "heavy_top_trindade_1.toml", "stiff_damped_spring.toml"}) {
    const system::Scene scene = experiments::read_scene(std::string(LGI_SCENES_DIR) + "/" + file);
    const system::AnyModel model = system::make_model(scene);
    const double h = scene.dt.value_or(1e-3);
    for (const auto& scheme : integrators::scheme_registry()) {
      if (!integrators::unsupported_reason(scheme, model).empty()) continue;
      // Explicit schemes blow up there; compositions take negative substeps,
      // which run the damper backward (composition.hpp).
      if (std::string(file) == "stiff_damped_spring.toml" &&
          (!scheme.properties.implicit || !scheme.base_scheme.empty()))
        continue;
      // Odeint's bulirsch_stoer resizes its extrapolation tables when it
      // changes order: that is the library's, not ours, and it is documented
      // in `lgi schemes`. It is the one baseline that states no order (variable order).
      if (scheme.properties.baseline && scheme.order == 0) continue;
      // The identity start of free_body_hlw is the Euler-angle singularity
      // itself (theta = 0): the run refuses it, by design.
      if (scheme.properties.euler_angle_chart && std::string(file) == "free_body_hlw.toml") continue;
      const long few = allocations_of_run(scheme, model, scene, 10, h);
      const long many = allocations_of_run(scheme, model, scene, 1000, h);
      INFO(scheme.name << " on " << file << ": " << few << " allocations for 10 steps, " << many << " for 1000");
      CHECK(many == few);
    }
  }
}

TEST_CASE("no T^3 scheme allocates per step", "[allocations][cardan]") {
  namespace kit = experiments::verification;
  REQUIRE(!integrators::cardan_scheme_registry().empty());
  for (const char* name : {"cardan_euler_tilted", "cardan_general_horizontal"}) {
    const kit::CardanProblem p = kit::load_cardan_problem(LGI_SCENES_DIR, name);
    for (const auto& scheme : integrators::cardan_scheme_registry()) {
      const double h = 1e-3, tol = scheme.properties.adaptive ? 1e-8 : 0.0;
      auto allocations = [&](std::int64_t steps) {
        system::TorusState x = p.scene.cardan_initial;
        integrators::BasicNullObserver<system::TorusState> none;
        const long before = lgi::testing::counted_allocations();
        const auto stats = kit::run_cardan_span(scheme, p.top, x, 0.0, static_cast<double>(steps) * h, h, tol, none);
        const long after = lgi::testing::counted_allocations();
        INFO(scheme.name << " on " << name << ": " << stats.status);
        REQUIRE(stats.ok);
        return after - before;
      };
      const long few = allocations(10), many = allocations(1000);
      INFO(scheme.name << " on " << name << ": " << few << " allocations for 10 steps, " << many << " for 1000");
      CHECK(many == few);
    }
  }
}

TEST_CASE("the GALI loop allocates nothing per step", "[allocations][gali]") {
  // The curves are allocated once for the samples; the steps, the
  // normalisations and the SVDs (fixed maximal sizes) allocate nothing.
  const system::Scene scene = experiments::read_scene(std::string(LGI_SCENES_DIR) + "/general_top_richter.toml");
  const auto count = [&](double t_end) {
    experiments::IndicatorSettings s;
    s.t_end = t_end, s.dt = 0.01, s.gali = true, s.gali_sampling = {20, false};
    const long before = lgi::testing::counted_allocations();
    const auto c = experiments::gali_curves(scene, scene.initial, s, 0);
    const long after = lgi::testing::counted_allocations();
    REQUIRE(c.t.size() == 20);
    return after - before;
  };
  CHECK(count(1.0) == count(8.0));
}

TEST_CASE("the Cardan tangent step allocates nothing", "[allocations][cardan]") {
  // The dual-number field (integrators/system/dual.hpp) lives in fixed-size
  // Eigen objects: one vector and six vectors, not a single allocation.
  const system::CardanTop top = testing::cardan_test_top(0.4);
  system::Vec6 x = system::stack(testing::cardan_test_initial(top));
  system::Vec6 v = system::Vec6::Ones();
  system::Mat6 V = system::Mat6::Identity();
  const long before = lgi::testing::counted_allocations();
  for (int k = 0; k < 100; ++k) {
    integrators::torus::torus_tangent_step(top, x, v, 1e-3);
    integrators::torus::torus_tangent_step(top, x, V, 1e-3);
  }
  const long after = lgi::testing::counted_allocations();
  CHECK(after - before == 0);
  CHECK(v.allFinite());
}

}  // namespace test_allocations
