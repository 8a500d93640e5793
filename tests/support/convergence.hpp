#pragma once
// Observed order of convergence: least-squares slope of log(error) against
// log(h), after dropping the round-off plateau (errors below `floor`) and
// the pre-asymptotic regime (errors above `ceiling`), as in JuliaGNI's
// verification tests.
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "lie/so3.hpp"
#include "integrators/system/rigid_body.hpp"

namespace lgi::testing {

struct ConvergencePoint {
  double h;
  double error;
};

struct SlopeFit {
  double slope = 0.0;
  int points = 0;
};

inline SlopeFit fitted_slope(const std::vector<ConvergencePoint>& pts, double floor = 1e-11, double ceiling = 1e-2) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (const auto& p : pts) {
    if (!(p.error > floor && p.error < ceiling)) continue;
    const double x = std::log(p.h), y = std::log(p.error);
    sx += x; sy += y; sxx += x * x; sxy += x * y;
    ++n;
  }
  SlopeFit f;
  f.points = n;
  if (n >= 2) f.slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  return f;
}

/// One line on stdout with the fitted slope and every (h, error) point, so a
/// test run records the orders it measured.
inline void report_slope(const std::string& name, const std::string& problem, const SlopeFit& fit,
                         const std::vector<ConvergencePoint>& pts) {
  std::cout << "order " << name << " on " << problem << ": slope " << fit.slope << " from " << fit.points
            << " points;";
  for (const auto& p : pts) std::cout << " (" << p.h << ", " << p.error << ")";
  std::cout << '\n';
}

/// Global error of docs/conventions.md §7: the larger of the geodesic attitude
/// error and the relative momentum error.
inline double global_error(const system::State& s, const system::State& ref) {
  const double attitude = lie::geodesic_distance(ref.R, s.R);
  const double momentum = (s.Pi - ref.Pi).norm() / ref.Pi.norm();
  return std::max(attitude, momentum);
}

}  // namespace lgi::testing
