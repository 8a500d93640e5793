// The diagonal-inertia fast path of dmv, lgvi and dmv-pre*
// (integrators/schemes/moser_veselov_diagonal.hpp) against the general Newton solve
// (integrators/schemes/moser_veselov.hpp), and the free body's modified-inertia
// series evaluated once per run as a polynomial in h²:
//  - the same Cayley parameter and the same step to round-off, over a range
//    of h|Ω| and random diagonal bodies;
//  - one Newton correction per step on Hairer & Vilmart's body at h = 0.01;
//  - a clean, reported failure where no solution exists;
//  - the predicted start (six past roots) takes one correction to the cold
//    solve's root along a trajectory, and a poor guess goes on with Newton;
//  - the series in h² equals the series evaluated at each step.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <utility>

#include "integrators/schemes/moser_veselov.hpp"
#include "integrators/schemes/moser_veselov_series.hpp"
#include "support/registered_run.hpp"

namespace test_moser_veselov_diagonal {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
using lie::Mat3;
using lie::Vec3;
namespace mv = integrators::moser_veselov;

namespace {

system::FreeBody diagonal_body(const Vec3& I) {
  system::FreeBody body;
  body.inertia = system::make_inertia(Mat3(I.asDiagonal()));
  return body;
}

}  // namespace

TEST_CASE("the diagonal fast path solves the DMV equation of the general Newton solve", "[variational][newton]") {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> moment(0.5, 2.0), component(-1.0, 1.0);
  for (const double turn : {1e-4, 1e-2, 0.03, 0.3, 0.8}) {  // h|Ω|
    for (int trial = 0; trial < 50; ++trial) {
      const Vec3 I(moment(rng), moment(rng), moment(rng));
      const Vec3 Pi(component(rng), component(rng), component(rng));
      const double h = turn / Pi.cwiseQuotient(I).norm();
      const Mat3 J = I.asDiagonal();
      const Mat3 J_inv = I.cwiseInverse().asDiagonal();
      Vec3 f_general;
      mv::DiagonalSolution x;
      const mv::DiagonalMoments m(I, I.cwiseInverse());
      const auto general = mv::solve_cayley_parameter(J, J_inv, h * Pi, f_general);
      const auto fast = mv::solve_cayley_parameter_diagonal(m, h, Pi, x);
      const Vec3 f_fast = x.f;
      CHECK(x.f == m.mu.cwiseProduct(x.w));  // f = μ ∘ w, rounded once
      INFO("h|Omega| = " << turn << ", I = " << I.transpose() << ", Pi = " << Pi.transpose());
      REQUIRE(general.converged);
      REQUIRE(fast.converged);
      CHECK(fast.residual <= 4.0 * std::numeric_limits<double>::epsilon());
      CHECK((f_fast - f_general).norm() <= 1e-14 * f_general.norm());
      if (turn <= 0.03) CHECK(fast.iterations <= 2);
    }
  }
}

TEST_CASE("a diagonal DMV step equals the general step to round-off", "[variational]") {
  const Vec3 I(0.6, 0.8, 1.0);
  const system::State x0{Mat3::Identity(), Vec3(1.8, 0.4, -0.9)};
  for (const double h : {1e-3, 1e-2, 0.1}) {
    system::State general = x0, fast = x0;
    mv::Carry c_general, c_fast;
    REQUIRE(mv::dmv_step(Mat3(I.asDiagonal()), Mat3(I.cwiseInverse().asDiagonal()), general, c_general, h).converged);
    REQUIRE(mv::dmv_step_diagonal(mv::DiagonalMoments(I, I.cwiseInverse()), fast, c_fast, h).converged);
    INFO("h = " << h);
    CHECK((fast.Pi - general.Pi).norm() <= 1e-15 * x0.Pi.norm());
    CHECK((fast.R - general.R).norm() <= 1e-15);
  }
}

TEST_CASE("dmv-pre10 takes one Newton correction per step on Hairer-Vilmart's body at h = 0.01", "[variational][newton]") {
  const system::AnyModel body = diagonal_body(Vec3(0.6, 0.8, 1.0));
  const system::State x0{Mat3::Identity(), Vec3(1.8, 0.4, -0.9)};
  for (const char* name : {"dmv", "dmv-pre4", "dmv-pre10"}) {
    const auto run = testing::run_registered(name, body, x0, 100.0, 0.01);
    INFO(name << ": " << run.stats.status);
    REQUIRE(run.stats.ok);
    CHECK(run.stats.work.newton_iterations_max == 1);
    CHECK(run.stats.work.newton_failures == 0);
  }
}

TEST_CASE("the diagonal fast path fails cleanly where no DMV solution exists", "[variational][newton]") {
  // A spin about a principal axis has sin θ = h|Ω| (moser_veselov.hpp): none past h|Ω| = 1.
  const Vec3 I(1.0, 2.0, 3.0);
  const Vec3 Pi(0.0, 0.0, 3.0);  // Ω = (0, 0, 1)
  mv::DiagonalSolution x;
  const mv::DiagonalMoments m(I, I.cwiseInverse());
  const auto ok = mv::solve_cayley_parameter_diagonal(m, 0.99, Pi, x);
  CHECK(ok.converged);
  CHECK(std::abs(2.0 * std::atan(x.f.z()) - std::asin(0.99)) < 1e-12);
  const auto fail = mv::solve_cayley_parameter_diagonal(m, 1.01, Pi, x);
  CHECK_FALSE(fail.converged);
  CHECK(fail.iterations <= mv::max_newton_iterations);
  CHECK(fail.residual > 0.0);
}

TEST_CASE("the free body's modified-inertia series in h^2 equals the series at each step", "[variational]") {
  const Vec3 I(0.6, 0.8, 1.0);
  const Vec3 Pi(1.8, 0.4, -0.9);
  const double H = 0.5 * Pi.dot(I.cwiseInverse().cwiseProduct(Pi)), C = 0.5 * Pi.squaredNorm();
  auto check = [&](const auto& series) {
    std::array<double, 4> cs{}, cd{};
    series.coefficients_in_h2(H, C, cs, cd);
    for (const double h : {1e-3, 1e-2, 0.1, 0.3}) {
      double css = 0.0, cdd = 0.0;
      series.evaluate(h * h * H, h * h * C, css, cdd);
      const double degrees = series.degrees;
      INFO("order " << 2 * (degrees + 1) << ", h = " << h);
      CHECK(std::abs(mv::horner_in_h2(cs, series.degrees, h * h, 1.0) - css) <= 4e-16 * std::abs(css));
      CHECK(std::abs(mv::horner_in_h2(cd, series.degrees, h * h, 0.0) - cdd) <= 4e-16 * std::abs(css));
    }
  };
  check(mv::ModifiedInertiaSeries<4>(I));
  check(mv::ModifiedInertiaSeries<6>(I));
  check(mv::ModifiedInertiaSeries<8>(I));
  check(mv::ModifiedInertiaSeries<10>(I));
}

TEST_CASE("the predicted start: one correction to the cold solve's root, and the cold Newton when the guess is poor",
          "[variational][newton]") {
  // Along a trajectory of equal steps the predictor's guess (six past roots,
  // CayleyPredictor) is accepted after one correction and lands on the root of
  // the cold solve to round-off; a guess that is off goes on with Newton to the same root.
  // The solves' unknown is w = J f (moser_veselov_diagonal.hpp), and so is the guess.
  // The steps are those of a fixed-step run's grid t_k = t0 + k dt, so from
  // t0 = 1e4 on their lengths h = t_{k+1} − t_k jitter by ulp(t) (relative
  // 1.8e-10 there, 1.5e-9 at 1e5): the guess, extrapolated in w/h, must not
  // notice (extrapolated in f itself, it missed the acceptance at 1e4, and past a
  // jitter of 1e-9 the history was dropped).
  const Vec3 I(0.6, 0.8, 1.0);
  const mv::DiagonalMoments m(I, I.cwiseInverse());
  for (const auto& [dt, t0] : {std::pair{1e-3, 0.0}, std::pair{1e-2, 0.0}, std::pair{3e-2, 0.0},
                               std::pair{1e-2, 1e4}, std::pair{1e-2, 1e5}, std::pair{1e-3, 3e4}}) {
    system::State s{Mat3::Identity(), Vec3(1.8, 0.4, -0.9)};
    mv::Carry carry;
    mv::CayleyPredictor predictor;
    int predicted = 0, jittered = 0;
    for (int k = 0; k < 400; ++k) {
      const double h = (t0 + static_cast<double>(k + 1) * dt) - (t0 + static_cast<double>(k) * dt);
      jittered += h != dt;
      const bool ready = predictor.ready(h);
      mv::DiagonalSolution cold_solution;
      REQUIRE(mv::solve_cayley_parameter_diagonal(m, h, s.Pi, cold_solution).converged);
      const Vec3 cold = cold_solution.w;
      if (ready) {
        mv::DiagonalSolution x;
        const Vec3 p = predictor.guess(h);
        const auto st = mv::solve_cayley_parameter_predicted(m, h, s.Pi, p, x);
        const Vec3 w = x.w;
        INFO("dt = " << dt << ", t0 = " << t0 << ", step " << k);
        REQUIRE(st.converged);
        CHECK(st.iterations == 1);
        CHECK((w - cold).norm() <= 4e-16 * cold.norm());
        // Accepted after that one correction δ ((c |δ|²)² ≤ 1e-38 |p − δ|², c the Newton
        // bound), not after more Newton work, at h|Ω| ≤ 0.03 (at dt = 0.03, h|Ω| ≈ 0.09,
        // the guess is off by more).
        const double a[3] = {h * s.Pi.x(), h * s.Pi.y(), h * s.Pi.z()};
        const mv::DiagonalResidual r(m, a, p.x(), p.y(), p.z());
        Vec3 d;
        r.jacobian(m, a).solve(r.r0, r.r1, r.r2, d.x(), d.y(), d.z());
        if (dt <= 1e-2) {
          const double bound = m.newton_bound * d.squaredNorm();
          CHECK(bound * bound <= 1e-38 * (p - d).squaredNorm());
          // The accepted guess's status residual, max|ψ_i| / (2 max|a_i|), is the stopping
          // test's relative residual there to O(|f|) (h|Ω|/2 ≤ 0.02 here).
          CHECK(st.residual > 0.0);
          CHECK(st.residual == Approx(r.relative()).epsilon(0.05));
        }
        ++predicted;
      }
      REQUIRE(mv::dmv_step_diagonal(m, s, carry, h, &predictor).converged);
    }
    CHECK(predicted == 400 - mv::CayleyPredictor::points);  // the first six steps start cold
    if (t0 > 0.0) CHECK(jittered > 100);                   // the grid's steps do differ there
  }
  // A poor guess (10% off): not accepted after one correction, Newton goes on to the same root.
  const Vec3 Pi(1.8, 0.4, -0.9);
  mv::DiagonalSolution cold_solution, x;
  REQUIRE(mv::solve_cayley_parameter_diagonal(m, 0.01, Pi, cold_solution).converged);
  const Vec3 cold = cold_solution.w;
  const auto st = mv::solve_cayley_parameter_predicted(m, 0.01, Pi, 1.1 * cold, x);
  REQUIRE(st.converged);
  CHECK(st.iterations > 1);
  CHECK((x.w - cold).norm() <= 4e-16 * cold.norm());
  // A step of another length starts the history anew (and a failed step too).
  mv::CayleyPredictor p;
  for (int k = 0; k < 6; ++k) p.record(0.01, cold);
  CHECK(p.ready(0.01));
  CHECK_FALSE(p.ready(0.02));
  p.record(0.02, cold);
  CHECK_FALSE(p.ready(0.02));
  p.reset();
  CHECK_FALSE(p.ready(0.01));
}

}  // namespace test_moser_veselov_diagonal
