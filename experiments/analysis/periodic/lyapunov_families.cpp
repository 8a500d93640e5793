#include "experiments/analysis/periodic/lyapunov_families.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <numbers>

namespace lgi::experiments {

namespace {

Vec6 state_of(const RelativeEquilibrium& e) {
  Vec6 x;
  x << e.angular_momentum, e.gamma;
  return x;
}

/// Minimum-norm Newton steps onto Π·Γ = ℓ, |Γ|² = 1.
Vec6 project_to_leaf(const HeavyTopBody& body, Vec6 x, double l) {
  for (int it = 0; it < 8; ++it) {
    const Invariants inv = euler_poisson_invariants(body, x);
    const Eigen::Vector2d r(inv.value(1) - l, inv.value(2) - 1.0);
    const Eigen::Matrix<double, 2, 6> G = inv.gradients.bottomRows<2>();
    x -= G.transpose() * (G * G.transpose()).ldlt().solve(r);
  }
  return x;
}

/// The real part of the eigenvector of the linearisation at x_e nearest iω, unit length.
Vec6 mode_direction(const HeavyTopBody& body, const Vec6& xe, double omega) {
  const Eigen::EigenSolver<Mat6> es(euler_poisson_jacobian(body, xe));
  int best = 0;
  for (int k = 1; k < 6; ++k)
    if (std::abs(es.eigenvalues()(k) - std::complex<double>(0.0, omega)) <
        std::abs(es.eigenvalues()(best) - std::complex<double>(0.0, omega)))
      best = k;
  Vec6 u = es.eigenvectors().col(best).real();
  if (u.norm() < 1e-3 * es.eigenvectors().col(best).norm()) u = es.eigenvectors().col(best).imag();
  return u.normalized();
}

/// One continuation step by dh from the last row; halves dh up to four times.
/// `xe` (the equilibrium, or null for a seed) gives the first step's predictor.
bool step_family(const HeavyTopBody& body, std::vector<FamilyOrbit>& rows, const Vec6* xe, double h_e, double& dh,
                 double l, const FamilySettings& s) {
  const FamilyOrbit last = rows.back();
  for (int tries = 0; tries < 5; ++tries, dh *= 0.5) {
    const double h = last.orbit.h + dh;
    if (h < s.h_min || h > s.h_max) return false;
    Vec6 x = last.orbit.x0;
    double T = last.orbit.period;
    if (rows.size() >= 2) {  // secant
      const PeriodicOrbit& a = rows[rows.size() - 2].orbit;
      const double r = dh / (last.orbit.h - a.h);
      x += r * (last.orbit.x0 - a.x0), T += r * (last.orbit.period - a.period);
    } else if (xe) {  // amplitude ∝ √(h − h_e) near the equilibrium
      x = *xe + std::sqrt((h - h_e) / (last.orbit.h - h_e)) * (last.orbit.x0 - *xe);
    }
    PeriodicOrbit o = correct_orbit(body, x, T, h, l, s.shooting);
    if (o.converged) {
      rows.push_back({last.family, last.index + 1, last.equilibrium, last.omega, o});
      return true;
    }
  }
  return false;
}

}  // namespace

std::vector<double> equilibrium_frequencies(const RelativeEquilibrium& e) {
  const double disc = e.g1 * e.g1 - 4.0 * e.g2;
  if (!(disc >= 0.0)) return {};
  const double s = std::sqrt(disc);
  std::vector<double> w;
  for (const double mu : {0.5 * (-e.g1 - s), 0.5 * (-e.g1 + s)})
    if (mu < 0.0) w.push_back(std::sqrt(-mu));
  std::sort(w.begin(), w.end());
  return w;
}

std::vector<FamilyOrbit> continue_family(const HeavyTopBody& body, const Vec6& x0, double T, double h, double l,
                                         double direction, const FamilySettings& s) {
  std::vector<FamilyOrbit> rows;
  PeriodicOrbit o = correct_orbit(body, x0, T, h, l, s.shooting);
  if (!o.converged) return rows;
  rows.push_back({0, 0, -1, 2.0 * std::numbers::pi / T, o});
  double dh = direction * s.h_step;
  for (int k = 0; k < s.steps; ++k)
    if (!step_family(body, rows, nullptr, 0.0, dh, l, s)) break;
  return rows;
}

std::vector<FamilyOrbit> lyapunov_families(const HeavyTopBody& body, double l, const FamilySettings& s) {
  std::vector<FamilyOrbit> all;
  const EquilibriumSet set = equilibria_at(body, l);
  int family = 0;
  for (std::size_t i = 0; i < set.rows.size(); ++i) {
    const RelativeEquilibrium& e = set.rows[i];
    if (e.stability != EquilibriumStability::stable) continue;
    const Vec6 xe = state_of(e);
    for (const double omega : equilibrium_frequencies(e)) {
      const Vec6 start = project_to_leaf(body, xe + s.amplitude * xe.norm() * mode_direction(body, xe, omega), l);
      const double h0 = euler_poisson_invariants(body, start).value(0);
      const double T0 = 2.0 * std::numbers::pi / omega;
      PeriodicOrbit o = correct_orbit(body, start, T0, h0, l, s.shooting);
      if (!o.converged) continue;
      std::vector<FamilyOrbit> rows{{family, 0, static_cast<int>(i), omega, o}};
      double dh = (h0 >= e.h ? 1.0 : -1.0) * s.h_step;
      for (int k = 0; k < s.steps; ++k)
        if (!step_family(body, rows, &xe, e.h, dh, l, s)) break;
      all.insert(all.end(), rows.begin(), rows.end());
      ++family;
    }
  }
  return all;
}

}  // namespace lgi::experiments
