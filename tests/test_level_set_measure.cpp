// The level-set draw (experiments/analysis/level_set_draw.hpp, docs/atlas.md §6)
// and the Wilson interval of a chaotic fraction (analysis/binomial_interval.hpp):
//  - every draw lies on {H = h, Π·Γ = l, |Γ| = 1} to round-off, for both measures;
//  - the Γ marginal of the Liouville draw is the density (ΓᵀJΓ)^(−1/2) on the
//    accessible region, the uniform draw's is uniform (chi-square against a
//    quadrature of the densities on a Fibonacci lattice), and each fails the
//    other's density: the test tells them apart;
//  - the Wilson interval's ends are the roots of (k − np)² = z² np(1 − p).
// The flow invariance of the Liouville draw (and the drift of the uniform
// one) is tested on whole orbits in tests/commands/test_liouville.py.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <vector>

#include "experiments/analysis/binomial_interval.hpp"
#include "experiments/analysis/level_set_draw.hpp"
#include "support/shipped_scene.hpp"

namespace test_level_set_measure {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
using experiments::LevelMeasure;
using lie::Vec3;

namespace {

constexpr double h = 2.0, l = 2.2;  // Richter's top, the level of experiments/CHAOS_MAP.md's measured fractions
constexpr int bins = 10;

int bin_of(const Vec3& gamma) { return std::min(bins - 1, static_cast<int>((gamma.z() + 1.0) * 0.5 * bins)); }

/// The law of Γ3 in `bins` equal bins under the density (uniform or Liouville)
/// on the accessible region: a quadrature on 400000 points of a Fibonacci lattice.
std::vector<double> expected_bins(const experiments::LevelSetBody& b, LevelMeasure m) {
  constexpr int n = 400000;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  std::vector<double> p(bins, 0.0);
  double total = 0.0;
  for (int k = 0; k < n; ++k) {
    const double z = 1.0 - (2.0 * k + 1.0) / n, r = std::sqrt(1.0 - z * z);
    const Vec3 g(r * std::cos(golden * k), r * std::sin(golden * k), z);
    const double liouville = experiments::liouville_gamma_density(b, h, l, g);
    const double w = m == LevelMeasure::liouville ? liouville : (liouville > 0.0 ? 1.0 : 0.0);
    p[static_cast<std::size_t>(bin_of(g))] += w, total += w;
  }
  for (double& x : p) x /= total;
  return p;
}

/// Chi-square of the Γ3 histogram of `draws` against the law `p` (bins with an expected count of at least 5).
double chi_square(const std::vector<Vec3>& draws, const std::vector<double>& p) {
  std::vector<double> count(bins, 0.0);
  for (const Vec3& g : draws) count[static_cast<std::size_t>(bin_of(g))] += 1.0;
  double chi2 = 0.0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    const double e = p[k] * static_cast<double>(draws.size());
    if (e >= 5.0) chi2 += (count[k] - e) * (count[k] - e) / e;
  }
  return chi2;
}

std::vector<Vec3> draw_gammas(const experiments::LevelSetBody& b, LevelMeasure m, int n) {
  std::vector<Vec3> out;
  for (int i = 0; i < n; ++i) {
    experiments::CounterRng rng(7, i, 1u << 20);
    Vec3 gamma, Pi;
    REQUIRE(experiments::draw_level_point(b, h, l, m, rng, gamma, Pi));
    out.push_back(gamma);
  }
  return out;
}

}  // namespace

TEST_CASE("level-set draws lie on the level set, for both measures", "[level_set]") {
  const system::Scene scene = testing::shipped_scene("general_top_richter");
  const experiments::LevelSetBody b = experiments::level_set_body(scene);
  CHECK(b.j_min == Approx(1.0).epsilon(1e-14));
  for (const LevelMeasure m : {LevelMeasure::liouville, LevelMeasure::uniform}) {
    for (int i = 0; i < 500; ++i) {
      experiments::CounterRng rng(3, i, 1u << 20);
      Vec3 gamma, Pi;
      REQUIRE(experiments::draw_level_point(b, h, l, m, rng, gamma, Pi));
      const double H = 0.5 * Pi.dot(b.J_inv * Pi) + b.weight.dot(gamma);
      CHECK(std::abs(H - h) < 1e-13 * 4.0);
      CHECK(std::abs(Pi.dot(gamma) - l) < 1e-13 * 4.0);
      CHECK(std::abs(gamma.norm() - 1.0) < 1e-15 * 4.0);
      // A function of (seed, index) alone.
      experiments::CounterRng again(3, i, 1u << 20);
      Vec3 gamma2, Pi2;
      REQUIRE(experiments::draw_level_point(b, h, l, m, again, gamma2, Pi2));
      CHECK((gamma2 == gamma && Pi2 == Pi));
    }
  }
}

TEST_CASE("the Liouville draw has the density (Gamma^T J Gamma)^(-1/2) in Gamma, the uniform draw a flat one",
          "[level_set]") {
  const experiments::LevelSetBody b = experiments::level_set_body(testing::shipped_scene("general_top_richter"));
  const std::vector<double> p_liouville = expected_bins(b, LevelMeasure::liouville),
                            p_uniform = expected_bins(b, LevelMeasure::uniform);
  const std::vector<Vec3> liouville = draw_gammas(b, LevelMeasure::liouville, 20000),
                          uniform = draw_gammas(b, LevelMeasure::uniform, 20000);
  // At most 9 degrees of freedom: 27.9 is the 0.999 quantile of chi-square(9).
  CHECK(chi_square(liouville, p_liouville) < 27.9);
  CHECK(chi_square(uniform, p_uniform) < 27.9);
  CHECK(chi_square(liouville, p_uniform) > 50.0);
  CHECK(chi_square(uniform, p_liouville) > 50.0);
}

TEST_CASE("the Wilson interval's ends are the roots of (k - np)^2 = z^2 n p (1 - p)", "[level_set]") {
  // The roots, from the quadratic (n² + z²n) p² − (2kn + z²n) p + k² = 0 (numpy.roots).
  const struct {
    std::int64_t k, n;
    double low, high;
  } cases[] = {{7, 10, 0.39677814746114526, 0.892208732593699},
               {0, 20, 0.0, 0.16112515805281935},
               {140, 200, 0.6332093162728074, 0.7592525531762859},
               {172, 200, 0.805101191342927, 0.9013301736654407}};
  for (const auto& c : cases) {
    const experiments::BinomialInterval w = experiments::wilson_interval(c.k, c.n);
    CHECK(w.fraction == static_cast<double>(c.k) / static_cast<double>(c.n));
    CHECK(w.low == Approx(c.low).margin(1e-13));
    CHECK(w.high == Approx(c.high).margin(1e-13));
  }
  CHECK(experiments::wilson_interval(5, 5).high == 1.0);
  CHECK(std::isnan(experiments::wilson_interval(0, 0).fraction));
  CHECK(experiments::format_fraction(140, 200) == "140/200 = 0.700 [0.633, 0.759]");
}

}  // namespace test_level_set_measure
