// Cost per step of the implicit RKMK schemes under the three Newton
// variants (integrators/schemes/implicit_rkmk.hpp: refreshed, the registry's
// default; full; simplified), with rkmk4 on the same scene and step as the
// baseline of the ratio, and the Newton iterations as counters. The
// iteration bounds themselves are asserted in tests/test_implicit.cpp.
#include <benchmark/benchmark.h>

#include <string>
#include <utility>
#include <variant>

#include "experiments/io/scene_reader.hpp"
#include "integrators/schemes/implicit_rkmk.hpp"
#include "integrators/schemes/rkmk.hpp"
#include "integrators/core/stepper_loop.hpp"
#include "integrators/system/model.hpp"

using namespace lgi;

namespace {

constexpr std::int64_t steps_per_iteration = 256;

template <class Scheme>
void bench_newton(benchmark::State& state, const char* scene_name, double h, Scheme proto) {
  const system::Scene scene = experiments::read_scene(std::string(LGI_SCENES_DIR) + "/" + scene_name + ".toml");
  const system::AnyModel model = system::make_model(scene);
  integrators::RunConfig cfg{0.0, static_cast<double>(steps_per_iteration) * h, h, 0.0, 1 << 30};
  integrators::NullObserver none;
  double steps = 0.0;
  std::int64_t iterations_max = 0;
  for (auto _ : state) {
    system::State x = scene.initial;
    Scheme scheme = proto;
    const auto stats =
        std::visit([&](const auto& m) { return integrators::integrate_fixed(scheme, m, x, cfg, none); }, model);
    benchmark::DoNotOptimize(x);
    if (!stats.ok) {
      state.SkipWithError(stats.status.c_str());
      break;
    }
    steps += static_cast<double>(stats.steps);
    iterations_max = std::max(iterations_max, stats.work.newton_iterations_max);
  }
  state.counters["ns_per_step"] =
      benchmark::Counter(steps * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["newton_iterations_max"] = static_cast<double>(iterations_max);
}

integrators::NewtonSettings settings(integrators::NewtonJacobian mode) {
  integrators::NewtonSettings ns;
  ns.jacobian = mode;
  return ns;
}

struct Registration {
  Registration() {
    using integrators::NewtonJacobian;
    const std::pair<NewtonJacobian, const char*> modes[] = {
        {NewtonJacobian::refreshed, "refreshed"}, {NewtonJacobian::full, "full"}, {NewtonJacobian::simplified, "simplified"}};
    for (const auto& [scene, h] : {std::pair{"free_body_hlw", 1e-1}, std::pair{"heavy_top_trindade_1", 1e-3}}) {
      const std::string prefix = std::string("newton/") + scene + "/h=" + (h == 1e-1 ? "0.1" : "0.001") + "/";
      benchmark::RegisterBenchmark((prefix + "rkmk4").c_str(), bench_newton<integrators::Rkmk4>, scene, h,
                                   integrators::Rkmk4{});
      for (const auto& [mode, label] : modes) {
        benchmark::RegisterBenchmark((prefix + "rkmk-gauss2/" + label).c_str(), bench_newton<integrators::RkmkGauss2>,
                                     scene, h, integrators::RkmkGauss2(settings(mode)));
        benchmark::RegisterBenchmark((prefix + "rkmk-gauss4/" + label).c_str(), bench_newton<integrators::RkmkGauss4>,
                                     scene, h, integrators::RkmkGauss4(settings(mode)));
        benchmark::RegisterBenchmark((prefix + "rkmk-radau5/" + label).c_str(), bench_newton<integrators::RkmkRadau5>,
                                     scene, h, integrators::RkmkRadau5(settings(mode)));
      }
    }
  }
} registration;

}  // namespace
