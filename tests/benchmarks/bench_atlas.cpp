// The atlas's speed targets: the full (l, h) bifurcation
// diagram of a general top (every branch sampled with lgi bifurcation's
// default 400 points, folds located, every point classified) and the
// equilibria at one l, on general_top_richter. The counter
// "fraction_of_2s_budget" is the time as a fraction of the 2 s target for
// one diagram (README, Performance); no timing is asserted anywhere.
#include <benchmark/benchmark.h>

#include <string>

#include "experiments/analysis/relative_equilibria.hpp"
#include "experiments/io/scene_reader.hpp"
#include "integrators/system/terms/gravity.hpp"

using namespace lgi;

namespace {

experiments::HeavyTopBody richter_top() {
  const system::Scene scene = experiments::read_scene(std::string(LGI_SCENES_DIR) + "/general_top_richter.toml");
  experiments::HeavyTopBody body;
  body.J = scene.inertia;
  body.weight = *scene.mass * scene.declared<system::GravityTerm>()->g * scene.center_of_mass.value_or(lie::Vec3::Zero());
  return body;
}

void bifurcation_diagram(benchmark::State& state) {
  const experiments::HeavyTopBody body = richter_top();
  std::size_t rows = 0;
  for (auto _ : state) {
    const experiments::EquilibriumSet set = experiments::equilibrium_branches(body, 400);
    rows = set.rows.size();
    benchmark::DoNotOptimize(set.rows.data());
  }
  state.counters["rows"] = static_cast<double>(rows);
  // seconds per diagram / 2 s: kIsIterationInvariantRate inverted gives s per iteration.
  state.counters["fraction_of_2s_budget"] =
      benchmark::Counter(2.0, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void equilibria_at_l(benchmark::State& state) {
  const experiments::HeavyTopBody body = richter_top();
  for (auto _ : state) {
    const experiments::EquilibriumSet set = experiments::equilibria_at(body, 3.0);
    benchmark::DoNotOptimize(set.rows.data());
  }
}

}  // namespace

BENCHMARK(bifurcation_diagram)->Name("atlas/bifurcation_general_top")->Unit(benchmark::kMillisecond);
BENCHMARK(equilibria_at_l)->Name("atlas/equilibria_general_top_l3")->Unit(benchmark::kMicrosecond);
