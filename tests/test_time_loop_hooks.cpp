// The time loop's optional scheme hooks (integrators/core/stepper_loop.hpp,
// scheme_interface.hpp), on toy schemes whose behaviour is known exactly:
//  - a refused step (StepStatus::refused) ends the run with the scheme's
//    refusal_reason(), is not counted as a step or a Newton failure, and
//    leaves the last accepted state;
//  - a refused start() fails the run after the initial sample;
//  - RunConfig::max_consecutive_rejections ends a run that never accepts;
//  - dense output: an adaptive scheme with interpolate() is not shortened to
//    land on output times; they are interpolated, with the sample time the
//    output time and the step number that of the step holding it.
// The baselines, which use all of these, are driven by the same loop
// (baselines/chart_scheme.hpp; tests/test_baselines_singularity.cpp).
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "integrators/core/stepper_loop.hpp"
#include "integrators/system/model.hpp"

namespace test_time_loop_hooks {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
using integrators::AdaptiveStatus;
using integrators::RunConfig;
using integrators::StepStatus;
using integrators::WorkCounters;
using system::State;

namespace {

/// Π moves along Π̇ = (1, 0, 0) exactly: Π₁(t) = Π₁(0) + t.
void drift(State& s, double h) { s.Pi.x() += h; }

/// Fixed step; refuses the step that would take Π₁ past `wall`.
struct WallScheme {
  double wall = 0.0;
  bool refuse_start = false;
  template <class Model>
  StepStatus start(const Model&, const State&, double) {
    StepStatus st;
    st.refused = refuse_start;
    return st;
  }
  template <class Model>
  StepStatus step(const Model&, State& s, double, double h, WorkCounters& work) {
    ++work.rhs_evaluations;
    StepStatus st;
    if (s.Pi.x() + h > wall) st.refused = true;  // the state is left as it was
    else drift(s, h);
    return st;
  }
  std::string refusal_reason() const { return "the wall at " + std::to_string(wall); }
};

/// Adaptive; rejects every attempt and proposes the same step again.
struct StubbornScheme {
  template <class Model>
  double initial_step(const Model&, const State&, double, double) {
    return 0.1;
  }
  template <class Model>
  AdaptiveStatus attempt(const Model&, State&, double, double h, WorkCounters& work) {
    ++work.rejected_steps;
    return {.accepted = false, .error_norm = 2.0, .h_next = h};
  }
};

/// Adaptive with steps of 0.3 and an exact dense output of the drift.
struct DenseScheme {
  State start_of_step{};
  double t_start = 0.0;
  template <class Model>
  double initial_step(const Model&, const State&, double, double) {
    return 0.3;
  }
  template <class Model>
  AdaptiveStatus attempt(const Model&, State& s, double t, double h, WorkCounters&) {
    start_of_step = s;
    t_start = t;
    drift(s, h);
    return {.accepted = true, .error_norm = 0.5, .h_next = 0.3};
  }
  template <class Model>
  void interpolate(const Model&, double t, State& out) const {
    out = start_of_step;
    drift(out, t - t_start);
  }
};

struct Sample {
  std::int64_t step;
  double t;
  double pi1;
};
class Recorder final : public integrators::Observer {
 public:
  void observe(std::int64_t step, double t, const State& s) override { samples.push_back({step, t, s.Pi.x()}); }
  std::vector<Sample> samples;
};

State at_rest() {
  State s;
  s.R.setIdentity();
  s.Pi.setZero();
  return s;
}

const system::FreeBody model{};

/// A run of `scheme` from rest over [0, 1] with h = 0.1: its statistics, samples and final state.
struct WallRun {
  integrators::RunStats stats;
  Recorder rec;
  State s;
};
WallRun run_wall(WallScheme scheme) {
  WallRun run{{}, {}, at_rest()};
  const RunConfig cfg{{.t0 = 0.0, .t_end = 1.0, .dt = 0.1}};
  run.stats = integrators::integrate_fixed(scheme, model, run.s, cfg, run.rec);
  return run;
}

}  // namespace

TEST_CASE("time loop: a refused step ends the run at the last accepted state", "[time-loop]") {
  WallScheme scheme{.wall = 0.35};
  const auto [stats, rec, s] = run_wall(scheme);
  CHECK_FALSE(stats.ok);
  CHECK(stats.status == scheme.refusal_reason());
  CHECK(stats.steps == 3);  // the refused 4th step is not a step
  CHECK(stats.work.newton_failures == 0);
  CHECK(s.Pi.x() == Approx(0.3).margin(1e-15));
  CHECK(rec.samples.back().step == 3);
}

TEST_CASE("time loop: a refused start fails the run after the initial sample", "[time-loop]") {
  WallScheme scheme{.wall = 10.0, .refuse_start = true};
  const auto [stats, rec, s] = run_wall(scheme);
  CHECK_FALSE(stats.ok);
  CHECK(stats.status == scheme.refusal_reason());
  CHECK(stats.steps == 0);
  REQUIRE(rec.samples.size() == 1);
  CHECK(rec.samples[0].t == 0.0);
}

TEST_CASE("time loop: too many consecutive rejections end an adaptive run", "[time-loop]") {
  StubbornScheme scheme;
  State s = at_rest();
  RunConfig cfg{{.t0 = 0.0, .t_end = 1.0, .tol = 1e-8}};
  cfg.max_consecutive_rejections = 50;
  Recorder rec;
  const auto stats = integrators::integrate_adaptive(scheme, model, s, cfg, rec);
  CHECK_FALSE(stats.ok);
  CHECK(stats.status.rfind("too many consecutive rejected steps at step 0", 0) == 0);
  CHECK(stats.work.rejected_steps == 51);
}

TEST_CASE("time loop: dense output observes output times inside steps", "[time-loop]") {
  DenseScheme scheme;
  State s = at_rest();
  const std::vector<double> times{0.0, 0.25, 0.5, 0.6, 0.95, 1.0};
  RunConfig cfg{{.t0 = 0.0, .t_end = 1.0, .tol = 1e-8}};
  cfg.output_times = &times;
  Recorder rec;
  const auto stats = integrators::integrate_adaptive(scheme, model, s, cfg, rec);
  REQUIRE(stats.ok);
  CHECK(stats.steps == 4);  // 0.3, 0.6, 0.9, 1.0: not shortened to 0.25 or 0.5
  REQUIRE(rec.samples.size() == times.size());
  const std::vector<std::int64_t> steps{0, 1, 2, 2, 4, 4};
  for (std::size_t i = 0; i < times.size(); ++i) {
    CHECK(rec.samples[i].t == times[i]);
    CHECK(rec.samples[i].step == steps[i]);
    CHECK(rec.samples[i].pi1 == Approx(times[i]).margin(1e-15));
  }
}

}  // namespace test_time_loop_hooks
