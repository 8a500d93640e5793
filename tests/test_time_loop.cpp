// The Lie-group time loop (integrators/core/stepper_loop.hpp) through the registry:
//  - RunConfig::output_times: a fixed-step scheme observes the output times on
//    its grid (and skips the others), an adaptive one lands on every one
//    exactly, and observes nowhere else;
//  - RunConfig::stop: a set flag ends the run after the current step with
//    ok = false, an "interrupted by signal" status, the steps counted and the
//    final state observed once (Observer::on_stop() first);
//  - both null: the same samples, bit for bit, as a run without the fields.
#include <catch2/catch.hpp>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "integrators/registry/registry.hpp"
#include "support/recorder.hpp"
#include "support/shipped_scene.hpp"

namespace test_time_loop {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
using testing::Recorder;

namespace {

const integrators::SchemeInfo& scheme(const char* name) {
  const auto* s = integrators::find_scheme(name);
  REQUIRE(s);
  return *s;
}

bool same(const system::State& a, const system::State& b) { return a.R == b.R && a.Pi == b.Pi; }

/// A run from `initial` with every sample recorded.
struct ObservedRun {
  system::State x;
  Recorder r;
  integrators::RunStats stats;
};
ObservedRun observed_run(const integrators::SchemeInfo& s, const system::AnyModel& model, const system::State& initial,
                         const integrators::RunConfig& cfg) {
  ObservedRun run{initial, {}, {}};
  run.stats = s.run(model, run.x, cfg, run.r);
  return run;
}

integrators::RunConfig config(const integrators::SchemeInfo& s, double t_end) {
  integrators::RunConfig cfg;
  cfg.t_end = t_end;
  if (s.properties.adaptive) cfg.tol = 1e-8;
  else cfg.dt = 1e-3;
  return cfg;
}

}  // namespace

TEST_CASE("time loop: output times are observed exactly, and nowhere else", "[time-loop]") {
  const system::Scene scene = testing::shipped_scene("free_body_hlw");
  const system::AnyModel model = system::make_model(scene);
  std::vector<double> times;
  for (int i = 0; i <= 100; ++i) times.push_back(0.01 * i);  // 0, 0.01, ..., 1 (as lgi singularity's grid)

  SECTION("fixed step (rkmk4): the times on its grid t0 + k dt; the grid is not changed") {
    const auto& s = scheme("rkmk4");
    std::vector<double> off = times;
    off.insert(off.begin() + 3, 0.0205);  // between grid points: skipped
    auto cfg = config(s, 1.0);
    cfg.output_times = &off;
    const auto [x, r, stats] = observed_run(s, model, scene.initial, cfg);
    REQUIRE(stats.ok);
    CHECK(stats.steps == 1000);
    REQUIRE(r.samples.size() == times.size());
    for (std::size_t i = 0; i < times.size(); ++i) {
      CHECK(r.samples[i].t == times[i]);
      CHECK(r.samples[i].step == 10 * static_cast<std::int64_t>(i));
    }
    // The states are those of the plain run at the same steps.
    system::State y = scene.initial;
    Recorder all;
    auto plain = config(s, 1.0);
    plain.save_every = 10;
    REQUIRE(s.run(model, y, plain, all).ok);
    REQUIRE(all.samples.size() == times.size());
    for (std::size_t i = 0; i < times.size(); ++i) CHECK(same(all.samples[i].s, r.samples[i].s));
    CHECK(same(x, y));
  }

  SECTION("adaptive (rkmk-dp54): steps are shortened to land on every time") {
    const auto& s = scheme("rkmk-dp54");
    std::vector<double> partial(times.begin() + 5, times.begin() + 60);  // not t0, not t_end
    auto cfg = config(s, 1.0);
    cfg.output_times = &partial;
    const auto [x, r, stats] = observed_run(s, model, scene.initial, cfg);
    INFO(stats.status);
    REQUIRE(stats.ok);
    CHECK(stats.t_final == 1.0);
    REQUIRE(r.samples.size() == partial.size());
    for (std::size_t i = 0; i < partial.size(); ++i) CHECK(r.samples[i].t == partial[i]);
    for (std::size_t i = 1; i < partial.size(); ++i) CHECK(r.samples[i].step > r.samples[i - 1].step);
    // Landing costs steps, but the proposal after a shortened step is not shrunk.
    system::State y = scene.initial;
    integrators::NullObserver none;
    const auto plain = s.run(model, y, config(s, 1.0), none);
    REQUIRE(plain.ok);
    CHECK(stats.steps >= plain.steps);
    CHECK(stats.steps <= plain.steps + static_cast<std::int64_t>(partial.size()));
    // And the run still ends close to the plain run's end state.
    CHECK((x.Pi - y.Pi).norm() < 1e-5);
  }
}

TEST_CASE("time loop: the stop flag ends a run cleanly with its statistics", "[time-loop]") {
  const system::Scene scene = testing::shipped_scene("free_body_hlw");
  const system::AnyModel model = system::make_model(scene);
  const std::atomic<bool> stop{true};
  for (const char* name : {"rkmk4", "rkmk-dp54"}) {
    for (const std::int64_t save_every : {std::int64_t{1}, std::int64_t{1000000}}) {
      INFO(name << " save_every " << save_every);
      const auto& s = scheme(name);
      auto cfg = config(s, 10.0);
      cfg.save_every = save_every;
      cfg.stop = &stop;
      const auto [x, r, stats] = observed_run(s, model, scene.initial, cfg);
      CHECK_FALSE(stats.ok);
      CHECK(stats.interrupted);
      CHECK(stats.status.rfind("interrupted by signal at step 1, t = ", 0) == 0);
      CHECK(stats.steps == 1);
      CHECK(stats.t_final > 0.0);
      CHECK(stats.t_final < 10.0);
      CHECK(stats.work.rhs_evaluations > 0);
      CHECK(stats.cpu_seconds >= 0.0);
      CHECK(r.stops == 1);
      CHECK(r.samples_at_stop == 1);  // the initial sample
      REQUIRE(r.samples.size() == 2);  // the final state observed once
      CHECK(r.samples.back().step == 1);
      CHECK(r.samples.back().t == stats.t_final);
      CHECK(same(r.samples.back().s, x));
    }
  }
  SECTION("with output times, the final state is observed too") {
    const auto& s = scheme("rkmk4");
    const std::vector<double> times = {0.0, 0.5, 1.0};
    auto cfg = config(s, 1.0);
    cfg.output_times = &times;
    cfg.stop = &stop;
    const auto [x, r, stats] = observed_run(s, model, scene.initial, cfg);
    CHECK(stats.interrupted);
    REQUIRE(r.samples.size() == 2);
    CHECK(r.samples[0].t == 0.0);
    CHECK(r.samples[1].step == 1);
    CHECK(r.samples[1].t == stats.t_final);
  }
  SECTION("a flag that stays false changes nothing") {
    const std::atomic<bool> go{false};
    const auto& s = scheme("rkmk-dp54");
    auto cfg = config(s, 1.0);
    cfg.stop = &go;
    const auto [x, r, stats] = observed_run(s, model, scene.initial, cfg);
    CHECK(stats.ok);
    CHECK_FALSE(stats.interrupted);
    CHECK(r.stops == 0);
  }
}

TEST_CASE("time loop: null output_times and stop reproduce the samples bit for bit", "[time-loop]") {
  const system::Scene scene = testing::shipped_scene("free_body_hlw");
  const system::AnyModel model = system::make_model(scene);
  for (const char* name : {"rkmk4", "rkmk-dp54", "lgvi"}) {
    const auto* found = integrators::find_scheme(name);
    if (!found) continue;
    INFO(name);
    const auto& s = *found;
    auto cfg = config(s, 2.0);
    cfg.save_every = 7;
    // The same run twice: once with the fields left null, once with a stop
    // flag that is never set and output times that are every saved time of
    // the first run (which must then be hit exactly on the same steps for
    // the fixed step).
    system::State x = scene.initial;
    Recorder a;
    const auto sa = s.run(model, x, cfg, a);
    REQUIRE(sa.ok);
    const std::atomic<bool> go{false};
    auto with_stop = cfg;
    with_stop.stop = &go;
    system::State y = scene.initial;
    Recorder b;
    const auto sb = s.run(model, y, with_stop, b);
    REQUIRE(sb.ok);
    CHECK(sa.steps == sb.steps);
    REQUIRE(a.samples.size() == b.samples.size());
    for (std::size_t i = 0; i < a.samples.size(); ++i) {
      CHECK(a.samples[i].step == b.samples[i].step);
      CHECK(a.samples[i].t == b.samples[i].t);
      CHECK(same(a.samples[i].s, b.samples[i].s));
    }
    CHECK(same(x, y));
    if (!s.properties.adaptive) {
      std::vector<double> times;
      for (const auto& smp : a.samples) times.push_back(smp.t);
      auto with_times = cfg;
      with_times.output_times = &times;
      system::State z = scene.initial;
      Recorder c;
      REQUIRE(s.run(model, z, with_times, c).ok);
      REQUIRE(c.samples.size() == a.samples.size());
      for (std::size_t i = 0; i < a.samples.size(); ++i) {
        CHECK(a.samples[i].step == c.samples[i].step);
        CHECK(a.samples[i].t == c.samples[i].t);
        CHECK(same(a.samples[i].s, c.samples[i].s));
      }
    }
  }
}

TEST_CASE("time loop: the baselines honour the same output times and stop flag", "[time-loop][baselines]") {
  const system::Scene scene = testing::shipped_scene("heavy_top_trindade_1");
  const system::AnyModel model = system::make_model(scene);
  const std::vector<double> times = {0.0, 0.01, 0.025, 0.1};
  for (const char* name : {"quat/rk4", "quat/dopri5", "matrix/rkf78"}) {
    INFO(name);
    const auto& s = scheme(name);
    {
      Recorder rec;
      integrators::RunConfig cfg = config(s, 0.1);
      cfg.output_times = &times;
      system::State x = scene.initial;
      REQUIRE(s.run(model, x, cfg, rec).ok);
      REQUIRE(rec.samples.size() == times.size());
      for (std::size_t i = 0; i < times.size(); ++i) CHECK(rec.samples[i].t == times[i]);
    }
    {
      const std::atomic<bool> stop{true};
      Recorder rec;
      integrators::RunConfig cfg = config(s, 0.1);
      cfg.stop = &stop;
      system::State x = scene.initial;
      const integrators::RunStats stats = s.run(model, x, cfg, rec);
      CHECK_FALSE(stats.ok);
      CHECK(stats.interrupted);
      CHECK(stats.status.rfind("interrupted by signal at step 1", 0) == 0);
      CHECK(stats.steps == 1);
      CHECK(rec.stops == 1);
      REQUIRE(rec.samples.size() == 2);  // the initial state and the state the run ends with
      CHECK(same(rec.samples.back().s, x));
    }
  }
}

}  // namespace test_time_loop
