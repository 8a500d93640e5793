// GALI_k (experiments/analysis/gali.hpp, experiments/INDICATORS.md):
//  - the volume of the first k columns (product of singular values) on
//    matrices whose volume is known, and against √det(VᵀV);
//  - the sample times (the loop's own doubles, T last);
//  - the laws of Skokos, Bountis & Antonopoulos (2007, 2008) in the full
//    tangent space ℝ⁶ (N = 3): on the Lagrange top's 3-tori GALI_2, GALI_3
//    stay and GALI_4, 5, 6 fall as t^−2, t^−4, t^−6; on the free body's
//    2-tori GALI_3 falls as t^−1 (and 4, 5, 6 as t^−2, t^−4, t^−6);
//  - on a chaotic orbit of Richter's top and of the tilted Cardan Euler top,
//    GALI_2 falls like e^{−(λ₁−λ₂)t}, λ from the Gram–Schmidt spectrum over
//    the same window;
//  - the Cardan tangent flow's block step is the single-vector step, bit for bit.
#include <catch2/catch.hpp>

#include <Eigen/LU>
#include <cmath>
#include <vector>

#include "experiments/analysis/chaos_indicators.hpp"
#include "experiments/analysis/gali.hpp"
#include "experiments/analysis/tangent_loops.hpp"
#include "experiments/io/scene_suspension.hpp"
#include "integrators/core/torus_tangent_flow.hpp"
#include "support/shipped_scene.hpp"

namespace test_gali {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
using integrators::Mat6;

namespace {

/// The least-squares slope of y against x over the points where keep(i).
template <class Keep>
double slope(const std::vector<double>& x, const std::vector<double>& y, Keep keep) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!keep(i)) continue;
    n += 1, sx += x[i], sy += y[i], sxx += x[i] * x[i], sxy += x[i] * y[i];
  }
  REQUIRE(n >= 5);
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

/// The power-law exponents of GALI_2 … GALI_6 over t ≥ t_from (log-spaced samples).
std::vector<double> power_laws(const system::Scene& scene, double t_end, double t_from) {
  experiments::IndicatorSettings s;
  s.t_end = t_end, s.dt = 0.01, s.seed = 3, s.gali = true;
  const experiments::GaliCurves c = experiments::gali_curves(scene, scene.initial, s, 0);
  std::vector<double> lt, out;
  for (const double t : c.t) lt.push_back(std::log10(t));
  for (std::size_t k = 0; k < 5; ++k) {
    std::vector<double> g;
    for (const auto& v : c.log10_gali) g.push_back(v[k]);
    out.push_back(slope(lt, g, [&](std::size_t i) { return c.t[i] >= t_from; }));
  }
  return out;
}

/// The exponential rate of GALI_2 (ln units) where 1e-12 < GALI_2 < 1e-1, and the
/// window's end (linear samples).
std::pair<double, double> gali2_rate(const experiments::GaliCurves& c) {
  std::vector<double> g, t;
  double end = 0.0;
  for (std::size_t i = 0; i < c.t.size(); ++i) {
    g.push_back(c.log10_gali[i][0]), t.push_back(c.t[i]);
    if (g.back() > -12.0) end = c.t[i];
  }
  const double r = slope(t, g, [&](std::size_t i) { return g[i] < -1.0 && g[i] > -12.0 && t[i] <= end; });
  return {-r * std::log(10.0), end};
}

}  // namespace

TEST_CASE("GALI_k is the volume of the first k columns", "[gali]") {
  CHECK(experiments::log10_gali(Mat6::Identity())[4] == Approx(0.0).margin(1e-14));
  const double theta = 0.3;
  Mat6 V = Mat6::Identity();
  V.col(1) = std::cos(theta) * V.col(0) + std::sin(theta) * V.col(1);
  for (const double g : experiments::log10_gali(V)) CHECK(g == Approx(std::log10(std::sin(theta))).epsilon(1e-13));
  Mat6 W = experiments::initial_deviation_vectors(7, 11);
  for (int c = 0; c < 6; ++c) W.col(c).normalize();
  const experiments::GaliValues g = experiments::log10_gali(W);
  for (int k = 2; k <= 6; ++k) {
    const Eigen::MatrixXd B = W.leftCols(k);
    const double gram = 0.5 * std::log10((B.transpose() * B).determinant());
    CHECK(g[static_cast<std::size_t>(k - 2)] == Approx(gram).margin(1e-12));
  }
  CHECK(experiments::initial_deviation_vectors(7, 11) == experiments::initial_deviation_vectors(7, 11));
  CHECK(experiments::initial_deviation_vectors(7, 11) != experiments::initial_deviation_vectors(7, 12));
}

TEST_CASE("GALI sample times are steps' ends, increasing, T last", "[gali]") {
  for (const bool log_spacing : {true, false}) {
    const auto targets = experiments::gali_targets(10.0, 0.03, {50, log_spacing});
    const auto times = experiments::gali_times(targets, 10.0, 0.03);
    CHECK(times.back() == 10.0);
    for (std::size_t i = 1; i < times.size(); ++i) CHECK(times[i] > times[i - 1]);
    CHECK(times.size() <= 50);
    if (!log_spacing) CHECK(times.size() == 50);
  }
  CHECK(experiments::gali_targets(1.0, 2.0, {50, true}) == std::vector<double>{1.0});
}

TEST_CASE("GALI on the Lagrange top's 3-tori: constant for k <= 3, t^-2(k-3) above", "[gali]") {
  const auto p = power_laws(testing::shipped_scene("lagrange_top_cigar"), 1000.0, 50.0);
  INFO("slopes " << p[0] << " " << p[1] << " " << p[2] << " " << p[3] << " " << p[4]);
  CHECK(std::abs(p[0]) < 0.25);
  CHECK(std::abs(p[1]) < 0.25);
  CHECK(p[2] == Approx(-2.0).margin(0.25));
  CHECK(p[3] == Approx(-4.0).margin(0.25));
  CHECK(p[4] == Approx(-6.0).margin(0.25));
}

TEST_CASE("GALI on the free body's 2-tori: GALI_3 falls as 1/t", "[gali]") {
  const auto p = power_laws(testing::shipped_scene("free_body_hlw"), 1000.0, 50.0);
  INFO("slopes " << p[0] << " " << p[1] << " " << p[2] << " " << p[3] << " " << p[4]);
  CHECK(std::abs(p[0]) < 0.25);
  CHECK(p[1] == Approx(-1.0).margin(0.25));
  CHECK(p[2] == Approx(-2.0).margin(0.25));
  CHECK(p[3] == Approx(-4.0).margin(0.25));
  CHECK(p[4] == Approx(-6.0).margin(0.25));
}

TEST_CASE("GALI_2 on a chaotic orbit of Richter's top falls like exp(-(l1 - l2) t)", "[gali]") {
  const system::Scene scene = testing::shipped_scene("general_top_richter");
  for (const std::uint64_t seed : {0u, 1u, 2u}) {
    experiments::IndicatorSettings s;
    s.t_end = 200.0, s.dt = 0.01, s.seed = seed, s.gali = true, s.gali_sampling = {100, false};
    const auto [rate, end] = gali2_rate(experiments::gali_curves(scene, scene.initial, s, 0));
    const auto l = experiments::lyapunov_spectrum(scene, scene.initial, end, s.dt);
    INFO("seed " << seed << ": GALI_2 rate " << rate << " over [0, " << end << "], l1 - l2 = " << l[0] - l[1]);
    CHECK(rate == Approx(l[0] - l[1]).epsilon(0.25));
  }
}

TEST_CASE("GALI_2 on the tilted Cardan Euler top (T^3 x R^3) falls like exp(-(l1 - l2) t)", "[gali]") {
  const system::Scene scene = testing::shipped_scene("cardan_euler_tilted");
  experiments::IndicatorSettings s;
  s.t_end = 70.0, s.dt = 0.01, s.seed = 0, s.gali = true, s.spectrum = false, s.gali_sampling = {70, false};
  const auto [rate, end] = gali2_rate(experiments::cardan_gali_curves(scene, scene.cardan_initial, s, 0));
  s.t_end = end, s.gali = false, s.spectrum = true;
  const auto r = experiments::cardan_state_indicators(scene, scene.cardan_initial, s, 0);
  INFO("GALI_2 rate " << rate << " over [0, " << end << "], l1 - l2 = " << r.spectrum[0] - r.spectrum[1]);
  CHECK(rate == Approx(r.spectrum[0] - r.spectrum[1]).epsilon(0.25));
}

TEST_CASE("the Cardan tangent flow's six-vector step is six single steps, bit for bit", "[gali]") {
  const system::Scene scene = testing::shipped_scene("cardan_euler_tilted");
  const system::CardanTop top = experiments::cardan_top(scene);
  const Mat6 V0 = experiments::initial_deviation_vectors(1, 2);
  system::Vec6 x = system::stack(scene.cardan_initial);
  Mat6 V = V0;
  for (int i = 0; i < 10; ++i) integrators::torus::torus_tangent_step(top, x, V, 0.01);
  for (int c = 0; c < 6; ++c) {
    system::Vec6 y = system::stack(scene.cardan_initial), v = V0.col(c);
    for (int i = 0; i < 10; ++i) integrators::torus::torus_tangent_step(top, y, v, 0.01);
    CHECK(y == x);
    CHECK(v == system::Vec6(V.col(c)));
  }
}

}  // namespace test_gali
