// Poisson, GOE and GUE reference statistics (reference_curves.hpp).
#include "experiments/analysis/spectral/reference_curves.hpp"

#include <cmath>
#include <numbers>

#include "experiments/analysis/spectral/special_functions.hpp"

namespace lgi::experiments::spectral {

using std::numbers::pi;

double poisson_spacing_density(double s) { return s < 0 ? 0.0 : std::exp(-s); }
double poisson_number_variance(double length) { return length; }
double poisson_rigidity(double length) { return length / 15.0; }

double wigner_spacing_density(double s) { return s < 0 ? 0.0 : 0.5 * pi * s * std::exp(-0.25 * pi * s * s); }

double goe_number_variance(double length) {
  if (!(length > 0)) return length == 0 ? 0.0 : NAN;
  const double si1 = sine_integral(pi * length), si2 = sine_integral(2 * pi * length);
  return 2.0 / (pi * pi) *
         (std::log(2 * pi * length) + std::numbers::egamma + 1.0 + 0.5 * si1 * si1 - 0.5 * pi * si1 -
          std::cos(2 * pi * length) - cosine_integral(2 * pi * length) + pi * pi * length * (1.0 - 2.0 / pi * si2));
}

double rigidity_from_number_variance(double length, double (*sigma2)(double)) {
  if (!(length > 0)) return NAN;
  static constexpr double x[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                                  0.9061798459386640};
  static constexpr double w[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                                  0.2369268850561891};
  const int panels = static_cast<int>(std::ceil(8.0 * length));
  const double h = length / panels, l2 = length * length, l3 = l2 * length;
  double sum = 0.0;
  for (int p = 0; p < panels; ++p) {
    const double mid = (p + 0.5) * h;
    for (int q = 0; q < 5; ++q) {
      const double r = mid + 0.5 * h * x[q];
      sum += 0.5 * h * w[q] * (l3 - 2.0 * l2 * r + r * r * r) * sigma2(r);
    }
  }
  return 2.0 * sum / (l2 * l2);
}

double goe_rigidity(double length) { return rigidity_from_number_variance(length, goe_number_variance); }

double gue_spacing_density(double s) { return s < 0 ? 0.0 : 32.0 / (pi * pi) * s * s * std::exp(-4.0 * s * s / pi); }

double gue_number_variance(double length) {
  if (!(length > 0)) return length == 0 ? 0.0 : NAN;
  const double x = 2 * pi * length;
  return (std::log(x) + std::numbers::egamma + 1.0 - std::cos(x) - cosine_integral(x)) / (pi * pi) +
         length * (1.0 - 2.0 / pi * sine_integral(x));
}

double gue_rigidity(double length) { return rigidity_from_number_variance(length, gue_number_variance); }

}  // namespace lgi::experiments::spectral
