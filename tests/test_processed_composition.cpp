// Processed compositions BASE@bcm-processed6 / @bcm-processed8
// (integrators/schemes/processed_composition.hpp) as the loop drives them: the loop
// holds the kernel's variable and observers get the trajectory's state. Their
// orders are measured with every other composition (tests/test_composition.cpp),
// their symmetry, conservation, resume and allocations by the generic tests.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "experiments/io/scene_reader.hpp"
#include "integrators/registry/registry.hpp"
#include "support/reference_solution.hpp"
#include "support/registered_run.hpp"
#include "support/run_command.hpp"

namespace test_processed_composition {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;

namespace {

const std::string scenes = LGI_SCENES_DIR;

struct Recorder final : integrators::Observer {
  std::vector<double> t;
  std::vector<system::State> x;
  void observe(std::int64_t, double time, const system::State& s) override {
    t.push_back(time);
    x.push_back(s);
  }
};

double distance(const system::State& a, const system::State& b) {
  return std::max((a.R - b.R).cwiseAbs().maxCoeff(), (a.Pi - b.Pi).cwiseAbs().maxCoeff());
}

struct Top {
  system::Scene scene = experiments::read_scene(scenes + "/heavy_top_hlw.toml");
  system::AnyModel model = system::make_model(scene);
};

}  // namespace

TEST_CASE("a processed composition is observed on the trajectory, not on the kernel's variable",
          "[processed][composition]") {
  const Top top;
  const auto& model = std::get<system::SceneModel>(top.model);
  const system::State ref = testing::reference_solution(model, top.scene.initial, 0.0, 10.0);
  // The errors at h = 0.1 are 1.8e-12 and 1.4e-6 (lgi work-precision, docs/math.md §8).
  const std::vector<std::pair<std::string, double>> runs = {{"split-symmetric@bcm-processed8", 1e-11},
                                                            {"lgvi@bcm-processed6", 1e-5}};
  for (const auto& [name, bound] : runs) {
    INFO(name);
    Recorder every, rare;
    const auto a = testing::run_registered(name, top.model, top.scene.initial, 10.0, 0.1, &every, 1);
    const auto b = testing::run_registered(name, top.model, top.scene.initial, 10.0, 0.1, &rare);
    REQUIRE(a.stats.ok);
    REQUIRE(b.stats.ok);
    // Observing does not perturb the run: the final states agree bit for bit.
    CHECK(distance(a.state, b.state) == 0.0);
    // The first sample is the initial state itself, the last the run's final state.
    REQUIRE(every.x.size() == 101);
    CHECK(distance(every.x.front(), top.scene.initial) == 0.0);
    CHECK(distance(every.x.back(), a.state) == 0.0);
    // Each sample is on the trajectory (order 6 or 8 at h = 0.1), not O(h²) off it
    // as the kernel's variable y = π⁻¹(x) is.
    CHECK(distance(a.state, ref) < bound);
    const system::State mid = testing::reference_solution(model, top.scene.initial, 0.0, 5.0);
    CHECK(every.t[50] == Approx(5.0));
    CHECK(distance(every.x[50], mid) < bound);
  }
}

TEST_CASE("a processed run's final state is its last sample, formed once", "[processed][composition]") {
  // Evaluations of a run of n steps observed at the end only: P + n K + P
  // (the processor before the first step, the kernels, one postprocessor);
  // observed after every step, (n − 1) P more. So 2 E(n) − E(2n) = 2P, with
  // P = (E_every(n) − E(n)) / (n − 1); a second postprocessor for the final
  // state (the run's end before it reused the last sample) would make it 3P.
  const Top top;
  const std::string name = "split-symmetric@bcm-processed8";
  Recorder every;
  const auto e10 = testing::run_registered(name, top.model, top.scene.initial, 1.0, 0.1);
  const auto e20 = testing::run_registered(name, top.model, top.scene.initial, 2.0, 0.1);
  const auto all10 = testing::run_registered(name, top.model, top.scene.initial, 1.0, 0.1, &every, 1);
  REQUIRE((e10.stats.ok && e20.stats.ok && all10.stats.ok));
  const std::int64_t P = (all10.stats.work.rhs_evaluations - e10.stats.work.rhs_evaluations) / 9;
  CHECK(P > 0);
  CHECK((all10.stats.work.rhs_evaluations - e10.stats.work.rhs_evaluations) % 9 == 0);
  CHECK(2 * e10.stats.work.rhs_evaluations - e20.stats.work.rhs_evaluations == 2 * P);
  CHECK(distance(every.x.back(), all10.state) == 0.0);
  CHECK(distance(e10.state, all10.state) == 0.0);
}

TEST_CASE("a step of another length is processed again: a clipped last step keeps the order",
          "[processed][composition]") {
  const Top top;
  const auto& model = std::get<system::SceneModel>(top.model);
  const double T = 10.03;  // 100 steps of 0.1, then one of 0.03
  const system::State ref = testing::reference_solution(model, top.scene.initial, 0.0, T);
  const auto run = testing::run_registered("split-symmetric@bcm-processed8", top.model, top.scene.initial, T, 0.1);
  REQUIRE(run.stats.ok);
  CHECK(run.stats.steps == 101);
  // Without processing again, the last step's kernel would meet a processor
  // for h = 0.1 and leave an O(h⁵) error (1e-6 here); with it, 1e-11.
  CHECK(distance(run.state, ref) < 1e-9);
}

TEST_CASE("a halving retry of a processed composition goes on from a consistent state", "[processed][composition]") {
  // lgvi@bcm-processed8 on the fast top: its Newton solves fail at h = 0.05 (in
  // the processor, whose stages come first), so every step is redone as two of
  // 0.025. A failed step must leave both the state and the processed length as
  // they were (processed_composition.hpp); if the length stayed at 0.05, the
  // retry would map back with the wrong processor and leave an O(h²) error, not
  // the run at h = 0.025 to round-off (its error is 5.8e-4 against split-symmetric@kahan-li8 at h = 1e-3).
  const system::Scene scene = experiments::read_scene(scenes + "/heavy_top_trindade_1.toml");
  const system::AnyModel model = system::make_model(scene);
  const auto& scheme = testing::registered_scheme("lgvi@bcm-processed8");
  integrators::NullObserver none;
  integrators::RunConfig cfg;
  cfg.t_end = 1.0;
  cfg.dt = 0.05;
  cfg.retry_halving = 2;
  system::State halved = scene.initial;
  const auto retried = scheme.run(model, halved, cfg, none);
  REQUIRE(retried.ok);
  CHECK(retried.work.rejected_steps == 20);
  const auto plain = testing::run_registered(scheme, model, scene.initial, 1.0, 0.025);
  REQUIRE(plain.stats.ok);
  CHECK(distance(halved, plain.state) <= 1e-10 * plain.state.Pi.norm());
}

TEST_CASE("a processed composition refuses events and scenes with a damper", "[processed][composition]") {
  const Top top;
  struct Height final : integrators::EventFunctions {
    int count() const override { return 1; }
    double value(int, double, const system::State& x) const override { return x.R(2, 2); }
    int direction(int) const override { return 0; }
  } height;
  integrators::RunConfig cfg;
  cfg.t_end = 1.0;
  cfg.dt = 0.1;
  cfg.events = &height;
  system::State x = top.scene.initial;
  integrators::NullObserver none;
  const auto& processed = testing::registered_scheme("split-axes@bcm-processed8");
  CHECK_FALSE(processed.locates_events);  // lgi poincare and the sweeps refuse it up front
  CHECK(testing::registered_scheme("split-axes@kahan-li8").locates_events);
  const auto stats = processed.run(top.model, x, cfg, none);
  CHECK_FALSE(stats.ok);
  CHECK(stats.status.find("processed composition") != std::string::npos);
  CHECK(stats.steps == 0);
  CHECK(distance(x, top.scene.initial) == 0.0);

  const system::Scene damped = experiments::read_scene(scenes + "/stiff_damped_spring.toml");
  const auto& scheme = testing::registered_scheme("split-exact@bcm-processed6");
  CHECK_FALSE(integrators::unsupported_reason(scheme, system::make_model(damped)).empty());
}

TEST_CASE("lgi poincare refuses a processed composition with a clear line and exit 2", "[processed][cli]") {
  const auto r = testing::run_lgi("poincare --scene " + scenes +
                                  "/heavy_top_hlw.toml --l 0.5 --h 1.5 --ics 2 --t-end 1 "
                                  "--scheme split-symmetric@bcm-processed8 --out processed_poincare.h5 --force --quiet");
  CHECK(r.status == 2);
  CHECK(r.err.find("--scheme") != std::string::npos);
  CHECK(r.err.find("split-symmetric@bcm-processed8") != std::string::npos);
}

}  // namespace test_processed_composition
