#include "experiments/analysis/periodic/periodic_orbit.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

namespace lgi::experiments {

namespace {

using System = Eigen::Matrix<double, 10, 7>;
using Residual = Eigen::Matrix<double, 10, 1>;

struct Linearised {
  Residual r;
  System A;
  Shot shot;
};

Linearised linearise(const HeavyTopBody& body, const Vec6& x0, double T, const Vec6& x_ref, const Vec6& f_ref,
                     double h, double l, double dt) {
  Linearised L;
  L.shot = shoot(body, x0, T, dt);
  const Invariants inv = euler_poisson_invariants(body, x0);
  L.r.head<6>() = L.shot.end - x0;
  L.r(6) = f_ref.dot(x0 - x_ref);
  L.r.tail<3>() = inv.value - Eigen::Vector3d(h, l, 1.0);
  L.A.setZero();
  L.A.topLeftCorner<6, 6>() = L.shot.monodromy - Mat6::Identity();
  L.A.block<6, 1>(0, 6) = euler_poisson_field(body, L.shot.end);
  L.A.block<1, 6>(6, 0) = f_ref.transpose();
  L.A.bottomLeftCorner<3, 6>() = inv.gradients;
  return L;
}

double residual_of(const Residual& r) {
  return std::max({r.head<6>().norm(), std::abs(r(7)), std::abs(r(8)), std::abs(r(9))});
}

}  // namespace

PeriodicOrbit correct_orbit(const HeavyTopBody& body, const Vec6& x_guess, double T_guess, double h, double l,
                            const ShootingSettings& s) {
  PeriodicOrbit o;
  o.h = h, o.l = l;
  Vec6 x = x_guess;
  double T = T_guess;
  const Vec6 f_ref = euler_poisson_field(body, x_guess).normalized();
  double best = INFINITY, previous = INFINITY;
  for (int it = 0; it <= s.max_iterations; ++it) {
    Linearised L = linearise(body, x, T, x_guess, f_ref, h, l, s.dt);
    if (!L.shot.ok || !L.r.allFinite()) break;
    const double res = residual_of(L.r);
    o.iterations = it;
    if (res < best) {
      best = res;
      o.x0 = x, o.period = T, o.residual = res, o.monodromy = L.shot.monodromy;
      const Eigen::Matrix<double, 7, 1> sv = Eigen::JacobiSVD<System>(L.A).singularValues();
      o.rank_ratio = sv(6) / sv(0);
    }
    // Stop well below the tolerance, or at it once round-off dominates (no
    // tenfold gain left), or when Newton stalls.
    if (res <= s.tolerance * 1e-2 || (res <= s.tolerance && res > 0.1 * previous) || (it > 8 && res > 0.5 * previous))
      break;
    previous = res;
    Eigen::CompleteOrthogonalDecomposition<System> cod;
    cod.setThreshold(1e-9);
    cod.compute(L.A);
    const Eigen::Matrix<double, 7, 1> dz = cod.solve(L.r);
    x -= dz.head<6>();
    T -= dz(6);
    if (!(T > 0.0)) break;
  }
  o.converged = o.residual <= s.tolerance;
  classify_orbit(o);
  return o;
}

void classify_orbit(PeriodicOrbit& o) {
  const Eigen::EigenSolver<Mat6> es(o.monodromy, false);
  std::array<std::complex<double>, 6> mu{};
  for (int k = 0; k < 6; ++k) mu[static_cast<std::size_t>(k)] = es.eigenvalues()(k);
  std::sort(mu.begin(), mu.end(), [](auto a, auto b) { return std::abs(a - 1.0) < std::abs(b - 1.0); });
  o.multipliers = mu;
  std::complex<double> product = 1.0;
  o.trivial_deviation = 0.0;
  for (std::size_t k = 0; k < 6; ++k) {
    product *= mu[k];
    if (k < 4) o.trivial_deviation = std::max(o.trivial_deviation, std::abs(mu[k] - 1.0));
  }
  o.product_deviation = std::abs(product - 1.0);
  // The nontrivial pair (μ, 1/μ): on the unit circle, real positive or real negative.
  const std::complex<double> m = std::abs(mu[4]) >= std::abs(mu[5]) ? mu[4] : mu[5];
  const bool on_circle = std::abs(std::abs(m) - 1.0) <= 1e-6;
  const bool real = std::abs(m.imag()) <= 1e-9 * std::abs(m);
  if (on_circle) o.stability = "elliptic";
  else if (!real) o.stability = "complex";
  else o.stability = m.real() > 0.0 ? "hyperbolic" : "inverse_hyperbolic";
  o.degenerate = o.rank_ratio < 1e-7 && std::abs(mu[5] - 1.0) <= 1e-5 && std::abs(mu[4] - 1.0) <= 1e-5;
}

}  // namespace lgi::experiments
