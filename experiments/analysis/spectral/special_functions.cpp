// Digamma, trigamma, Si and Ci (special_functions.hpp).
#include "experiments/analysis/spectral/special_functions.hpp"

#include <cmath>
#include <complex>
#include <numbers>

namespace lgi::experiments::spectral {
namespace {

// Below this argument Si and Ci come from their power series (A&S 5.2.14, 5.2.16),
// whose terms stay below e^4, so no digit is lost; above it from E1(ix)'s continued
// fraction (A&S 5.1.22), which converges in a few tens of terms there.
constexpr double kSeriesLimit = 4.0;

// E1(z) for Re z >= 0, |z| >= kSeriesLimit: the even contraction of A&S 5.1.22,
// E1(z) = e^{-z} / (z + 1 - 1²/(z + 3 - 2²/(z + 5 - ...))), by Lentz's method.
std::complex<double> exponential_integral_cf(std::complex<double> z) {
  using C = std::complex<double>;
  constexpr double tiny = 1e-300;
  C b = z + 1.0, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 1000; ++i) {
    const double a = -static_cast<double>(i) * static_cast<double>(i);
    b += 2.0;
    d = a * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + a / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const C del = c * d;
    h *= del;
    if (std::abs(del - 1.0) < 1e-16) break;
  }
  return h * std::exp(-z);
}

}  // namespace

double digamma(double x) {
  // Recurrence ψ(x) = ψ(x + 1) − 1/x up to x >= 10, then the asymptotic series (A&S 6.3.18).
  double shift = 0.0;
  while (x < 10.0) {
    shift -= 1.0 / x;
    x += 1.0;
  }
  const double r = 1.0 / (x * x);
  return shift + std::log(x) - 0.5 / x -
         r * (1.0 / 12 - r * (1.0 / 120 - r * (1.0 / 252 - r * (1.0 / 240 - r * (1.0 / 132)))));
}

double trigamma(double x) {
  // Recurrence ψ'(x) = ψ'(x + 1) + 1/x² up to x >= 10, then A&S 6.4.12.
  double shift = 0.0;
  while (x < 10.0) {
    shift += 1.0 / (x * x);
    x += 1.0;
  }
  const double r = 1.0 / (x * x);
  return shift + 1.0 / x + 0.5 * r +
         r / x * (1.0 / 6 - r * (1.0 / 30 - r * (1.0 / 42 - r * (1.0 / 30 - r * (5.0 / 66)))));
}

double sine_integral(double x) {
  const double ax = std::fabs(x);
  double si;
  if (ax < kSeriesLimit) {
    // Si(x) = Σ (−1)^k x^{2k+1} / ((2k+1)(2k+1)!)
    double term = ax, sum = ax;
    for (int k = 1; k < 60; ++k) {
      const double kk = static_cast<double>(k);
      term *= -ax * ax / ((2 * kk) * (2 * kk + 1));
      const double add = term / (2 * kk + 1);
      sum += add;
      if (std::fabs(add) < 1e-17 * std::fabs(sum)) break;
    }
    si = sum;
  } else {
    // E1(ix) = −Ci(x) + i (Si(x) − π/2) (A&S 5.2.23)
    si = std::numbers::pi / 2 + exponential_integral_cf({0.0, ax}).imag();
  }
  return x < 0 ? -si : si;
}

double cosine_integral(double x) {
  if (!(x > 0)) return std::nan("");
  if (x < kSeriesLimit) {
    // Ci(x) = γ + ln x + Σ (−1)^k x^{2k} / (2k (2k)!)
    double term = 1.0, sum = 0.0;
    for (int k = 1; k < 60; ++k) {
      const double kk = static_cast<double>(k);
      term *= -x * x / ((2 * kk - 1) * (2 * kk));
      const double add = term / (2 * kk);
      sum += add;
      if (std::fabs(add) < 1e-17 * (std::fabs(sum) + 1e-300)) break;
    }
    return std::numbers::egamma + std::log(x) + sum;
  }
  return -exponential_integral_cf({0.0, x}).real();
}

}  // namespace lgi::experiments::spectral
