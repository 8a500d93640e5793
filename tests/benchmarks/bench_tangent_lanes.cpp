// Trajectories per second per core of the tangent flow (docs/ensemble.md,
// "Tangent flows in lanes"): the chaos indicators' loop (λ and MEGNO, one
// tangent vector) one trajectory after another against the same loop in the
// lanes of each instruction set this CPU has, on the same trajectories in
// the same run: 64 trajectories of 1000 steps from initial states near the
// scene's, one thread.
//   tangent/<scene>/megno/scalar   accumulate_chaos_indicators with scalar_tangent_step,
//                                  what `lgi chaos-map` and `lgi indicators` run with --simd off
//   tangent/<scene>/megno/eigen    the same loop with tangent_flow.hpp's Eigen step (the spring's)
//   tangent/<scene>/megno/<isa>    TangentEnsemble::chaos_indicators
// and the state with six tangent vectors (GALI's, the spectrum's) stepped
// 200 times, without the loop's normalisations:
//   tangent/<scene>/six/scalar, tangent/<scene>/six/<isa>
// scripts/benchmark_ratios.py prints each speed-up over the scalar loop and
// its fraction of the instruction set's vector ceiling (limits/vector_peak).
#include <benchmark/benchmark.h>

#include <memory>
#include <random>
#include <string>
#include <variant>
#include <vector>

#include "experiments/io/scene_reader.hpp"
#include "integrators/ensemble/tangent_ensemble.hpp"

using namespace lgi;
namespace ensemble = lgi::integrators::ensemble;
using integrators::Mat6;
using integrators::Vec6;

namespace {

constexpr int trajectories = 64;
constexpr int steps = 1000;
constexpr int six_steps = 200;

struct Problem {
  system::Scene scene;
  system::AnyModel model;
  ensemble::EnsembleModel lanes_model;
  std::vector<system::State> initial;
  std::vector<Mat6> vectors;
  double h = 0.0;
  explicit Problem(const std::string& file)
      : scene(experiments::read_scene(std::string(LGI_SCENES_DIR) + "/" + file + ".toml")),
        model(system::make_model(scene)),
        lanes_model(*ensemble::ensemble_model(model)) {
    std::mt19937_64 gen(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int k = 0; k < trajectories; ++k) {
      system::State s = scene.initial;
      s.R = s.R * lie::exp_so3(lie::Vec3(u(gen), u(gen), u(gen)));
      s.Pi = (1.0 + 0.2 * u(gen)) * s.Pi + 0.1 * s.Pi.norm() * lie::Vec3(u(gen), u(gen), u(gen));
      initial.push_back(s);
      Mat6 V;
      for (int i = 0; i < 36; ++i) V.data()[i] = u(gen);
      vectors.push_back(V);
    }
    h = scene.dt.value_or(1e-2);
  }
};

void count(benchmark::State& state) {
  const auto n = static_cast<double>(state.iterations()) * trajectories;
  state.counters["trajectories_per_second"] = benchmark::Counter(n, benchmark::Counter::kIsRate);
}

void megno_scalar(benchmark::State& state, const Problem* p, bool eigen) {
  for (auto _ : state) {
    for (int k = 0; k < trajectories; ++k) {
      system::State x = p->initial[static_cast<std::size_t>(k)];
      Vec6 v = p->vectors[static_cast<std::size_t>(k)].col(0);
      const auto finite = [&] { return x.Pi.allFinite(); };
      integrators::ChaosIndicators r;
      if (eigen) {
        r = std::visit(
            [&](const auto& m) {
              return integrators::accumulate_chaos_indicators(
                  [&](double t, double h, Vec6& w) { integrators::tangent_step(m, x, w, t, h); }, finite, v, 0.0,
                  steps * p->h, p->h);
            },
            p->model);
      } else {
        r = integrators::accumulate_chaos_indicators(
            [&](double t, double h, Vec6& w) { ensemble::scalar_tangent_step(p->lanes_model, x, w, t, h); }, finite, v,
            0.0, steps * p->h, p->h);
      }
      benchmark::DoNotOptimize(r.megno);
    }
  }
  count(state);
}

void megno_lanes(benchmark::State& state, const Problem* p, ensemble::Isa isa) {
  auto e = ensemble::TangentEnsemble::make(p->model, isa);
  const int width = e->lanes();
  std::vector<integrators::ChaosIndicators> out(static_cast<std::size_t>(width));
  for (auto _ : state) {
    for (int first = 0; first < trajectories; first += width) {
      const int n = std::min(width, trajectories - first);
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
    for (int k = 0; k < trajectories; ++k) {
      system::State x = p->initial[static_cast<std::size_t>(k)];
      Mat6 V = p->vectors[static_cast<std::size_t>(k)];
      for (int i = 0; i < six_steps; ++i) ensemble::scalar_tangent_step(p->lanes_model, x, V, i * p->h, p->h);
      benchmark::DoNotOptimize(V.data());
    }
  }
  count(state);
}

void six_lanes(benchmark::State& state, const Problem* p, ensemble::Isa isa) {
  auto e = ensemble::TangentEnsemble::make(p->model, isa, 6);
  const int width = e->lanes();
  for (auto _ : state) {
    for (int first = 0; first < trajectories; first += width) {
      const int n = std::min(width, trajectories - first);
      for (int l = 0; l < width; ++l) {
        const auto u = static_cast<std::size_t>(first + (l < n ? l : 0));
        e->set_lane(l, p->initial[u], p->vectors[u]);
      }
      for (int i = 0; i < six_steps; ++i) e->step(i * p->h, p->h);
      system::State x;
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
    for (const char* file : {"free_body_hlw", "kovalevskaya"}) {
      problems.push_back(std::make_unique<Problem>(file));
      const Problem* p = problems.back().get();
      const std::string name = std::string("tangent/") + file + "/";
      benchmark::RegisterBenchmark((name + "megno/scalar").c_str(), megno_scalar, p, false);
      benchmark::RegisterBenchmark((name + "megno/eigen").c_str(), megno_scalar, p, true);
      for (const ensemble::Isa isa : ensemble::available_isas())
        benchmark::RegisterBenchmark((name + "megno/" + ensemble::isa_name(isa)).c_str(), megno_lanes, p, isa);
      benchmark::RegisterBenchmark((name + "six/scalar").c_str(), six_scalar, p);
      for (const ensemble::Isa isa : ensemble::available_isas())
        benchmark::RegisterBenchmark((name + "six/" + ensemble::isa_name(isa)).c_str(), six_lanes, p, isa);
    }
  }
} registration;

}  // namespace
