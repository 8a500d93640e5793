// The sweep engine against the bare stepping, per trajectory, on the spec
// experiments/sweeps/short_trajectories.toml (100 steps of rkmk4 each):
//  - sweep/bare: trajectory i's initial state, then the scheme's run
//    function with a null observer (what a hand-written loop would do);
//  - sweep/runner: SweepRunner::run (inputs, scene reuse, the observer with
//    invariant errors and the row), everything but the file.
// scripts/benchmark_sweep.py divides them, and adds lgi sweep end to end.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "experiments/analysis/sweep_trajectory.hpp"
#include "experiments/io/scene_reader.hpp"

using namespace lgi;

namespace {

struct ShortSweep {
  experiments::SweepSpec spec =
      experiments::read_sweep_spec(std::string(LGI_SWEEPS_DIR) + "/short_trajectories.toml");
  system::Scene scene = experiments::read_scene(spec.scene_path);
  experiments::SweepPlan plan{spec, scene};
  const integrators::SchemeInfo* scheme = integrators::find_scheme(spec.scheme);
  integrators::RunConfig cfg = [this] {
    integrators::RunConfig c{0.0, *spec.t_end, *spec.dt, 0.0, spec.monitor_every};
    c.cpu_clock = false;  // a hand-written loop reads no clock per trajectory
    return c;
  }();
};

const ShortSweep& short_sweep() {
  static const ShortSweep s;
  return s;
}

void bare(benchmark::State& state) {
  const auto& s = short_sweep();
  const system::AnyModel model = system::make_model(s.scene);
  integrators::NullObserver none;
  std::vector<double> inputs;
  std::int64_t i = 0;
  for (auto _ : state) {
    s.plan.inputs(i, inputs);
    system::State x = s.plan.initial_state(i, s.scene, inputs);
    const auto stats = s.scheme->run(model, x, s.cfg, none);
    benchmark::DoNotOptimize(x);
    benchmark::DoNotOptimize(stats.steps);
    i = (i + 1) % s.plan.count();
  }
  state.counters["us_per_trajectory"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * 1e-6, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void runner(benchmark::State& state) {
  const auto& s = short_sweep();
  experiments::SweepRunner run(s.spec, s.plan, *s.scheme, s.cfg, {"energy", "orthogonality"});
  std::vector<double> events;
  experiments::TrajectoryRow row;
  std::int64_t i = 0;
  for (auto _ : state) {
    run.run(i, events, nullptr, row);
    benchmark::DoNotOptimize(row.steps);
    i = (i + 1) % s.plan.count();
  }
  state.counters["us_per_trajectory"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * 1e-6, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

}  // namespace

BENCHMARK(bare)->Name("sweep/bare");
BENCHMARK(runner)->Name("sweep/runner");
