// controller_math.hpp: ln and exp for the pairs' step-size controller, from
// IEEE + − × ÷ only, to the 1e-9 its header states, over the whole range the
// controller can meet (err from the subnormals to 1e300, exponents from −745
// to 709), and the special values a controller can be handed. That the pairs'
// runs are then the same bits on either of glibc's code paths is
// tests/commands/test_libm_paths.py.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "integrators/core/controller_math.hpp"

namespace test_controller_math {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

namespace cm = lgi::integrators::controller_math;

TEST_CASE("controller_math::log is within 1e-9 of libm's, subnormals included", "[controller]") {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> exponent(-744.0, 709.0), near_one(0.5, 2.0);
  double worst = 0.0;  // |Δ ln x| / max(1, |ln x|)
  for (int i = 0; i < 200000; ++i) {
    const double x = i % 2 ? std::exp(exponent(rng)) : near_one(rng);
    const double exact = std::log(x);
    worst = std::max(worst, std::abs(cm::log(x) - exact) / std::max(1.0, std::abs(exact)));
  }
  CHECK(worst <= 1e-9);
  CHECK(worst > 0.0);  // the short series, not libm (a test of the test)
  CHECK(cm::log(1.0) == 0.0);
  CHECK(cm::log(std::numeric_limits<double>::denorm_min()) == Approx(std::log(4.9406564584124654e-324)));
  CHECK(cm::log(0.0) == -std::numeric_limits<double>::infinity());
  CHECK(std::isnan(cm::log(-1.0)));
  CHECK(std::isnan(cm::log(std::numeric_limits<double>::quiet_NaN())));
  CHECK(cm::log(std::numeric_limits<double>::infinity()) == std::numeric_limits<double>::infinity());
}

TEST_CASE("controller_math::exp is within 1e-9 of libm's, to overflow and into the subnormals", "[controller]") {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> wide(-745.0, 709.7), narrow(-3.0, 3.0);
  double worst = 0.0;  // relative, where e^y is normal
  for (int i = 0; i < 200000; ++i) {
    const double y = i % 2 ? wide(rng) : narrow(rng);
    const double libm = std::exp(y);
    // Below e^−708 the result is subnormal: its absolute error is what counts.
    if (libm < std::numeric_limits<double>::min()) CHECK(std::abs(cm::exp(y) - libm) <= 1e-9 * 2.3e-308);
    else worst = std::max(worst, std::abs(cm::exp(y) - libm) / libm);
  }
  CHECK(worst <= 1e-9);
  CHECK(cm::exp(0.0) == 1.0);
  CHECK(cm::exp(710.0) == std::numeric_limits<double>::infinity());
  CHECK(cm::exp(-800.0) == 0.0);
  CHECK(cm::exp(-std::numeric_limits<double>::infinity()) == 0.0);
  CHECK(std::isnan(cm::exp(std::numeric_limits<double>::quiet_NaN())));
  CHECK(cm::pow(1e-10, 1.0 / 8.0) == Approx(std::pow(1e-10, 1.0 / 8.0)).epsilon(1e-9));
}

}  // namespace test_controller_math
