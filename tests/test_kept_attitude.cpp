// The attitude a free body's preprocessed DMV run keeps as a quaternion
// (integrators/schemes/cayley_quaternion.hpp; the loop's "Kept attitude",
// integrators/core/stepper_loop.hpp):
//  - one update is R F to round-off, and its increment is accurate to ε
//    relative (not merely ε |q|), on non-commuting random steps;
//  - the loop, which steps q and writes R only where it is read, gives the
//    run of step() at every step bit for bit: every sample, the crossings of
//    an event function of R, the final state, with output times, after an
//    interruption and after a failed step;
//  - a resumed run goes on bit for bit;
//  - a non-finite attitude stops the run at its first step;
//  - step() takes up a state the caller sets (no stale quaternion);
//  - |q| and RᵀR stay 1 to round-off over 10⁵ steps, without renormalisation.
#include <catch2/catch.hpp>
#include <atomic>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <string>

#include "integrators/schemes/moser_veselov_preprocessed.hpp"
#include "integrators/core/stepper_loop.hpp"
#include "lie/so3.hpp"
#include "tests/ensemble_test_support.hpp"

namespace test_kept_attitude {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
using integrators::State;
using lie::Mat3;
using lie::Vec3;
using lgi::ensemble_test::Recorder;
using lgi::ensemble_test::require_same_run;
using lgi::ensemble_test::same_bits;
namespace mv = integrators::moser_veselov;

namespace {

/// Every state of a run taken through step(), for comparison with the loop.
struct StepByStep {
  Recorder samples;
  State final_state;
};

/// The run of n steps on the grid k h taken with step() alone (no loop), each state observed.
StepByStep run_with_step(const system::FreeBody& body, const State& x0, double h, int n) {
  StepByStep r;
  integrators::DmvPre10 scheme;
  scheme.start(body, x0, 0.0);
  State s = x0;
  r.samples.observe(0, 0.0, s);
  integrators::WorkCounters work;
  for (int k = 0; k < n; ++k) {  // the loop's grid: t_k = k h computed, each step t_{k+1} − t_k
    const double t = static_cast<double>(k) * h, t_next = static_cast<double>(k + 1) * h;
    REQUIRE(scheme.step(body, s, t, t_next - t, work).converged);
    r.samples.observe(k + 1, t_next, s);
  }
  r.final_state = s;
  return r;
}

/// One run of dmv-pre10 through the loop from x0: its samples, stats and final state.
struct LoopRun {
  Recorder samples;
  State x;
  integrators::RunStats stats;
};
LoopRun loop_run(const system::FreeBody& body, const State& x0, const integrators::RunConfig& cfg) {
  LoopRun r{{}, x0, {}};
  integrators::DmvPre10 scheme;
  r.stats = integrators::integrate_fixed(scheme, body, r.x, cfg, r.samples);
  return r;
}

/// The third entry of R's last row (an event function that reads the attitude).
struct TiltCrossing final : integrators::EventFunctions {
  int count() const override { return 1; }
  double value(int, double, const State& x) const override { return x.R(2, 0) - 0.3; }
  int direction(int) const override { return 0; }
};

/// Keeps the checkpoint offered at step `at`.
struct KeepOne final : integrators::Checkpoints {
  explicit KeepOne(std::int64_t at) : at_(at) { every = 1; }
  bool due(std::int64_t step) override { return step == at_; }
  void save(const integrators::LoopCheckpoint& c) override { kept = c; }
  std::optional<integrators::LoopCheckpoint> kept;
  std::int64_t at_;
};

system::FreeBody hairer_vilmart_body() {
  system::FreeBody body;
  body.inertia = system::make_inertia(Mat3(Vec3(0.6, 0.8, 1.0).asDiagonal()));
  return body;
}

State initial_state() {
  State x;
  x.R = lie::exp_so3(Vec3(0.4, -1.1, 0.7));
  x.Pi = Vec3(0.6 * 1.1, 0.8 * -0.4, 1.0 * 0.9);
  return x;
}

}  // namespace

TEST_CASE("a quaternion step is R cay(2f), its increment accurate to eps relative", "[variational][quaternion]") {
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  constexpr double eps = std::numeric_limits<double>::epsilon();
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 axis(u(rng), u(rng), u(rng));
    const Mat3 R = lie::exp_so3(3.0 * axis);
    const double size = std::pow(10.0, -4.0 + 3.5 * (0.5 + 0.5 * u(rng)));  // |f| from 1e-4 to 0.3
    const Vec3 f = size * Vec3(u(rng), u(rng), u(rng));
    mv::CayleyQuaternion q;
    q.set_from(R);
    const double qa[4] = {q.q[0], q.q[1], q.q[2], q.q[3]};
    const double fa[3] = {f.x(), f.y(), f.z()};
    const double ff = (fa[0] * fa[0] + fa[1] * fa[1]) + fa[2] * fa[2];
    double dq[4];
    mv::cayley_quaternion_increment(qa, fa, ff, dq);
    // The increment in long double: q ⊗ (1, f)/√(1 + |f|²) − q.
    using L = long double;
    const L s = std::sqrt(1.0L + (L(fa[0]) * fa[0] + L(fa[1]) * fa[1] + L(fa[2]) * fa[2]));
    const L pw = 1.0L / s, px = fa[0] / s, py = fa[1] / s, pz = fa[2] / s;
    const L exact[4] = {qa[0] * pw - qa[1] * px - qa[2] * py - qa[3] * pz - qa[0],
                        qa[0] * px + qa[1] * pw + qa[2] * pz - qa[3] * py - qa[1],
                        qa[0] * py + qa[2] * pw + qa[3] * px - qa[1] * pz - qa[2],
                        qa[0] * pz + qa[3] * pw + qa[1] * py - qa[2] * px - qa[3]};
    L err = 0.0L, norm = 0.0L;
    for (int i = 0; i < 4; ++i) err = std::max(err, std::abs(exact[i] - L(dq[i]))), norm = std::max(norm, std::abs(exact[i]));
    INFO("|f| = " << f.norm());
    CHECK(static_cast<double>(err / norm) <= 8.0 * eps);
    q.rotate(fa, ff);
    Mat3 R1;
    q.write(R1);
    CHECK((R1 - R * lie::cay(2.0 * f)).lpNorm<Eigen::Infinity>() <= 16.0 * eps);
  }
}

TEST_CASE("the loop's kept attitude is step()'s run bit for bit", "[variational][quaternion][time-loop]") {
  const system::FreeBody body = hairer_vilmart_body();
  const State x0 = initial_state();
  const double h = 0.01;
  const int n = 700;
  const StepByStep each = run_with_step(body, x0, h, n);
  integrators::RunConfig cfg{0.0, n * h, h, 0.0, 1};
  cfg.cpu_clock = false;

  SECTION("every step observed") {
    const auto [r, x, st] = loop_run(body, x0, cfg);
    REQUIRE(st.ok);
    REQUIRE(r.states.size() == each.samples.states.size());
    for (std::size_t k = 0; k < r.states.size(); ++k) CHECK(same_bits(r.states[k], each.samples.states[k]));
    CHECK(same_bits(x, each.final_state));
  }
  SECTION("samples every 37 steps, output times, and the final state") {
    for (const bool times : {false, true}) {
      const std::vector<double> at{0.0, 0.37, 1.0, 2.5, 6.99, 7.0};
      integrators::RunConfig c = cfg;
      c.save_every = 37;
      if (times) c.output_times = &at;
      const auto [r, x, st] = loop_run(body, x0, c);
      REQUIRE(st.ok);
      for (std::size_t k = 0; k < r.states.size(); ++k) {
        INFO("sample at step " << r.steps[k]);
        CHECK(same_bits(r.states[k], each.samples.states[static_cast<std::size_t>(r.steps[k])]));
      }
      CHECK(r.states.size() == (times ? at.size() : 1 + n / 37 + 1));
      CHECK(same_bits(x, each.final_state));
    }
  }
  SECTION("an event function of R: the same steps, and crossings where step() finds them") {
    TiltCrossing tilt;
    integrators::RunConfig c = cfg;
    c.save_every = 1000;
    c.events = &tilt;
    const auto [r, x, st] = loop_run(body, x0, c);
    REQUIRE(st.ok);
    CHECK(same_bits(x, each.final_state));
    REQUIRE(r.hits.size() >= 2);
    for (const integrators::EventHit& hit : r.hits) {
      // Between the states step() reaches on either side of the crossing.
      const double before = each.samples.states[static_cast<std::size_t>(hit.step - 1)].R(2, 0) - 0.3;
      const double after = each.samples.states[static_cast<std::size_t>(hit.step)].R(2, 0) - 0.3;
      CHECK(before * after <= 0.0);
      CHECK(std::abs(hit.state.R(2, 0) - 0.3) <= 1e-12);
    }
  }
  SECTION("an interrupted run ends with R(q) of its last step") {
    std::atomic<bool> stop{true};
    integrators::RunConfig c = cfg;
    c.save_every = 1000;
    c.stop = &stop;
    const auto [r, x, st] = loop_run(body, x0, c);
    CHECK(st.interrupted);
    REQUIRE(st.steps == 1);
    CHECK(same_bits(r.states.back(), each.samples.states[1]));
    CHECK(same_bits(x, each.samples.states[1]));
  }
  SECTION("a refused step ends the run with R(q) of the last step taken") {
    integrators::RunConfig c = cfg;
    c.dt = 1e4 * h;  // |h Ω| > π: refused at the first step, which leaves q as it was
    c.t_end = 2e4 * h;
    const auto [r, x, st] = loop_run(body, x0, c);
    CHECK_FALSE(st.ok);
    CHECK((x.R - x0.R).lpNorm<Eigen::Infinity>() <= 1e-15);
    CHECK(same_bits(x.Pi.data(), x0.Pi.data(), 3));
  }
}

// Π's update never reads the attitude, so a NaN attitude is caught only by
// the loop's blow-up check (which reads the R set at the start and kept
// since, stepper_loop.hpp, "Kept attitude"): it must end the run at its first step.
TEST_CASE("a non-finite kept attitude stops the run as a blow-up", "[variational][quaternion][time-loop]") {
  const system::FreeBody body = hairer_vilmart_body();
  State x0 = initial_state();
  x0.R(1, 2) = std::numeric_limits<double>::quiet_NaN();
  integrators::RunConfig cfg{0.0, 1.0, 0.01, 0.0, 10};
  cfg.cpu_clock = false;
  const auto [r, x, st] = loop_run(body, x0, cfg);
  CHECK_FALSE(st.ok);
  CHECK(st.steps == 1);
  CHECK(st.status.find("non-finite") != std::string::npos);
  CHECK(std::isfinite(x.Pi.squaredNorm()));
}

TEST_CASE("a free body's dmv-pre10 run resumes bit for bit from a checkpoint", "[variational][quaternion][resume]") {
  const system::FreeBody body = hairer_vilmart_body();
  const State x0 = initial_state();
  integrators::RunConfig cfg{0.0, 4.0, 0.01, 0.0, 9};
  cfg.cpu_clock = false;
  KeepOne keep(173);
  cfg.checkpoints = &keep;
  const auto [whole, x, all] = loop_run(body, x0, cfg);
  REQUIRE(all.ok);
  REQUIRE(keep.kept);
  // The checkpoint's state has the attitude the run had reached: R(q) of step 173.
  const StepByStep each = run_with_step(body, x0, 0.01, 173);
  CHECK(same_bits(keep.kept->state, each.final_state));

  KeepOne from(-1);
  from.resume_from = &*keep.kept;
  integrators::RunConfig c = cfg;
  c.checkpoints = &from;
  const auto [rest, y, st] = loop_run(body, x0, c);
  REQUIRE(st.ok);
  CHECK(st.steps == all.steps);
  CHECK(same_bits(y, x));
  std::size_t first = 0;
  while (whole.steps[first] <= 173) ++first;
  REQUIRE(rest.states.size() == whole.states.size() - first);
  for (std::size_t k = 0; k < rest.states.size(); ++k) CHECK(same_bits(rest.states[k], whole.states[first + k]));
}

TEST_CASE("step() takes up a state the caller sets", "[variational][quaternion]") {
  const system::FreeBody body = hairer_vilmart_body();
  const State x0 = initial_state();
  integrators::DmvPre10 scheme;
  scheme.start(body, x0, 0.0);
  State s = x0;
  integrators::WorkCounters work;
  for (int k = 0; k < 50; ++k) REQUIRE(scheme.step(body, s, 0.0, 0.01, work).converged);
  // A new state, not the one the scheme's quaternion holds.
  State other = x0;
  other.R = lie::exp_so3(Vec3(-2.0, 0.3, 0.5));
  State a = other;
  REQUIRE(scheme.step(body, a, 0.0, 0.01, work).converged);
  integrators::DmvPre10 fresh;
  fresh.start(body, other, 0.0);
  State b = other;
  REQUIRE(fresh.step(body, b, 0.0, 0.01, work).converged);
  CHECK((a.R - b.R).lpNorm<Eigen::Infinity>() <= 1e-14);  // a stale q would be off by O(1)
}

TEST_CASE("|q| and R(q)'s orthogonality stay at round-off over 1e5 steps", "[variational][quaternion][round-off]") {
  const system::FreeBody body = hairer_vilmart_body();
  integrators::RunConfig cfg{0.0, 1000.0, 0.01, 0.0, std::int64_t{1} << 40};
  cfg.cpu_clock = false;
  integrators::NullObserver none;
  State x = initial_state();
  integrators::DmvPre10 scheme;
  REQUIRE(integrators::integrate_fixed(scheme, body, x, cfg, none).ok);
  const double orthogonality = (x.R.transpose() * x.R - Mat3::Identity()).lpNorm<Eigen::Infinity>();
  INFO("||R^T R - I|| = " << orthogonality);
  CHECK(orthogonality <= 2e-14);
  CHECK(std::abs(x.R.determinant() - 1.0) <= 2e-14);
}

}  // namespace test_kept_attitude
