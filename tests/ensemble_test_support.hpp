#pragma once
// What the ensemble tests share (tests/test_ensemble.cpp, tests/test_ensemble_dmv.cpp):
// comparison bit for bit, seeded initial states near a scene's, the shipped
// scenes, and the ensemble loop checked against the registry's run.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "experiments/io/scene_reader.hpp"
#include "integrators/ensemble/ensemble_loop.hpp"
#include "integrators/registry/registry.hpp"
#include "integrators/core/scheme_interface.hpp"
#include "lie/so3.hpp"

namespace lgi::ensemble_test {

using integrators::State;

/// Bit for bit, except that any two NaNs are equal: IEEE 754 leaves the sign
/// and payload of a NaN produced by arithmetic unspecified, and SSE2 and x87
/// paths differ there (a lane started at NaN or infinity).
inline bool same_bits(const double* a, const double* b, int n) {
  for (int i = 0; i < n; ++i)
    if (!(std::isnan(a[i]) && std::isnan(b[i])) && std::memcmp(a + i, b + i, sizeof(double)) != 0) return false;
  return true;
}
inline bool same_bits(const State& a, const State& b) {
  return same_bits(a.R.data(), b.R.data(), 9) && same_bits(a.Pi.data(), b.Pi.data(), 3);
}

/// Initial states near the scene's: the attitude turned and the momentum
/// scaled and tilted by a seeded draw (some lanes far from others).
inline std::vector<State> initial_states(const State& base, int n, unsigned seed) {
  std::mt19937_64 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<State> out;
  for (int l = 0; l < n; ++l) {
    State s = base;
    s.R = base.R * lie::exp_so3(lie::Vec3(u(gen), u(gen), u(gen)));
    s.Pi = (1.5 + u(gen)) * base.Pi + 0.3 * base.Pi.norm() * lie::Vec3(u(gen), u(gen), u(gen));
    out.push_back(s);
  }
  return out;
}

inline system::Scene shipped(const std::string& name) {
  return experiments::read_scene(std::string(LGI_SCENES_DIR) + "/" + name + ".toml");
}

/// Everything a run hands its observer.
struct Recorder final : integrators::Observer {
  std::vector<std::int64_t> steps;
  std::vector<double> times;
  std::vector<State> states;
  std::vector<integrators::EventHit> hits;
  bool stopped = false;
  void observe(std::int64_t step, double t, const State& s) override {
    steps.push_back(step), times.push_back(t), states.push_back(s);
  }
  void on_event(const integrators::EventHit& hit) override { hits.push_back(hit); }
  void on_stop() override { stopped = true; }
};

inline void require_same_run(const Recorder& a, const Recorder& b, const integrators::RunStats& sa,
                      const integrators::RunStats& sb, const State& xa, const State& xb) {
  CHECK(sa.steps == sb.steps);
  CHECK(sa.ok == sb.ok);
  CHECK(sa.status == sb.status);
  CHECK(sa.interrupted == sb.interrupted);
  CHECK(sa.t_final == sb.t_final);
  CHECK(sa.work.rhs_evaluations == sb.work.rhs_evaluations);
  CHECK(sa.work.newton_iterations_max == sb.work.newton_iterations_max);
  CHECK(sa.work.newton_failures == sb.work.newton_failures);
  CHECK(same_bits(xa, xb));
  CHECK(a.stopped == b.stopped);
  REQUIRE(a.steps == b.steps);
  CHECK(a.times == b.times);
  for (std::size_t k = 0; k < a.states.size(); ++k) CHECK(same_bits(a.states[k], b.states[k]));
  REQUIRE(a.hits.size() == b.hits.size());
  for (std::size_t k = 0; k < a.hits.size(); ++k) {
    CHECK(a.hits[k].event == b.hits[k].event);
    CHECK(a.hits[k].direction == b.hits[k].direction);
    CHECK(a.hits[k].step == b.hits[k].step);
    CHECK(a.hits[k].t == b.hits[k].t);
    CHECK(same_bits(a.hits[k].state, b.hits[k].state));
  }
}

/// The ensemble loop against the registry's run of `scheme`, lane by lane.
inline void check_loop(const char* scheme, const system::Scene& scene, const integrators::RunConfig& cfg,
                       const std::vector<State>& initial) {
  const system::AnyModel model = system::make_model(scene);
  const integrators::SchemeInfo& alone_run = *integrators::find_scheme(scheme);
  for (const integrators::ensemble::Isa isa : integrators::ensemble::available_isas()) {
    auto e = integrators::ensemble::EnsembleStepper::make(scheme, model, isa);
    REQUIRE(e);
    const auto n = std::min(initial.size(), static_cast<std::size_t>(e->lanes()));
    std::vector<State> states(initial.begin(), initial.begin() + static_cast<std::ptrdiff_t>(n));
    std::vector<Recorder> recorders(n);
    std::vector<integrators::Observer*> observers;
    for (auto& r : recorders) observers.push_back(&r);
    std::vector<integrators::RunStats> stats(n);
    integrators::ensemble::EnsembleWorkspace ws;
    integrators::ensemble::run_ensemble(*e, model, states, cfg, observers, stats, ws);
    for (std::size_t l = 0; l < n; ++l) {
      INFO(scheme << ", " << integrators::ensemble::isa_name(isa) << ", lane " << l);
      Recorder alone;
      State x = initial[l];
      const integrators::RunStats s = alone_run.run(model, x, cfg, alone);
      require_same_run(recorders[l], alone, stats[l], s, states[l], x);
    }
  }
}

/// The loop tests' run: t from 0 to 3, h = 1e-2, a sample every 7 steps, no
/// CPU clock (the runs are compared bit for bit), crossings of `events`.
inline integrators::RunConfig loop_config(const integrators::EventFunctions* events) {
  integrators::RunConfig cfg{0.0, 3.0, 1e-2, 0.0, 7};
  cfg.cpu_clock = false;
  cfg.events = events;
  return cfg;
}

/// Output times for the loop tests, off the step grid but for the ends.
inline const std::vector<double> loop_output_times{0.0, 0.05, 1.0, 1.234, 2.37, 3.0};

}  // namespace lgi::ensemble_test
