// Unfolding by a smooth counting function and the polynomial fit of the staircase (unfolding.hpp).
#include "experiments/analysis/spectral/unfolding.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <cstddef>

#include "experiments/errors/input_error.hpp"

namespace lgi::experiments::spectral {

double StaircaseFit::operator()(double energy) const {
  const double t = (energy - centre) / half_width;
  double sum = 0.0;  // Horner
  for (std::size_t k = coefficients.size(); k-- > 0;) sum = sum * t + coefficients[k];
  return sum;
}

void check_levels(std::span<const double> levels, const std::string& what) {
  for (std::size_t i = 0; i < levels.size(); ++i) {
    if (!std::isfinite(levels[i]))
      throw InputError(what + ": level " + std::to_string(i) + " is not a finite number");
    if (i > 0 && levels[i] < levels[i - 1])
      throw InputError(what + ": the levels are not sorted (level " + std::to_string(i) + " is below level " +
                       std::to_string(i - 1) + ")");
  }
}

StaircaseFit fit_staircase(std::span<const double> levels, int degree) {
  const std::string what = "staircase fit";
  check_levels(levels, what);
  if (degree < 1) throw InputError(what + ": the degree must be at least 1, not " + std::to_string(degree));
  const auto n = static_cast<Eigen::Index>(levels.size());
  if (n < degree + 2)
    throw InputError(what + ": " + std::to_string(n) + " levels are too few for a polynomial of degree " +
                     std::to_string(degree));
  StaircaseFit fit;
  fit.centre = 0.5 * (levels.front() + levels.back());
  fit.half_width = 0.5 * (levels.back() - levels.front());
  if (!(fit.half_width > 0)) throw InputError(what + ": all levels are equal");
  Eigen::MatrixXd a(n, degree + 1);
  Eigen::VectorXd y(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double t = (levels[static_cast<std::size_t>(i)] - fit.centre) / fit.half_width;
    double p = 1.0;
    for (int k = 0; k <= degree; ++k, p *= t) a(i, k) = p;
    y(i) = static_cast<double>(i) + 0.5;
  }
  const Eigen::VectorXd c = a.colPivHouseholderQr().solve(y);
  fit.coefficients.assign(c.data(), c.data() + c.size());
  // Increasing over the levels: the derivative sampled finely between the ends.
  constexpr int samples = 2000;
  double previous = fit(levels.front());
  for (int s = 1; s <= samples; ++s) {
    const double value = fit(levels.front() + (levels.back() - levels.front()) * s / samples);
    if (value < previous)
      throw InputError(what + ": the polynomial of degree " + std::to_string(degree) +
                       " decreases inside the spectrum; choose a lower degree or pass Weyl's law");
    previous = value;
  }
  return fit;
}

std::vector<double> unfold(std::span<const double> levels, const std::function<double(double)>& n_smooth,
                           const std::string& what) {
  check_levels(levels, what);
  std::vector<double> x(levels.size());
  for (std::size_t i = 0; i < levels.size(); ++i) {
    x[i] = n_smooth(levels[i]);
    if (!std::isfinite(x[i]))
      throw InputError(what + ": the counting function is not finite at level " + std::to_string(i));
    if (i > 0 && x[i] < x[i - 1])
      throw InputError(what + ": the counting function decreases between levels " + std::to_string(i - 1) +
                       " and " + std::to_string(i));
  }
  return x;
}

}  // namespace lgi::experiments::spectral
