// Trajectories per second per core of the Cardan top's tangent flow
// (docs/ensemble.md, "Cardan tangent flows"): the chaos indicators' loop
// (λ and MEGNO, one tangent vector) one orbit after another against the same
// loop in the lanes of each instruction set this CPU has, on the same orbits
// in the same run: 64 orbits of 1000 steps from states near the scene's, one
// thread. Upright frame (cos and sin of q2, q3 per stage) and horizontal
// frame (and of q1).
//   tangent/<scene>/megno/scalar   scalar_cardan_chaos_indicators (the lane kernel on double),
//                                  what `lgi chaos-map` runs with one orbit per item
//   tangent/<scene>/megno/torus    the same loop with torus_tangent_flow.hpp's Eigen and
//                                  dual-number step (the scalar path before the lanes)
//   tangent/<scene>/megno/<isa>    CardanTangentEnsemble::chaos_indicators
// and the state with six tangent vectors (GALI's, the spectrum's) stepped 200 times:
//   tangent/<scene>/six/scalar, tangent/<scene>/six/<isa>
// scripts/benchmark_ratios.py prints each speed-up over .../scalar and its
// fraction of the instruction set's vector ceiling (limits/vector_peak).
#include <benchmark/benchmark.h>

#include <memory>
#include <random>
#include <string>
#include <vector>

#include "experiments/io/scene_reader.hpp"
#include "experiments/io/scene_suspension.hpp"
#include "integrators/ensemble/cardan_tangent_ensemble.hpp"
#include "integrators/core/torus_tangent_flow.hpp"

using namespace lgi;
namespace ensemble = lgi::integrators::ensemble;
using integrators::Mat6;
using integrators::Vec6;

namespace {

constexpr int orbits = 64;
constexpr int steps = 1000;
constexpr int six_steps = 200;

struct Problem {
  system::Scene scene;
  system::CardanTop top;
  ensemble::CardanLaneModel lanes_model;
  std::vector<Vec6> initial;
  std::vector<Mat6> vectors;
  double h = 0.0;
  explicit Problem(const std::string& file)
      : scene(experiments::read_scene(std::string(LGI_SCENES_DIR) + "/" + file + ".toml")),
        top(experiments::cardan_top(scene)),
        lanes_model(ensemble::cardan_lane_model(top)) {
    std::mt19937_64 gen(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const Vec6 base = system::stack(scene.cardan_initial);
    for (int k = 0; k < orbits; ++k) {
      Vec6 x = base;
      for (int i = 0; i < 3; ++i) x(i) += u(gen), x(3 + i) = (1.0 + 0.2 * u(gen)) * x(3 + i) + 0.1 * u(gen);
      initial.push_back(x);
      Mat6 V;
      for (int i = 0; i < 36; ++i) V.data()[i] = u(gen);
      vectors.push_back(V);
    }
    h = scene.dt.value_or(1e-2);
  }
};

void count(benchmark::State& state) {
  const auto n = static_cast<double>(state.iterations()) * orbits;
  state.counters["trajectories_per_second"] = benchmark::Counter(n, benchmark::Counter::kIsRate);
}

void megno_scalar(benchmark::State& state, const Problem* p, bool torus) {
  for (auto _ : state) {
    for (int k = 0; k < orbits; ++k) {
      const auto u = static_cast<std::size_t>(k);
      Vec6 x = p->initial[u];
      const Vec6 v = p->vectors[u].col(0);
      integrators::ChaosIndicators r;
      if (torus) {
        system::TorusState s = system::unstack(x);
        r = integrators::torus::torus_chaos_indicators(p->top, s, v, steps * p->h, p->h);
      } else {
        r = ensemble::scalar_cardan_chaos_indicators(p->lanes_model, x, v, steps * p->h, p->h);
      }
      benchmark::DoNotOptimize(r.megno);
    }
  }
  count(state);
}

void megno_lanes(benchmark::State& state, const Problem* p, ensemble::Isa isa) {
  auto e = ensemble::CardanTangentEnsemble::make(p->top, isa);
  const int width = e->lanes();
  std::vector<integrators::ChaosIndicators> out(static_cast<std::size_t>(width));
  for (auto _ : state) {
    for (int first = 0; first < orbits; first += width) {
      const int n = std::min(width, orbits - first);
      for (int l = 0; l < n; ++l) {
        const auto u = static_cast<std::size_t>(first + l);
        e->set_lane(l, p->initial[u], Vec6(p->vectors[u].col(0)));
      }
      e->chaos_indicators(0.0, steps * p->h, p->h, nullptr, {out.data(), static_cast<std::size_t>(n)});
      benchmark::DoNotOptimize(out.data());
    }
  }
  count(state);
}

void six_scalar(benchmark::State& state, const Problem* p) {
  for (auto _ : state) {
    for (int k = 0; k < orbits; ++k) {
      Vec6 x = p->initial[static_cast<std::size_t>(k)];
      Mat6 V = p->vectors[static_cast<std::size_t>(k)];
      for (int i = 0; i < six_steps; ++i) ensemble::scalar_cardan_tangent_step(p->lanes_model, x, V, p->h);
      benchmark::DoNotOptimize(V.data());
    }
  }
  count(state);
}

void six_lanes(benchmark::State& state, const Problem* p, ensemble::Isa isa) {
  auto e = ensemble::CardanTangentEnsemble::make(p->top, isa, 6);
  const int width = e->lanes();
  for (auto _ : state) {
    for (int first = 0; first < orbits; first += width) {
      const int n = std::min(width, orbits - first);
      for (int l = 0; l < width; ++l) {
        const auto u = static_cast<std::size_t>(first + (l < n ? l : 0));
        e->set_lane(l, p->initial[u], p->vectors[u]);
      }
      for (int i = 0; i < six_steps; ++i) e->step(p->h);
      Vec6 x;
      Mat6 V;
      e->get_lane(0, x, V);
      benchmark::DoNotOptimize(V.data());
    }
  }
  count(state);
}

struct Registration {
  std::vector<std::unique_ptr<Problem>> problems;
  Registration() {
    for (const char* file : {"cardan_general_asymmetric_up", "cardan_general_horizontal"}) {
      problems.push_back(std::make_unique<Problem>(file));
      const Problem* p = problems.back().get();
      const std::string name = std::string("tangent/") + file + "/";
      benchmark::RegisterBenchmark((name + "megno/scalar").c_str(), megno_scalar, p, false);
      benchmark::RegisterBenchmark((name + "megno/torus").c_str(), megno_scalar, p, true);
      for (const ensemble::Isa isa : ensemble::available_isas())
        benchmark::RegisterBenchmark((name + "megno/" + ensemble::isa_name(isa)).c_str(), megno_lanes, p, isa);
      benchmark::RegisterBenchmark((name + "six/scalar").c_str(), six_scalar, p);
      for (const ensemble::Isa isa : ensemble::available_isas())
        benchmark::RegisterBenchmark((name + "six/" + ensemble::isa_name(isa)).c_str(), six_lanes, p, isa);
    }
  }
} registration;

}  // namespace
