#pragma once
// Observed order of convergence: least-squares slope of log(error) against
// log(h), after dropping the round-off plateau (errors below `floor`) and
// the pre-asymptotic regime (errors above `ceiling`), as in JuliaGNI's
// verification tests; the fit is the verification kit's.
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "experiments/analysis/scheme_verification.hpp"
#include "lie/so3.hpp"
#include "integrators/system/rigid_body.hpp"

namespace lgi::testing {

using experiments::verification::ConvergencePoint;
using experiments::verification::SlopeFit;

/// The verification kit's fit (experiments/analysis/scheme_verification.hpp), with the tests' default band.
inline SlopeFit fitted_slope(const std::vector<ConvergencePoint>& pts, double floor = 1e-11, double ceiling = 1e-2) {
  return experiments::verification::fitted_slope(pts, floor, ceiling);
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
