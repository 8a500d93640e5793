#include "experiments/analysis/periodic/periodic_orbit.hpp"

#include "experiments/analysis/periodic/multiple_shooting.hpp"
#include "experiments/io/number_format.hpp"

#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

namespace lgi::experiments {

namespace {

using System = Eigen::Matrix<double, 11, 8>;
using Residual = Eigen::Matrix<double, 11, 1>;

struct Linearised {
  Residual r;
  System A;
  Shot shot;
};

/// The eleven equations of the header at z and their Jacobian.
Linearised linearise(const PeriodicFlow& body, const FamilyPoint& z, const FamilyPoint& z_p, const FamilyPoint& t,
                     const Vec6& f_ref, double fixed, const ShootingSettings& s) {
  Linearised L;
  L.shot = shoot(body, z.head<6>(), z(6), s.dt);
  const CondensedSystem c = condensed_system(body, z, z_p, t, f_ref, fixed, s, L.shot.end, L.shot.monodromy);
  L.r = c.r, L.A = c.A;
  return L;
}

/// Every equation's defect, the phase and continuation planes included (a
/// least-squares step need not satisfy them when the system loses rank).
double residual_of(const Residual& r) {
  return std::max({r.head<6>().norm(), std::abs(r(6)), std::abs(r(7)), std::abs(r(8)), std::abs(r(9)), std::abs(r(10))});
}

}  // namespace

CondensedSystem condensed_system(const PeriodicFlow& body, const FamilyPoint& z, const FamilyPoint& z_p,
                                 const FamilyPoint& t, const Vec6& f_ref, double fixed, const ShootingSettings& s,
                                 const Vec6& end, const Mat6& monodromy) {
  CondensedSystem L;
  const Vec6 x0 = z.head<6>();
  const Invariants inv = flow_invariants(body, x0);
  L.r.head<6>() = flow_difference(body, end, x0);
  L.r(6) = s.section ? section_value(body, *s.section, x0) : f_ref.dot(x0 - z_p.head<6>());
  L.r.segment<3>(7) = inv.value - (s.in_l ? invariant_levels(body, fixed, z(7)) : invariant_levels(body, z(7), fixed));
  L.r(10) = t.dot(z - z_p);
  L.A.setZero();
  L.A.topLeftCorner<6, 6>() = monodromy - Mat6::Identity();
  L.A.block<6, 1>(0, 6) = flow_field(body, end);
  L.A.block<1, 6>(6, 0) = (s.section ? section_gradient(body, *s.section, x0) : f_ref).transpose();
  L.A.block<3, 6>(7, 0) = inv.gradients;
  L.A(s.in_l ? 8 : 7, 7) = -1.0;
  L.A.row(10) = t.transpose();
  return L;
}

void record_iterate(PeriodicOrbit& o, const FamilyPoint& z, double residual, const Mat6& monodromy,
                    const Eigen::Matrix<double, 11, 8>& A) {
  o.x0 = z.head<6>(), o.period = z(6), o.residual = residual, o.monodromy = monodromy;
  (o.in_l ? o.l : o.h) = z(7);
  const Eigen::Matrix<double, 8, 1> sv = Eigen::JacobiSVD<System>(A).singularValues();
  o.rank_ratio = sv(7) / sv(0);
  // The family's tangent: the null vector of the ten equations without the continuation row.
  const Eigen::JacobiSVD<Eigen::Matrix<double, 10, 8>> family(A.topRows<10>(), Eigen::ComputeFullV);
  o.tangent = family.matrixV().col(7);
}

FamilyPoint family_point(const PeriodicOrbit& o) {
  FamilyPoint z;
  z << o.x0, o.period, parameter_of(o);
  return z;
}

PeriodicOrbit correct_orbit(const PeriodicFlow& body, const Vec6& x_guess, double T_guess, double h, double l,
                            const ShootingSettings& s) {
  FamilyPoint z_p, t = FamilyPoint::Zero();
  z_p << x_guess, T_guess, s.in_l ? l : h;
  t(7) = 1.0;
  return correct_on_family(body, z_p, t, s.in_l ? h : l, s);
}

PeriodicOrbit correct_on_family(const PeriodicFlow& body, const FamilyPoint& z_p, const FamilyPoint& t, double fixed,
                                const ShootingSettings& s) {
  if (s.shooting_points > 1) return correct_multiple(body, z_p, t, fixed, s);
  PeriodicOrbit o;
  o.in_l = s.in_l;
  (s.in_l ? o.h : o.l) = fixed;
  FamilyPoint z = z_p;
  const Vec6 f_ref = flow_field(body, z_p.head<6>()).normalized();
  double best = INFINITY, previous = INFINITY;
  for (int it = 0; it <= s.max_iterations; ++it) {
    Linearised L = linearise(body, z, z_p, t, f_ref, fixed, s);
    if (!L.shot.ok || !L.r.allFinite()) break;
    const double res = residual_of(L.r);
    o.iterations = it;
    if (res < best) {
      best = res;
      record_iterate(o, z, res, L.shot.monodromy, L.A);
      o.drift = L.shot.drift;
      o.pieces = std::move(L.shot.pieces);
    }
    if (newton_done(it, res, previous, s)) break;
    previous = res;
    Eigen::CompleteOrthogonalDecomposition<System> cod;
    cod.setThreshold(1e-9);
    cod.compute(L.A);
    z -= cod.solve(L.r);
    if (!(z(6) > 0.0)) break;
  }
  // false when no iterate was finite (residual ∞), or at the trivial solution T → 0
  o.converged = o.residual <= s.tolerance && !collapsed_to_zero_period(o, s);
  if (o.residual < INFINITY) classify_orbit(body, o);
  return o;
}

std::string correction_failure(const PeriodicOrbit& o, const ShootingSettings& s) {
  if (o.residual <= s.tolerance && collapsed_to_zero_period(o, s))
    return "Newton went to the trivial solution T = 0 (period " + format_general(o.period, 3) + ", at most one step)";
  return "Newton did not converge (residual " + std::to_string(o.residual) + ")";
}

}  // namespace lgi::experiments
