// Nanoseconds per step of every registered scheme on free_body_hlw,
// heavy_top_trindade_1 and free_body_hairer_vilmart (Hairer & Vilmart's test
// body I = (0.6, 0.8, 1.0), Π0 = (1.8, 0.4, −0.9) at h = 0.01, a benchmark
// scene of its own: tests/benchmarks/scenes/), through the same run functions
// lgi simulate uses (no output: a null observer, and no CPU clock: the run's
// two clock_gettime calls are system calls of ~2 µs on this kind of virtual
// machine, which at 256 steps per run added ~14 ns to every scheme's step;
// 2048 steps per run amortise start()). Ratios to quat/rk4 (or
// rkmk4 where the baselines are absent) on the same scene come from
// scripts/benchmark_ratios.py, which runs this program and divides.
#include <benchmark/benchmark.h>

#include <memory>
#include <string>
#include <vector>

#include "experiments/io/scene_reader.hpp"
#include "integrators/registry/registry.hpp"

using namespace lgi;

namespace {

constexpr std::int64_t steps_per_iteration = 2048;

void bench_scheme(benchmark::State& state, const integrators::SchemeInfo* scheme, const system::Scene* scene,
                  const system::AnyModel* model) {
  const double h = scene->dt.value_or(1e-3);
  integrators::RunConfig cfg{0.0, static_cast<double>(steps_per_iteration) * h, h, 1e-8, 1 << 30};
  cfg.cpu_clock = false;
  integrators::NullObserver none;
  double steps = 0.0;  // counted, since adaptive schemes choose their own steps
  for (auto _ : state) {
    system::State x = scene->initial;
    const auto stats = scheme->run(*model, x, cfg, none);
    benchmark::DoNotOptimize(x);
    if (!stats.ok) {
      state.SkipWithError(stats.status.c_str());
      break;
    }
    steps += static_cast<double>(stats.steps);
  }
  // ns per step: elapsed / (steps · 1e-9).
  state.counters["ns_per_step"] =
      benchmark::Counter(steps * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

struct Registration {
  // Scenes and models live as long as the program (the registered benchmarks
  // point to them) and are released at exit, so LeakSanitizer stays quiet.
  std::vector<std::unique_ptr<system::Scene>> scenes;
  std::vector<std::unique_ptr<system::AnyModel>> models;
  Registration() {
    static const struct {
      const char* dir;
      const char* file;
    } files[] = {{LGI_SCENES_DIR, "free_body_hlw"},
                 {LGI_SCENES_DIR, "heavy_top_trindade_1"},
                 {LGI_BENCH_SCENES_DIR, "free_body_hairer_vilmart"}};
    for (const auto& [dir, file] : files) {
      scenes.push_back(
          std::make_unique<system::Scene>(experiments::read_scene(std::string(dir) + "/" + file + ".toml")));
      models.push_back(std::make_unique<system::AnyModel>(system::make_model(*scenes.back())));
      const system::Scene* scene = scenes.back().get();
      const system::AnyModel* model = models.back().get();
      for (const auto& scheme : integrators::scheme_registry()) {
        if (!integrators::unsupported_reason(scheme, *model).empty()) continue;
        benchmark::RegisterBenchmark((std::string(file) + "/" + scheme.name).c_str(), bench_scheme, &scheme, scene,
                                     model);
      }
    }
  }
} registration;

}  // namespace
