#include "experiments/analysis/periodic/multiple_shooting.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <vector>

namespace lgi::experiments {

namespace {

struct Segments {
  std::vector<Shot> shots;  // segment k from x_k over T/M
  Eigen::VectorXd r;        // the 6M + 5 equations
  Eigen::MatrixXd A;        // their Jacobian in (x_0 … x_{M−1}, T, p)
  double residual = INFINITY;
  bool ok = true;
};

/// The equations of the header at Z = (x_0 … x_{M−1}, T, p) and their Jacobian.
Segments linearise(const PeriodicFlow& body, const Eigen::VectorXd& Z, const FamilyPoint& z_p, const FamilyPoint& t,
                   const Vec6& f_ref, double fixed, const ShootingSettings& s) {
  const int M = s.shooting_points, n = 6 * M, iT = n, ip = n + 1;
  Segments g;
  g.r = Eigen::VectorXd::Zero(n + 5);
  g.A = Eigen::MatrixXd::Zero(n + 5, n + 2);
  const double T = Z(iT);
  double matching = 0.0;
  for (int k = 0; k < M; ++k) {
    const int next = 6 * ((k + 1) % M);
    g.shots.push_back(shoot(body, Z.segment<6>(6 * k), T / M, s.dt));
    const Shot& sh = g.shots.back();
    if (!sh.ok) {
      g.ok = false;
      return g;
    }
    g.r.segment<6>(6 * k) = flow_difference(body, sh.end, Z.segment<6>(next));
    matching = std::max(matching, g.r.segment<6>(6 * k).norm());
    g.A.block<6, 6>(6 * k, 6 * k) += sh.monodromy;
    g.A.block<6, 6>(6 * k, next) -= Mat6::Identity();
    g.A.block<6, 1>(6 * k, iT) = flow_field(body, sh.end) / M;
  }
  FamilyPoint z;
  z << Z.head<6>(), T, Z(ip);
  // The rows on x_0 alone are those of single shooting (rows 6 … 10 of the condensed system).
  const CondensedSystem c = condensed_system(body, z, z_p, t, f_ref, fixed, s, g.shots.back().end, Mat6::Identity());
  g.r.tail<5>() = c.r.tail<5>();
  g.A.block(n, 0, 5, 6) = c.A.block<5, 6>(6, 0);
  g.A.block(n, iT, 5, 1) = c.A.block<5, 1>(6, 6);
  g.A.block(n, ip, 5, 1) = c.A.block<5, 1>(6, 7);
  g.residual = std::max(matching, c.r.tail<5>().cwiseAbs().maxCoeff());
  g.ok = g.r.allFinite();
  return g;
}

}  // namespace

PeriodicOrbit correct_multiple(const PeriodicFlow& body, const FamilyPoint& z_p, const FamilyPoint& t, double fixed,
                               const ShootingSettings& s) {
  const int M = s.shooting_points, n = 6 * M;
  PeriodicOrbit o;
  o.in_l = s.in_l;
  (s.in_l ? o.h : o.l) = fixed;
  const Vec6 f_ref = flow_field(body, z_p.head<6>()).normalized();
  // The starts: the predictor's orbit at kT/M.
  Eigen::VectorXd Z(n + 2);
  Z.head<6>() = z_p.head<6>();
  for (int k = 1; k < M; ++k) {
    const Shot sh = shoot(body, Z.segment<6>(6 * (k - 1)), z_p(6) / M, s.dt);
    if (!sh.ok) return o;
    Z.segment<6>(6 * k) = sh.end;
  }
  Z(n) = z_p(6), Z(n + 1) = z_p(7);
  double best = INFINITY, previous = INFINITY;
  for (int it = 0; it <= s.max_iterations; ++it) {
    const Segments g = linearise(body, Z, z_p, t, f_ref, fixed, s);
    if (!g.ok) break;
    o.iterations = it;
    if (g.residual < best) {
      best = g.residual;
      Mat6 product = Mat6::Identity();
      for (const Shot& sh : g.shots) product = sh.monodromy * product;
      FamilyPoint z;
      z << Z.head<6>(), Z(n), Z(n + 1);
      const CondensedSystem c = condensed_system(body, z, z_p, t, f_ref, fixed, s, g.shots.back().end, product);
      record_iterate(o, z, g.residual, product, c.A);
      o.drift = 0.0;
      o.pieces.clear();
      for (const Shot& sh : g.shots) {
        o.drift += sh.drift;
        o.pieces.insert(o.pieces.end(), sh.pieces.begin(), sh.pieces.end());
      }
    }
    if (newton_done(it, g.residual, previous, s)) break;
    previous = g.residual;
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod;
    cod.setThreshold(1e-9);
    cod.compute(g.A);
    Z -= cod.solve(g.r);
    if (!(Z(n) > 0.0)) break;
  }
  o.converged = o.residual <= s.tolerance && !collapsed_to_zero_period(o, s);
  if (o.residual < INFINITY) classify_orbit(body, o);
  return o;
}

}  // namespace lgi::experiments
