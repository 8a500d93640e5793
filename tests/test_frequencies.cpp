// NAFF frequency analysis (experiments/analysis/frequency/, docs/frequency_analysis.md):
//  - Laskar's error law on a synthetic quasi-periodic signal: the error of the
//    leading frequency decays as T^−(2p+2) for the window of order p (slope of
//    a log-log fit over four run lengths, for p = 1 and p = 2);
//  - the free body: the frequency of Π(t) equals 2π/T with T = 4K(k)/λ from
//    Boost's complete elliptic integral (Landau & Lifshitz, Mechanics §37),
//    computed here independently of lgi, to 1e-10 on two bodies;
//  - the Lagrange top: the frequency of γ3 = cos θ equals the closed form's
//    nutation frequency 2π/T_θ (analysis/actions.hpp) to 1e-9;
//  - consistency with `lgi actions`: NAFF's lines on the Euler and Lagrange
//    tops are integer combinations of the closed-form ∂H/∂I, on the Kovalevskaya
//    top of the numerical torus's.
#include <boost/math/special_functions/ellint_1.hpp>
#include <catch2/catch.hpp>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <complex>
#include <iostream>
#include <numbers>
#include <vector>

#include "experiments/analysis/actions.hpp"
#include "experiments/analysis/frequency/frequency_diffusion.hpp"
#include "experiments/analysis/frequency/naff.hpp"
#include "experiments/analysis/frequency/observable_series.hpp"
#include "experiments/io/scene_reader.hpp"
#include "integrators/registry/registry.hpp"
#include "support/shipped_scene.hpp"
#include "support/verbose.hpp"

namespace test_frequencies {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
namespace fq = lgi::experiments::frequency;

namespace {

constexpr double pi = std::numbers::pi;

/// The leading-frequency error of NAFF on e^{iω1 t} + 0.5 e^{i(ω2 t + 0.3)} sampled on [0, T].
double synthetic_error(double T, int p) {
  const double w1 = 1.0, w2 = 1.7, dt = 0.05;
  const auto n = static_cast<std::size_t>(std::llround(T / dt)) + 1;
  std::vector<std::complex<double>> f(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * dt;
    f[i] = std::polar(1.0, w1 * t) + 0.5 * std::polar(1.0, w2 * t + 0.3);
  }
  const fq::NaffResult r = fq::naff_complex(f, dt, {1, p});
  return std::abs(r.terms.at(0).frequency - w1);
}

/// The least-squares slope of log(error) against log(T).
double loglog_slope(const std::vector<double>& T, const std::vector<double>& e) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const auto n = static_cast<double>(T.size());
  for (std::size_t i = 0; i < T.size(); ++i) {
    const double x = std::log(T[i]), y = std::log(e[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

/// The frequency of the circulating components of a free body's Π (Landau & Lifshitz §37):
/// with moments I1 < I2 < I3, 2E = Σ Πᵢ²/Iᵢ and G² = |Π|², on G² > 2E I2 (rotation about axis 3)
/// λ² = (I3 − I2)(G² − 2E I1)/(I1 I2 I3), k² = (I2 − I1)(2E I3 − G²)/((I3 − I2)(G² − 2E I1)), and
/// the other regime with I1 and I3 exchanged; Π1, Π2 ∝ cn, sn of λt, period 4K(k)/λ.
/// `around` gets the axis Π circulates about (its component keeps its sign and has period T/2).
double free_body_frequency(const lie::Vec3& moments, const lie::Vec3& Pi, int& around) {
  const double e2 = (Pi.array().square() / moments.array()).sum(), g2 = Pi.squaredNorm();
  lie::Vec3 I = moments;
  std::sort(I.data(), I.data() + 3);
  if (g2 < e2 * I[1]) std::swap(I[0], I[2]);
  moments.maxCoeff(&around);
  if (g2 < e2 * I[1]) moments.minCoeff(&around);
  const double lambda2 = (I[2] - I[1]) * (g2 - e2 * I[0]) / (I[0] * I[1] * I[2]);
  const double k2 = (I[1] - I[0]) * (e2 * I[2] - g2) / ((I[2] - I[1]) * (g2 - e2 * I[0]));
  return 2.0 * pi * std::sqrt(lambda2) / (4.0 * boost::math::ellint_1(std::sqrt(k2)));
}

fq::SampledRun run(const system::Scene& scene, const std::string& scheme, double dt, double t_end,
                   const std::vector<std::string>& names) {
  const integrators::SchemeInfo* info = integrators::find_scheme(scheme);
  REQUIRE(info != nullptr);
  fq::SamplingSettings s;
  s.t_end = t_end, s.dt = dt, s.output_dt = dt;
  fq::SampledRun r = fq::sample_observables(scene, *info, s, names, nullptr);
  REQUIRE(r.stats.ok);
  return r;
}

double relative(double a, double b) { return std::abs(a - b) / std::abs(b); }

/// The distance of ν from the nearest |m a + n b| with |m| ≤ 2, |n| ≤ 4.
double combination_distance(double nu, double a, double b) {
  double best = INFINITY;
  for (int m = -2; m <= 2; ++m)
    for (int n = -4; n <= 4; ++n) best = std::min(best, std::abs(nu - std::abs(m * a + n * b)));
  return best;
}

}  // namespace

TEST_CASE("NAFF's frequency error follows Laskar's law T^-(2p+2)", "[frequencies]") {
  // Run lengths 4π/Δω apart (Δω = 0.7): the error's oscillating factor is the same at each.
  const double period = 4.0 * pi / 0.7;
  for (const int p : {1, 2}) {
    std::vector<double> T, e;
    for (const double m : {2.0, 3.0, 4.0, 6.0}) {
      T.push_back(m * period + 1.0);
      e.push_back(synthetic_error(T.back(), p));
    }
    const double slope = loglog_slope(T, e);
    if (testing::verbose()) std::cout << "p = " << p << ": errors " << e[0] << " .. " << e[3] << ", slope " << slope << '\n';
    CHECK(slope == Approx(-(2.0 * p + 2.0)).margin(0.5));
  }
}

TEST_CASE("NAFF recovers the amplitudes and phases of a real quasi-periodic signal", "[frequencies]") {
  const double dt = 0.02, T = 400.0;
  std::vector<double> f;
  for (double t = 0.0; t <= T + 1e-9; t += dt)
    f.push_back(0.25 + 1.5 * std::cos(1.3 * t + 0.4) + 0.6 * std::cos(std::sqrt(3.0) * t - 1.0) +
                0.1 * std::cos(0.31 * t + 2.0));
  const fq::NaffResult r = fq::naff_real(f, dt, {4, 2});
  REQUIRE(r.terms.size() >= 3);
  CHECK(r.mean.real() == Approx(0.25).margin(1e-9));
  CHECK(r.terms[0].frequency == Approx(1.3).epsilon(1e-9));
  CHECK(r.terms[0].amplitude == Approx(1.5).epsilon(1e-8));
  CHECK(r.terms[0].phase == Approx(0.4).margin(1e-7));
  CHECK(r.terms[1].frequency == Approx(std::sqrt(3.0)).epsilon(1e-9));
  CHECK(r.terms[1].amplitude == Approx(0.6).epsilon(1e-8));
  CHECK(r.terms[1].phase == Approx(-1.0).margin(1e-7));
  CHECK(r.terms[2].frequency == Approx(0.31).epsilon(1e-10));
  CHECK(r.terms[2].amplitude == Approx(0.1).epsilon(1e-7));
  // A torus: the two halves agree (the diffusion index is at the precision of NAFF on T/2 = 200).
  const fq::FrequencyDiffusion d = fq::frequency_diffusion(f, dt, {4, 2}, r.terms[0].frequency);
  CHECK(d.relative_change < 1e-7);
}

TEST_CASE("NAFF reads its stop flag: unset, the same terms; set, it throws NaffStopped", "[frequencies]") {
  const double dt = 0.02;
  std::vector<double> f;
  for (int i = 0; i <= 200000; ++i) f.push_back(std::cos(1.3 * i * dt) + 0.2 * std::cos(0.7 * i * dt));
  std::atomic<bool> stop{false};
  const fq::NaffResult plain = fq::naff_real(f, dt, {3, 2}), polled = fq::naff_real(f, dt, {3, 2, &stop});
  REQUIRE(plain.terms.size() == polled.terms.size());
  for (std::size_t k = 0; k < plain.terms.size(); ++k) CHECK(plain.terms[k].frequency == polled.terms[k].frequency);
  stop = true;
  CHECK_THROWS_AS(fq::naff_real(f, dt, {3, 2, &stop}), fq::NaffStopped);
  std::vector<std::complex<double>> z(f.begin(), f.end());
  CHECK_THROWS_AS(fq::frequency_diffusion(z, dt, {3, 2, &stop}, 1.3), fq::NaffStopped);
}

TEST_CASE("NAFF's frequency of the free body's Pi is 2 pi / T_exact to 1e-10", "[frequencies]") {
  // Two bodies: HLW's (rotation about the smallest moment) and one about the largest.
  const system::Scene hlw = testing::shipped_scene("free_body_hlw");
  const system::Scene other = experiments::parse_scene(
      "name = \"f\"\n[body]\ninertia = [3.0, 2.0, 1.2]\n[initial]\nangular_momentum = [1.0, 0.4, 0.3]\n", "f.toml");
  for (const system::Scene* scene : {&hlw, &other}) {
    int around = 0;
    const double exact = free_body_frequency(scene->inertia.diagonal(), scene->initial.Pi, around);
    std::vector<std::string> names;
    for (int k = 0; k < 3; ++k)
      if (k != around) names.push_back("angular_momentum_" + std::to_string(k + 1));
    const fq::SampledRun r = run(*scene, "exact", 0.02, 600.0, names);
    for (std::size_t k = 0; k < 2; ++k) {
      const fq::NaffResult n = fq::naff_real(r.series[k], r.output_dt, {3, 2});
      if (testing::verbose()) std::cout << scene->file << " " << names[k] << ": " << n.terms[0].frequency << " vs " << exact << ", relative "
                              << relative(n.terms[0].frequency, exact) << '\n';
      CHECK(relative(n.terms[0].frequency, exact) < 1e-10);
    }
  }
}

TEST_CASE("NAFF's nutation frequency of the Lagrange top is the closed form's to 1e-9", "[frequencies]") {
  const system::Scene scene = testing::shipped_scene("lagrange_top_cigar");
  const system::State& x = scene.initial;
  const lie::Vec3 gamma = x.R.row(2).transpose();
  const experiments::LagrangeBody body{scene.inertia(0, 0), scene.inertia(2, 2), 1.0};  // m g χ3 = 1
  const double l = x.Pi.dot(gamma), h = 0.5 * x.Pi.dot(scene.inertia.inverse() * x.Pi) + body.w * gamma.z();
  const auto closed = experiments::lagrange_actions(body, l, x.Pi.z(), h);
  REQUIRE(closed);
  const fq::SampledRun r = run(scene, "split-symmetric@kahan-li8", 0.01, 300.0, {"gamma_3", "gamma_1"});
  const fq::NaffResult nutation = fq::naff_real(r.series[0], r.output_dt, {3, 2});
  const double omega_theta = 2.0 * pi / closed->period;
  if (testing::verbose()) std::cout << "nutation: " << nutation.terms[0].frequency << " vs " << omega_theta << ", relative "
                           << relative(nutation.terms[0].frequency, omega_theta) << '\n';
  CHECK(relative(nutation.terms[0].frequency, omega_theta) < 1e-9);
  CHECK(relative(closed->frequencies[2], omega_theta) < 1e-12);
  // γ1 = sin θ sin φ: its lines are |m ω_φ + n ω_θ| (∂H/∂I of `lgi actions`; ω_ψ is invisible in the body frame).
  const fq::NaffResult spin = fq::naff_real(r.series[1], r.output_dt, {4, 2});
  for (std::size_t k = 0; k < 2; ++k)
    CHECK(combination_distance(spin.terms[k].frequency, closed->frequencies[1], omega_theta) <
          1e-8 * closed->frequencies[1]);
}

TEST_CASE("NAFF's lines on the Euler top are combinations of the closed-form dH/dI", "[frequencies]") {
  const system::Scene scene = testing::shipped_scene("free_body_hlw");
  const auto closed = experiments::euler_actions(scene.inertia.diagonal(), scene.initial.Pi,
                                                 scene.initial.Pi.dot(scene.initial.R.row(2).transpose()));
  REQUIRE(closed);
  const double omega_g = closed->frequencies[1], omega_l = closed->frequencies[2];
  const fq::SampledRun r = run(scene, "exact", 0.02, 600.0, {"angular_momentum_1", "gamma_1", "gamma_3"});
  CHECK(relative(fq::naff_real(r.series[0], r.output_dt, {2, 2}).terms[0].frequency, std::abs(omega_l)) < 1e-10);
  for (std::size_t s = 1; s < 3; ++s) {
    const fq::NaffResult n = fq::naff_real(r.series[s], r.output_dt, {3, 2});
    for (std::size_t k = 0; k < 2; ++k) {
      if (testing::verbose()) std::cout << "gamma line " << n.terms[k].frequency << " amplitude " << n.terms[k].amplitude << '\n';
      CHECK(combination_distance(n.terms[k].frequency, omega_g, omega_l) < 1e-9 * omega_g);
    }
  }
}

TEST_CASE("NAFF's lines on the Kovalevskaya top are combinations of the numerical torus's dH/dI", "[frequencies]") {
  // `lgi actions`' numerical torus (docs/actions.md §3): ω_a = 2πρ/(kT̄), ω_b = 2π/(kT̄) of the reduced 2-torus.
  const system::Scene scene = testing::shipped_scene("kovalevskaya");
  const experiments::NumericalTorus torus = experiments::numerical_torus(scene, scene.initial, {});
  REQUIRE(torus.ok);
  const double wa = std::abs(torus.omega_a), wb = std::abs(torus.omega_b);
  const fq::SampledRun r = run(scene, "split-symmetric@kahan-li8", 0.01, 1000.0, {"gamma_3", "angular_momentum_3"});
  for (std::size_t s = 0; s < 2; ++s) {
    const fq::NaffResult n = fq::naff_real(r.series[s], r.output_dt, {5, 2});
    if (testing::verbose())
      std::cout << "Kovalevskaya leading " << n.terms[0].frequency << " vs omega_b " << wb << ", relative "
                << relative(n.terms[0].frequency, wb) << '\n';
    CHECK(relative(n.terms[0].frequency, wb) < 1e-8);  // measured: 2.8e-11 (γ3), 2.0e-9 (Π3)
    for (std::size_t k = 1; k < 4; ++k) CHECK(combination_distance(n.terms[k].frequency, wa, wb) < 1e-6 * wb);
  }
}

}  // namespace test_frequencies
