// The section of a numerical torus and the first estimate of its rotation
// number (docs/actions.md §3; declarations in actions_section.hpp).
#include "experiments/analysis/actions_section.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace lgi::experiments {

SectionChoice choose_section(const std::vector<Point6>& samples, double min_window) {
  SectionChoice best;
  const std::size_t n = samples.size();
  if (n < 5) return best;
  double pi_scale = 0.0;
  for (const auto& p : samples) pi_scale = std::max(pi_scale, p.head<3>().norm());
  std::vector<double> values;
  for (int c = 0; c < 6; ++c) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const auto& p : samples) lo = std::min(lo, p[c]), hi = std::max(hi, p[c]);
    if (!(hi - lo > 1e-9 * (c < 3 ? std::max(pi_scale, 1e-300) : 1.0))) continue;  // a constant (Π3 of a Lagrange top)
    values.assign({lo, hi});
    for (std::size_t k = 1; k + 1 < n; ++k) {
      const double a = samples[k - 1][c], b = samples[k][c], d = samples[k + 1][c];
      if (!((b - a) * (d - b) < 0.0)) continue;
      // The vertex of the parabola through the three samples (equal steps): the turning value.
      const double curvature = a - 2.0 * b + d;
      const double v = curvature != 0.0 ? b - (d - a) * (d - a) / (8.0 * curvature) : b;
      values.push_back(std::clamp(v, lo, hi));
    }
    std::sort(values.begin(), values.end());
    for (std::size_t k = 1; k < values.size(); ++k) {
      const double window = (values[k] - values[k - 1]) / (hi - lo);
      if (window > best.window) best = {c, 0.5 * (values[k] + values[k - 1]), window};
    }
  }
  if (best.window < min_window) best.coordinate = -1;
  return best;
}

namespace {

/// The length of the closed polygon through the first m points in the order of jρ mod 1.
double polygon_length(const std::vector<Point6>& y, std::size_t m, double rho, std::vector<std::pair<double, int>>& order) {
  order.resize(m);
  for (std::size_t j = 0; j < m; ++j) {
    const double a = static_cast<double>(j) * rho;
    order[j] = {a - std::floor(a), static_cast<int>(j)};
  }
  std::sort(order.begin(), order.end());
  double length = 0.0;
  for (std::size_t i = 0; i < m; ++i)
    length += (y[static_cast<std::size_t>(order[i].second)] - y[static_cast<std::size_t>(order[(i + 1) % m].second)]).norm();
  return length;
}

/// The ρ of least polygon length on the grid centre ± half_width with the given step.
double best_on_grid(const std::vector<Point6>& y, std::size_t m, double centre, double half_width, double step) {
  std::vector<std::pair<double, int>> order;
  double best = std::numeric_limits<double>::infinity(), arg = centre;
  const long steps = std::lround(half_width / step);
  for (long i = -steps; i <= steps; ++i) {
    const double rho = centre + static_cast<double>(i) * step;
    if (rho < 0.0 || rho > 0.5) continue;
    const double length = polygon_length(y, m, rho, order);
    if (length < best) best = length, arg = rho;
  }
  return arg;
}

}  // namespace

double polygon_rotation_number(const std::vector<Point6>& points) {
  const std::size_t n = points.size();
  if (n < 8) return std::nan("");
  // Each coordinate scaled to unit spread (a constant coordinate is left as it is: it adds nothing).
  Point6 mean = Point6::Zero(), spread = Point6::Zero();
  for (const auto& p : points) mean += p;
  mean /= static_cast<double>(n);
  for (const auto& p : points) spread += (p - mean).cwiseAbs2();
  spread = (spread / static_cast<double>(n)).cwiseSqrt();
  std::vector<Point6> y(n);
  for (std::size_t j = 0; j < n; ++j)
    for (int c = 0; c < 6; ++c) y[j][c] = spread[c] > 1e-12 ? (points[j][c] - mean[c]) / spread[c] : 0.0;
  // With m points, the order of jρ (j < m) is constant on intervals of ρ about 1/m² wide
  // (three-gap theorem), so a grid of step 1/(4m²) meets the true order or a neighbour of it.
  const std::size_t m1 = std::min<std::size_t>(n, 96), m2 = std::min<std::size_t>(n, 400);
  const double s1 = 0.25 / static_cast<double>(m1 * m1), s2 = 0.25 / static_cast<double>(m2 * m2);
  const double rho1 = best_on_grid(y, m1, 0.25, 0.25, s1);
  return m2 > m1 ? best_on_grid(y, m2, rho1, 8.0 * s1, s2) : rho1;
}

}  // namespace lgi::experiments
