#include "experiments/analysis/periodic/periodic_orbit.hpp"

#include "experiments/analysis/periodic/multiple_shooting.hpp"

#include <Eigen/Eigenvalues>
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

/// Q: (n₁, n₂, n₃, f̂, w₁, w₂) of classify_orbit's comment, from a QR of [∇H ∇C ∇|Γ|² f].
Mat6 adapted_basis(const PeriodicFlow& body, const Vec6& x0) {
  Eigen::Matrix<double, 6, 4> G;
  G.leftCols<3>() = flow_invariants(body, x0).gradients.transpose();
  G.col(3) = flow_field(body, x0);
  const Eigen::HouseholderQR<Eigen::Matrix<double, 6, 4>> qr(G);
  return qr.householderQ() * Mat6::Identity();
}

/// The trivial multipliers again, with the left basis at the shot's end x_T
/// (single shooting): the discrete map keeps H, C, |Γ|² exactly, so
/// ∇I(x_T)ᵀ M = ∇I(x0)ᵀ and M f(x0) ≈ f(x_T) hold without the error
/// (∇I(x0) − ∇I(x_T))ᵀ M, which the growth of M (≈ tr P) makes large on
/// strongly hyperbolic orbits. The nontrivial pair keeps the basis at x0.
void trivial_from_both_ends(const PeriodicFlow& body, PeriodicOrbit& o, const Vec6& end) {
  const Mat6 Q0 = adapted_basis(body, o.x0);
  Mat6 QT = adapted_basis(body, end);
  for (int k = 0; k < 6; ++k)  // Householder's signs may differ between the ends
    if (QT.col(k).dot(Q0.col(k)) < 0.0) QT.col(k) *= -1.0;
  const Mat6 B = QT.transpose() * o.monodromy * Q0;
  const Eigen::EigenSolver<Eigen::Matrix3d> normal(B.topLeftCorner<3, 3>(), false);
  std::array<std::complex<double>, 4> mu{};
  for (int k = 0; k < 3; ++k) mu[static_cast<std::size_t>(k)] = normal.eigenvalues()(k);
  mu[3] = B(3, 3);
  std::sort(mu.begin(), mu.end(), [](auto a, auto b) { return std::abs(a - 1.0) < std::abs(b - 1.0); });
  std::complex<double> product = o.multipliers[4] * o.multipliers[5];
  o.trivial_deviation = 0.0;
  for (std::size_t k = 0; k < 4; ++k) {
    o.multipliers[k] = mu[k], product *= mu[k];
    o.trivial_deviation = std::max(o.trivial_deviation, std::abs(mu[k] - 1.0));
  }
  o.product_deviation = std::abs(product - 1.0);
}

}  // namespace

CondensedSystem condensed_system(const PeriodicFlow& body, const FamilyPoint& z, const FamilyPoint& z_p,
                                 const FamilyPoint& t, const Vec6& f_ref, double fixed, const ShootingSettings& s,
                                 const Vec6& end, const Mat6& monodromy) {
  CondensedSystem L;
  const Vec6 x0 = z.head<6>();
  const Invariants inv = flow_invariants(body, x0);
  L.r.head<6>() = flow_difference(body, end, x0);
  L.r(6) = s.section ? section_value(body.body, *s.section, x0) : f_ref.dot(x0 - z_p.head<6>());
  L.r.segment<3>(7) = inv.value - (s.in_l ? invariant_levels(body, fixed, z(7)) : invariant_levels(body, z(7), fixed));
  L.r(10) = t.dot(z - z_p);
  L.A.setZero();
  L.A.topLeftCorner<6, 6>() = monodromy - Mat6::Identity();
  L.A.block<6, 1>(0, 6) = flow_field(body, end);
  L.A.block<1, 6>(6, 0) = (s.section ? section_gradient(body.body, *s.section, x0) : f_ref).transpose();
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
  Vec6 best_end = z_p.head<6>();
  for (int it = 0; it <= s.max_iterations; ++it) {
    Linearised L = linearise(body, z, z_p, t, f_ref, fixed, s);
    if (!L.shot.ok || !L.r.allFinite()) break;
    const double res = residual_of(L.r);
    o.iterations = it;
    if (res < best) {
      best = res;
      record_iterate(o, z, res, L.shot.monodromy, L.A);
      o.drift = L.shot.drift;
      best_end = L.shot.end;
    }
    if (newton_done(it, res, previous, s)) break;
    previous = res;
    Eigen::CompleteOrthogonalDecomposition<System> cod;
    cod.setThreshold(1e-9);
    cod.compute(L.A);
    z -= cod.solve(L.r);
    if (!(z(6) > 0.0)) break;
  }
  o.converged = o.residual <= s.tolerance;  // false when no iterate was finite (residual ∞)
  if (o.residual < INFINITY) classify_orbit(body, o);
  if (o.residual < INFINITY && !body.cardan) trivial_from_both_ends(body, o, best_end);
  return o;
}

void classify_orbit(const PeriodicFlow& body, PeriodicOrbit& o) {
  const Mat6 Q = adapted_basis(body, o.x0);
  const Mat6 B = Q.transpose() * o.monodromy * Q;
  o.invariance_defect = std::max(B.topRightCorner<3, 3>().cwiseAbs().maxCoeff(),
                                 B.block<2, 1>(4, 3).cwiseAbs().maxCoeff());
  o.reduced_monodromy = B.bottomRightCorner<2, 2>();
  o.section_basis = Q.rightCols<2>();
  o.reduced_trace = o.reduced_monodromy.trace();
  const Eigen::EigenSolver<Eigen::Matrix3d> normal(B.topLeftCorner<3, 3>(), false);
  const Eigen::EigenSolver<Eigen::Matrix2d> section(o.reduced_monodromy, false);
  std::array<std::complex<double>, 6> mu{};
  for (int k = 0; k < 3; ++k) mu[static_cast<std::size_t>(k)] = normal.eigenvalues()(k);
  mu[3] = B(3, 3);
  mu[4] = section.eigenvalues()(0), mu[5] = section.eigenvalues()(1);
  std::sort(mu.begin(), mu.begin() + 4, [](auto a, auto b) { return std::abs(a - 1.0) < std::abs(b - 1.0); });
  o.multipliers = mu;
  std::complex<double> product = 1.0;
  o.trivial_deviation = 0.0;
  for (std::size_t k = 0; k < 6; ++k) {
    product *= mu[k];
    if (k < 4) o.trivial_deviation = std::max(o.trivial_deviation, std::abs(mu[k] - 1.0));
  }
  o.product_deviation = std::abs(product - 1.0);
  // The nontrivial pair (μ, 1/μ) of the 2×2 P: on the unit circle (|tr P| < 2),
  // real positive (tr P > 2) or real negative (tr P < −2). |tr P| within
  // 1e-10 of 2 (|μ| − 1 below 1e-5: round-off cannot tell) counts as elliptic.
  const double tr = o.reduced_trace;
  o.stability = std::abs(tr) <= 2.0 + 1e-10 ? "elliptic" : (tr > 0.0 ? "hyperbolic" : "inverse_hyperbolic");
  o.degenerate = o.rank_ratio < 1e-7 && std::abs(mu[5] - 1.0) <= 1e-5 && std::abs(mu[4] - 1.0) <= 1e-5;
}

}  // namespace lgi::experiments
