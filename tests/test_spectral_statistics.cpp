// The spectral statistics unit (experiments/analysis/spectral/,
// docs/spectral_statistics.md) on spectra whose statistics are known exactly:
//  - ψ, ψ', Si and Ci against tabulated values (A&S; scipy.special to 16 digits),
//    both branches of Si and Ci meeting at x = 4;
//  - the Brody density: normalised with mean 1 for every β, Poisson at β = 0 and
//    Wigner at β = 1; the likelihood's slope and curvature are its derivatives;
//    the ML estimate recovers β from Brody samples and stops at its bounds;
//  - Δ₃ of one window in closed form against a brute-force least-squares fit;
//  - a picket fence: Σ²(L) = 0 at integer L, Δ₃(L) = 1/12 − 1/(60 L²) at integer L;
//  - Pandey's relation turns Σ² = L into Δ₃ = L/15; GOE Σ² and Δ₃ against
//    values computed independently (scipy quad of the same formulas);
//  - unfolding by a staircase fit and by a counting function, and the bad input.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <vector>

#include "experiments/analysis/seeded_random.hpp"
#include "experiments/analysis/spectral/brody_fit.hpp"
#include "experiments/analysis/spectral/number_variance.hpp"
#include "experiments/analysis/spectral/reference_curves.hpp"
#include "experiments/analysis/spectral/spacings.hpp"
#include "experiments/analysis/spectral/special_functions.hpp"
#include "experiments/analysis/spectral/spectral_rigidity.hpp"
#include "experiments/analysis/spectral/spectral_statistics.hpp"
#include "experiments/analysis/spectral/unfolding.hpp"
#include "experiments/errors/input_error.hpp"

namespace test_spectral_statistics {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi::experiments;
using namespace lgi::experiments::spectral;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;
using std::numbers::pi;

TEST_CASE("digamma, trigamma, Si and Ci agree with tabulated values", "[spectral]") {
  const double g = std::numbers::egamma;
  CHECK_THAT(digamma(1.0), WithinAbs(-g, 1e-13));
  CHECK_THAT(digamma(2.0), WithinAbs(1.0 - g, 1e-13));
  CHECK_THAT(digamma(0.5), WithinAbs(-g - 2.0 * std::log(2.0), 1e-13));
  CHECK_THAT(digamma(1.5), WithinAbs(0.03648997397857652, 1e-13));
  CHECK_THAT(trigamma(1.0), WithinRel(pi * pi / 6, 1e-13));
  CHECK_THAT(trigamma(1.5), WithinRel(pi * pi / 2 - 4.0, 1e-13));
  CHECK_THAT(trigamma(0.5), WithinRel(pi * pi / 2, 1e-13));
  CHECK_THAT(sine_integral(1.0), WithinAbs(0.9460830703671831, 1e-14));
  CHECK_THAT(sine_integral(-1.0), WithinAbs(-0.9460830703671831, 1e-14));
  CHECK_THAT(sine_integral(10.0), WithinAbs(1.658347594218874, 1e-14));
  CHECK_THAT(sine_integral(100.0), WithinAbs(1.5622254668890563, 1e-14));
  CHECK_THAT(cosine_integral(1.0), WithinAbs(0.33740392290096816, 1e-14));
  CHECK_THAT(cosine_integral(10.0), WithinAbs(-0.04545643300445537, 1e-14));
  CHECK_THAT(cosine_integral(30.0), WithinAbs(-0.03303241728207114, 1e-14));
  // The series (below 4) and the continued fraction (from 4) meet.
  CHECK_THAT(sine_integral(3.9999), WithinAbs(1.7582220584308403, 1e-14));
  CHECK_THAT(sine_integral(4.0001), WithinAbs(1.7581842183061578, 1e-14));
  CHECK_THAT(cosine_integral(3.9999), WithinAbs(-0.14096535564615076, 1e-14));
  CHECK_THAT(cosine_integral(4.0001), WithinAbs(-0.14099803782717713, 1e-14));
}

TEST_CASE("the Brody density is normalised with mean 1, Poisson at beta 0 and Wigner at beta 1", "[spectral]") {
  for (double beta : {0.0, 0.3, 0.7, 1.0}) {
    double mass = 0.0, mean = 0.0;
    const double h = 1e-3;
    for (int i = 0; i < 20000; ++i) {  // midpoint rule on [0, 20]
      const double s = (i + 0.5) * h, p = brody_density(s, beta);
      mass += p * h;
      mean += s * p * h;
    }
    CHECK_THAT(mass, WithinAbs(1.0, 1e-5));
    CHECK_THAT(mean, WithinAbs(1.0, 1e-5));
  }
  for (double s : {0.1, 0.5, 1.0, 2.5}) {
    CHECK_THAT(brody_density(s, 0.0), WithinRel(poisson_spacing_density(s), 1e-14));
    CHECK_THAT(brody_density(s, 1.0), WithinRel(wigner_spacing_density(s), 1e-14));
  }
}

namespace {

// n spacings drawn from the Brody law by inverting its distribution function
// F(s) = 1 − exp(−b s^{β+1}).
std::vector<double> brody_sample(double beta, int n, std::uint64_t seed) {
  const double c = beta + 1.0, b = std::pow(std::tgamma((beta + 2.0) / c), c);
  CounterRng rng(seed, 0, 1);
  std::vector<double> s(static_cast<std::size_t>(n));
  for (double& v : s) v = std::pow(-std::log(1.0 - rng.uniform()) / b, 1.0 / c);
  return s;
}

}  // namespace

TEST_CASE("the Brody log-likelihood's slope and curvature are its derivatives", "[spectral]") {
  const std::vector<double> s = brody_sample(0.4, 500, 7);
  for (double beta : {0.0, 0.2, 0.5, 0.9}) {
    const double h = 1e-4;
    const BrodyLikelihood at = brody_log_likelihood(s, beta), up = brody_log_likelihood(s, beta + h),
                          down = brody_log_likelihood(s, beta - h);
    CHECK_THAT(at.slope, WithinAbs((up.value - down.value) / (2 * h), 1e-5 * std::fabs(at.curvature)));
    CHECK_THAT(at.curvature, WithinRel((up.slope - down.slope) / (2 * h), 1e-6));
    CHECK(at.curvature < 0);
  }
}

TEST_CASE("the ML Brody estimate recovers beta within its standard error and stops at its bounds", "[spectral]") {
  // 2000 spacings: the standard error is about 0.02; 3 standard errors allowed.
  for (double beta : {0.25, 0.5, 0.8}) {
    const BrodyFit fit = fit_brody(brody_sample(beta, 2000, 11));
    INFO("beta " << beta << " fit " << fit.beta << " +- " << fit.standard_error);
    CHECK(fit.bound == 0);
    CHECK(fit.standard_error > 0.01);
    CHECK(fit.standard_error < 0.04);
    CHECK(std::fabs(fit.beta - beta) < 3 * fit.standard_error);
    CHECK(std::fabs(brody_log_likelihood(brody_sample(beta, 2000, 11), fit.beta).slope) < 1e-6);
  }
  // Equal spacings repel more than any Brody law: the slope is positive at 1.
  const BrodyFit rigid = fit_brody(std::vector<double>(50, 1.0));
  CHECK(rigid.bound == 1);
  CHECK(rigid.beta == 1.0);
  // A zero spacing has likelihood 0 for every beta > 0.
  std::vector<double> with_zero = brody_sample(0.8, 200, 3);
  with_zero[17] = 0.0;
  const BrodyFit zero = fit_brody(with_zero);
  CHECK(zero.bound == -1);
  CHECK(zero.beta == 0.0);
  CHECK(std::isfinite(zero.log_likelihood));
  // Clustered spacings (a mixture of very short and long ones) go below Poisson.
  std::vector<double> clustered;
  for (int i = 0; i < 100; ++i) clustered.push_back(i % 2 ? 1.98 : 0.02);
  CHECK(fit_brody(clustered).bound == -1);
  CHECK(std::isnan(fit_brody(std::vector<double>{1.0}).beta));
}

TEST_CASE("Delta3 of one window in closed form equals a brute-force least-squares fit", "[spectral]") {
  CounterRng rng(5, 0, 0);
  std::vector<double> x;
  double e = 0.0;
  for (int i = 0; i < 40; ++i) x.push_back(e += -std::log(1.0 - rng.uniform()));
  for (double start : {0.3, 4.1, 10.0}) {
    for (double length : {0.7, 3.0, 9.5}) {
      // Normal equations of min ∫ (N − Aξ − B)² on a fine midpoint grid.
      const int m = 200000;
      double s1 = 0, sx = 0, sxx = 0, sn = 0, sxn = 0, snn = 0;
      for (int k = 0; k < m; ++k) {
        const double xi = start + (k + 0.5) * length / m;
        double count = 0;
        for (double level : x) count += level <= xi ? 1.0 : 0.0;
        s1 += 1;
        sx += xi;
        sxx += xi * xi;
        sn += count;
        sxn += xi * count;
        snn += count * count;
      }
      const double det = s1 * sxx - sx * sx, a = (s1 * sxn - sx * sn) / det, b = (sxx * sn - sx * sxn) / det;
      const double brute = (snn - a * sxn - b * sn) / s1;
      CHECK_THAT(delta3_window(x, start, length), WithinAbs(brute, 2e-4));
    }
  }
}

TEST_CASE("a picket fence: Sigma2 = 0 at integer L, Delta3 = 1/12 - 1/(60 L^2) at integer L", "[spectral]") {
  std::vector<double> fence;
  for (int i = 0; i < 300; ++i) fence.push_back(i);
  for (int l : {1, 2, 3, 5, 10, 20}) {
    const double length = l;
    CHECK_THAT(number_variance(fence, length).value, WithinAbs(0.0, 1e-12));
    // Over a whole number of periods the phase t of the start is uniform; the best line's
    // slope differs from 1 by O(1/L²) (docs/spectral_statistics.md §4).
    CHECK_THAT(spectral_rigidity(fence, length).value, WithinAbs(1.0 / 12 - 1.0 / (60.0 * length * length), 1e-11));
  }
  // Between integers n takes two values: Σ² = f(1 − f), f the fractional part of L,
  // up to the end effect of starts over a range not a whole number of periods (O(1/N)).
  for (double length : {0.5, 2.25, 7.8}) {
    const double f = length - std::floor(length);
    CHECK_THAT(number_variance(fence, length).value, WithinAbs(f * (1 - f), 2.0 / 300));
  }
  // All spacings equal: ML at its upper bound; the histogram is one bin.
  const SpectralStatistics st = spectral_statistics(fence);
  CHECK(st.brody.bound == 1);
  CHECK(st.histogram.counts[10] == 299);
  CHECK_THAT(st.histogram.density[10], WithinRel(10.0, 1e-12));
}

TEST_CASE("reference curves: Pandey's relation, Poisson and GOE values", "[spectral]") {
  for (double length : {0.5, 3.0, 17.0})
    CHECK_THAT(rigidity_from_number_variance(length, poisson_number_variance),
               WithinRel(poisson_rigidity(length), 1e-12));
  // GOE values by scipy.integrate.quad of the same formulas with scipy.special.sici.
  CHECK_THAT(goe_number_variance(0.1), WithinRel(0.09054673855106311, 1e-10));
  CHECK_THAT(goe_number_variance(1.0), WithinRel(0.44633362426090667, 1e-12));
  CHECK_THAT(goe_number_variance(10.0), WithinRel(0.9086949209486089, 1e-12));
  CHECK_THAT(goe_rigidity(1.0), WithinRel(0.06054769843737199, 1e-9));
  CHECK_THAT(goe_rigidity(10.0), WithinRel(0.23569994663746266, 1e-9));
  CHECK_THAT(goe_rigidity(50.0), WithinRel(0.39140136235402645, 1e-9));
  // The asymptotic forms: (2/π²)(ln 2πL + γ + 1 − π²/8), (1/π²)(ln 2πL + γ − 5/4 − π²/8).
  const double g = std::numbers::egamma, big = 200.0;
  CHECK_THAT(goe_number_variance(big),
             WithinAbs(2 / (pi * pi) * (std::log(2 * pi * big) + g + 1 - pi * pi / 8), 1e-5));
  CHECK_THAT(goe_rigidity(big), WithinAbs((std::log(2 * pi * big) + g - 1.25 - pi * pi / 8) / (pi * pi), 1e-3));
}

TEST_CASE("unfolding: the staircase fit, a counting function, and bad input", "[spectral]") {
  // Levels E_i = √(i + 1/2): the staircase midpoints lie on N = E², a polynomial of degree 2.
  std::vector<double> levels;
  for (int i = 0; i < 100; ++i) levels.push_back(std::sqrt(i + 0.5));
  const StaircaseFit fit = fit_staircase(levels, 2);
  const std::vector<double> x = unfold(levels, fit);
  for (std::size_t i = 0; i < x.size(); ++i) CHECK_THAT(x[i], WithinAbs(static_cast<double>(i) + 0.5, 1e-9));
  const std::vector<double> by_weyl = unfold(levels, [](double e) { return e * e; });
  CHECK_THAT(by_weyl[42], WithinAbs(42.5, 1e-12));
  CHECK_THROWS_AS(unfold(std::vector<double>{1, 3, 2}, [](double e) { return e; }), InputError);
  CHECK_THROWS_AS(unfold(std::vector<double>{1, NAN}, [](double e) { return e; }), InputError);
  CHECK_THROWS_AS(unfold(std::vector<double>{1, 2, 3}, [](double e) { return -e; }), InputError);
  CHECK_THROWS_AS(fit_staircase(std::vector<double>{1, 2, 3}, 5), InputError);
  CHECK_THROWS_AS(nearest_spacings(std::vector<double>{1, 2}), InputError);
  CHECK_THROWS_AS(spacing_histogram(std::vector<double>{1, 2}, 0.0, 4.0), InputError);
  const std::vector<int> labels{0, 1};
  CHECK_THROWS_AS(statistics_by_class(std::vector<double>{1, 2, 3}, labels), InputError);
  const std::vector<int> three{0, 0, 0};
  CHECK_THROWS_AS(statistics_by_class(std::vector<double>{1, NAN, 3}, three), InputError);
  // A class with too few levels is kept, marked, with nothing computed.
  const std::vector<double> few{0.1, 0.5, 0.2, 0.9, 1.3, 1.7, 2.0, 2.2, 2.9, 3.3};
  const std::vector<int> few_labels{0, 0, 0, 0, 0, 0, 0, 0, 0, 1};
  StatisticsOptions options;
  options.fit_degree = 1;
  const std::vector<ClassStatistics> classes = statistics_by_class(few, few_labels, {}, options);
  REQUIRE(classes.size() == 2);
  CHECK_FALSE(classes[0].too_few);
  CHECK(classes[0].statistics.levels == 9);
  CHECK(classes[1].too_few);
  CHECK(classes[1].statistics.spacings.empty());
  // A fit that fails names the class.
  const std::vector<double> nine(few.begin(), few.end() - 1);  // degree 5 wiggles through these
  CHECK_THROWS_WITH(statistics_by_class(nine, std::vector<int>(nine.size(), 4)),
                    Catch::Contains("class 4: staircase fit: the polynomial of degree 5 decreases"));
}

TEST_CASE("reference curves: the GUE", "[spectral]") {
  // Σ²(L) against the direct integral L − 2∫(L − r) sinc²(r) dr (SciPy quad,
  // to 1e-13), its large-L asymptote, Δ₃'s asymptote, and the surmise's
  // normalisation and mean.
  CHECK_THAT(gue_number_variance(0.5), WithinRel(0.2801579363733302, 1e-12));
  CHECK_THAT(gue_number_variance(1.0), WithinRel(0.3441625935140381, 1e-12));
  CHECK_THAT(gue_number_variance(10.0), WithinRel(0.5792963359329928, 1e-11));
  const double p = std::numbers::pi, gamma = std::numbers::egamma;
  const double L = 200.0;
  CHECK(std::abs(gue_number_variance(L) - (std::log(2 * p * L) + gamma + 1.0) / (p * p)) < 1e-3);
  CHECK(std::abs(gue_rigidity(L) - (std::log(2 * p * L) + gamma - 1.25) / (2 * p * p)) < 1e-3);
  double norm = 0.0, mean = 0.0;
  for (int i = 0; i < 100000; ++i) {
    const double s = (i + 0.5) * 1e-4;
    norm += 1e-4 * gue_spacing_density(s), mean += 1e-4 * s * gue_spacing_density(s);
  }
  CHECK(norm == Approx(1.0).epsilon(1e-9));
  CHECK(mean == Approx(1.0).epsilon(1e-9));
}

}  // namespace test_spectral_statistics
