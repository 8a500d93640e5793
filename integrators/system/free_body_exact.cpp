// The exact free-rigid-body flow; formulas and references in free_body_exact.hpp.
#include "integrators/system/free_body_exact.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <numbers>

namespace lgi::system {

using lie::Mat3;
using lie::Vec3;
namespace fb = free_body_detail;

namespace {

/// Rotation by `angle` about the unit vector `e` (Rodrigues).
Mat3 rotation(const Vec3& e, double angle) {
  const double s = std::sin(angle);
  const double h = std::sin(0.5 * angle);
  const Mat3 E = lie::hat(e);
  return Mat3::Identity() + s * E + (2.0 * h * h) * (E * E);
}

}  // namespace

FreeBodyExactFlow::FreeBodyExactFlow(const Inertia& inertia, const lie::SO3xR3& initial) : initial_(initial) {
  const Vec3& pi0 = initial.Pi;
  const double G = pi0.norm();
  if (G == 0.0) {
    regime_ = Regime::rest;
    return;
  }
  axis_ = pi0 / G;

  // Principal frame sorted ascending, as a proper rotation P (x_body = P x_p).
  // A non-diagonal tensor is decomposed again in long double: the moments then
  // carry only their final rounding (Eigen's double solver leaves ~10 ulps,
  // which the precession angle G t/I1 accumulates).
  Vec3 principal = inertia.principal;
  Mat3 axes = inertia.principal_axes;
  if (!inertia.diagonal) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<long double, 3, 3>> eig(inertia.J.cast<long double>());
    principal = eig.eigenvalues().cast<double>();
    axes = eig.eigenvectors().cast<double>();
  }
  const fb::PrincipalFrame pf = fb::sorted_principal_frame(principal, axes);
  const Vec3& I = pf.I;
  const Mat3& P = pf.P;

  if (I(0) == I(2)) {  // spherical: Ω = Π/I constant
    regime_ = Regime::spherical;
    axis_rate_ = G / I(0);
    return;
  }
  if (I(0) == I(1) || I(1) == I(2)) {  // symmetric: closed-form precession
    regime_ = Regime::symmetric;
    const int d = I(0) == I(1) ? 2 : 0;
    const double A = I(1), C = I(d);
    sym_axis_ = P.col(d);
    axis_rate_ = G / A;
    nu_ = (1.0 / C - 1.0 / A) * pi0.dot(sym_axis_);
    if (nu_ != 0.0) momentum_period_ = 2.0 * std::numbers::pi / std::abs(nu_);
    return;
  }
  const Vec3 pi_p = P.transpose() * pi0;
  if (const int i = fb::steady_axis(pi_p); i >= 0) {  // steady rotation about a principal axis
    regime_ = Regime::steady;
    axis_rate_ = G / I(i);
    return;
  }

  // Working frame (header): Δ = G² − 2T I2 decides which end axis carries dn.
  const double delta = fb::separatrix_distance(pi_p, I);  // the same in either working frame
  const fb::WorkingFrame w = fb::working_frame(pf, delta < 0.0);
  const Vec3& Iw = w.I;
  Q_ = (w.Q.transpose() * pi0)(2) < 0.0 ? fb::half_turn(w.Q) : w.Q;  // Π3 > 0
  const Vec3 pw = Q_.transpose() * pi0;
  const double I1 = Iw(0), I2 = Iw(1), I3 = Iw(2);
  const double I21 = I2 - I1, I31 = I3 - I1, I32 = I3 - I2;  // all of one sign
  const double p1s = pw(0) * pw(0), p2s = pw(1) * pw(1), p3s = pw(2) * pw(2);
  const double C13 = p1s * I31 / I1 + p2s * I32 / I2;
  const double C31 = p2s * I21 / I2 + p3s * I31 / I3;

  lambda_ = std::sqrt(I32 * C31 / (I1 * I2 * I3));
  a1_ = std::copysign(std::sqrt(C13 * I1 / I31), pw(0));
  a3_ = std::sqrt(C31 * I3 / I31);
  b_ = a1_ * a3_ * I31 / (I1 * I3 * lambda_);
  k2_ = I21 * C13 / (I32 * C31);
  kc2_ = I31 * delta / (I32 * C31);
  kc_ = std::sqrt(kc2_);
  n_ = -I3 * I21 / (I1 * I32);
  n_third_ = n_ / 3.0;
  c_pi_ = G * I31 / (lambda_ * I1 * I3);

  // Phase: sn u0 ∝ Π2/b, cn u0 ∝ Π1/a1 ≥ 0, normalised.
  const fb::SinCos phi0 = fb::phase_angle(pw, a1_, b_);

  if (kc2_ < std::numeric_limits<double>::min()) {
    // k'² = 0, or so small (Δ/G² below 1e-308) that dn² could underflow: the
    // homoclinic orbit, which the elliptic one follows for |λt| < ln(4/k') > 350.
    kc2_ = 0.0;
    regime_ = Regime::separatrix;
    sep_root_ = std::sqrt(-n_);
    u0_ = std::asinh(phi0.s / phi0.c);
    psi_rate_ = G / I2;
    c_pi_ *= sep_root_ / (1.0 - n_);
  } else {
    regime_ = Regime::elliptic;
    K_ = fb::carlson_rf(0.0, kc2_, 1.0);
    two_zc_ = 2.0 * n_third_ * fb::carlson_rj(0.0, kc2_, 1.0, 1.0 - n_);
    u0_ = fb::incomplete_first(phi0, kc2_);
    psi_rate_ = G / I1;
    momentum_period_ = 4.0 * K_ / lambda_;
    agm_ = fb::build_agm(std::sqrt(k2_), kc_);
  }

  Vec3 pi_w0;
  momentum_and_angle(u0_, pi_w0, z0_);
  L_ = initial.R * Q_ * fb::alignment(pi_w0).transpose();
}

void FreeBodyExactFlow::momentum_and_angle(double u, Vec3& pi_w, double& z) const {
  if (regime_ == Regime::separatrix) {
    const double th = std::tanh(u);
    const double se = 1.0 / std::cosh(u);
    pi_w = Vec3(a1_ * se, b_ * th, a3_ * se);
    z = std::atan(sep_root_ * th);
    return;
  }
  // u = 2K j + r, |r| ≤ K; Z(am u) = j (2 Zc) for the whole half-periods + Z(am r).
  const fb::ReducedPhase p = fb::reduce_phase(agm_, K_, kc_, u);
  pi_w = Vec3(a1_ * p.sign * p.f.cn, b_ * p.sign * p.f.sn, a3_ * p.f.dn);
  z = p.j * two_zc_ + fb::z_am(p.f, n_, n_third_);
}

lie::SO3xR3 FreeBodyExactFlow::at(double t) const {
  switch (regime_) {
    case Regime::rest:
      return initial_;
    case Regime::spherical:
    case Regime::steady:
      return {initial_.R * rotation(axis_, axis_rate_ * t), initial_.Pi};
    case Regime::symmetric: {
      const double spin = nu_ * t;
      return {initial_.R * rotation(axis_, axis_rate_ * t) * rotation(sym_axis_, spin),
              rotation(sym_axis_, -spin) * initial_.Pi};
    }
    case Regime::elliptic:
    case Regime::separatrix:
      break;
  }
  Vec3 pi_w;
  double z;
  momentum_and_angle(lambda_ * t + u0_, pi_w, z);
  const double psi = psi_rate_ * t + c_pi_ * (z - z0_);
  return {L_ * fb::precessed(psi, fb::alignment(pi_w)) * Q_.transpose(), Q_ * pi_w};
}

}  // namespace lgi::system
