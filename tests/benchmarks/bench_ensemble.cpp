// Trajectories per second per core: the scalar loop (the registry's run
// function, one trajectory after another, what a sweep does with --simd off)
// against the ensemble loop (integrators/ensemble/, docs/ensemble.md) on each
// instruction set this CPU has, on the same trajectories in the same run:
// 64 trajectories of 1000 steps from initial states near the scene's, no
// samples but the first and the last (a null observer), one thread.
//   ensemble/<scene>/<scheme>/scalar      the baseline
//   ensemble/<scene>/<scheme>/<isa>       the ensemble loop on that instruction set
// scripts/benchmark_ratios.py prints each ensemble's speed-up over the
// scalar loop (trajectories per second, ratio).
#include <benchmark/benchmark.h>

#include <memory>
#include <random>
#include <string>
#include <vector>

#include "experiments/io/scene_reader.hpp"
#include "integrators/ensemble/ensemble_loop.hpp"
#include "integrators/registry/registry.hpp"

using namespace lgi;
namespace ensemble = lgi::integrators::ensemble;

namespace {

constexpr int trajectories = 64;
constexpr int steps = 1000;

struct Problem {
  system::Scene scene;
  system::AnyModel model;
  std::vector<system::State> initial;
  integrators::RunConfig cfg;
  explicit Problem(const std::string& file)
      : scene(experiments::read_scene(std::string(LGI_SCENES_DIR) + "/" + file + ".toml")),
        model(system::make_model(scene)) {
    std::mt19937_64 gen(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int k = 0; k < trajectories; ++k) {
      system::State s = scene.initial;
      s.R = s.R * lie::exp_so3(lie::Vec3(u(gen), u(gen), u(gen)));
      s.Pi = (1.0 + 0.2 * u(gen)) * s.Pi + 0.1 * s.Pi.norm() * lie::Vec3(u(gen), u(gen), u(gen));
      initial.push_back(s);
    }
    const double h = scene.dt.value_or(1e-2);
    cfg = integrators::RunConfig{0.0, steps * h, h, 0.0, 1 << 30};
    cfg.cpu_clock = false;
  }
};

void count(benchmark::State& state) {
  const auto n = static_cast<double>(state.iterations()) * trajectories;
  state.counters["trajectories_per_second"] = benchmark::Counter(n, benchmark::Counter::kIsRate);
}

void scalar(benchmark::State& state, const Problem* p, const integrators::SchemeInfo* scheme) {
  integrators::NullObserver none;
  for (auto _ : state) {
    for (const auto& x0 : p->initial) {
      system::State x = x0;
      const auto stats = scheme->run(p->model, x, p->cfg, none);
      benchmark::DoNotOptimize(x);
      benchmark::DoNotOptimize(stats.steps);
    }
  }
  count(state);
}

void lanes(benchmark::State& state, const Problem* p, const integrators::SchemeInfo* scheme, ensemble::Isa isa) {
  auto e = ensemble::EnsembleStepper::make(scheme->name, p->model, isa);
  const auto width = static_cast<std::size_t>(e->lanes());
  integrators::NullObserver none;
  std::vector<integrators::Observer*> observers(width, &none);
  std::vector<integrators::RunStats> stats(width);
  std::vector<system::State> x(width);
  ensemble::EnsembleWorkspace ws;
  for (auto _ : state) {
    for (std::size_t first = 0; first < p->initial.size(); first += width) {
      const std::size_t n = std::min(width, p->initial.size() - first);
      std::copy(p->initial.begin() + static_cast<std::ptrdiff_t>(first),
                p->initial.begin() + static_cast<std::ptrdiff_t>(first + n), x.begin());
      ensemble::run_ensemble(*e, p->model, {x.data(), n}, p->cfg, {observers.data(), n}, {stats.data(), n}, ws);
      benchmark::DoNotOptimize(x.data());
    }
  }
  count(state);
}

struct Registration {
  std::vector<std::unique_ptr<Problem>> problems;
  Registration() {
    for (const char* file : {"free_body_hlw", "kovalevskaya"}) {
      problems.push_back(std::make_unique<Problem>(file));
      const Problem* p = problems.back().get();
      for (const auto& scheme : integrators::scheme_registry()) {
        if (!ensemble::unsupported_reason(scheme.name, p->model).empty()) continue;
        const std::string name = std::string("ensemble/") + file + "/" + scheme.name + "/";
        benchmark::RegisterBenchmark((name + "scalar").c_str(), scalar, p, &scheme);
        for (const ensemble::Isa isa : ensemble::available_isas())
          benchmark::RegisterBenchmark((name + ensemble::isa_name(isa)).c_str(), lanes, p, &scheme, isa);
      }
    }
  }
} registration;

}  // namespace
