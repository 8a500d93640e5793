// The exact free-rigid-body flow; formulas and references in free_body_exact.hpp.
#include "integrators/system/free_body_exact.hpp"

#include <algorithm>
#include <Eigen/Eigenvalues>
#include <boost/math/policies/policy.hpp>
#include <boost/math/special_functions/ellint_rf.hpp>
#include <boost/math/special_functions/ellint_rj.hpp>
#include <cmath>
#include <limits>
#include <numbers>

namespace lgi::system {

using lie::Mat3;
using lie::Vec3;

namespace {

// Carlson's integrals in plain double (Boost otherwise promotes to long double,
// which costs time and is not needed: both are accurate to a few ulps), and
// without exceptions (the arguments are valid by construction: at most one of
// x, y is 0 since dn² ≥ k'² > 0, z = 1, p = 1 − n sn² ≥ 1).
namespace policies = boost::math::policies;
using CarlsonPolicy =
    policies::policy<policies::promote_double<false>, policies::domain_error<policies::errno_on_error>,
                     policies::evaluation_error<policies::errno_on_error>>;
double carlson_rf(double x, double y, double z) { return boost::math::ellint_rf(x, y, z, CarlsonPolicy()); }
double carlson_rj(double x, double y, double z, double p) {
  return boost::math::ellint_rj(x, y, z, p, CarlsonPolicy());
}

// Double-double arithmetic (error-free transformations: Knuth's TwoSum, TwoProd
// through an explicit fma; Dekker 1971), used once per set-up for Δ.
struct DoubleDouble {
  double hi, lo;
};
DoubleDouble two_sum(double a, double b) {
  const double s = a + b;
  const double bb = s - a;
  return {s, (a - (s - bb)) + (b - bb)};
}
DoubleDouble two_prod(double a, double b) {
  const double p = a * b;
  return {p, std::fma(a, b, -p)};
}
DoubleDouble normalise(double hi, double lo) {
  const double s = hi + lo;
  return {s, lo - (s - hi)};
}
DoubleDouble mul(const DoubleDouble& a, const DoubleDouble& b) {
  const DoubleDouble p = two_prod(a.hi, b.hi);
  return normalise(p.hi, p.lo + (a.hi * b.lo + a.lo * b.hi));
}
DoubleDouble add(const DoubleDouble& a, const DoubleDouble& b) {
  const DoubleDouble s = two_sum(a.hi, b.hi);
  return normalise(s.hi, s.lo + (a.lo + b.lo));
}

/// Δ = G² − 2T I2 = −Π1² (I2 − I1)/I1 + Π3² (I3 − I2)/I3 (principal frame). Its
/// two terms cancel near the separatrix planes, and its relative error becomes
/// that of k'² and hence of the period K ~ ln(4/k'): the numerator
/// Δ I1 I3 = Π3² (I3 − I2) I1 − Π1² (I2 − I1) I3 is formed in double-double, so
/// Δ is correct to a few ulps for any (double) Π and I.
double separatrix_distance(const Vec3& pi, const Vec3& I) {
  const DoubleDouble d21 = two_sum(I(1), -I(0)), d32 = two_sum(I(2), -I(1));
  const DoubleDouble t3 = mul(mul(two_prod(pi(2), pi(2)), d32), {I(0), 0.0});
  const DoubleDouble t1 = mul(mul(two_prod(pi(0), pi(0)), d21), {-I(2), 0.0});
  const DoubleDouble num = add(t3, t1);
  return (num.hi + num.lo) / (I(0) * I(2));
}

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
  std::array<int, 3> order{0, 1, 2};
  std::sort(order.begin(), order.end(), [&](int i, int j) { return principal(i) < principal(j); });
  Vec3 I;
  Mat3 P;
  for (int i = 0; i < 3; ++i) {
    I(i) = principal(order[static_cast<std::size_t>(i)]);
    P.col(i) = axes.col(order[static_cast<std::size_t>(i)]);
  }
  if (P.determinant() < 0.0) P.col(2) = -P.col(2);

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
  const int zeros = (pi_p(0) == 0.0) + (pi_p(1) == 0.0) + (pi_p(2) == 0.0);
  if (zeros >= 2) {  // steady rotation about a principal axis
    regime_ = Regime::steady;
    const int i = pi_p(0) != 0.0 ? 0 : (pi_p(1) != 0.0 ? 1 : 2);
    axis_rate_ = G / I(i);
    return;
  }

  // Working frame (header): Δ = G² − 2T I2 decides which end axis carries dn.
  const double delta = separatrix_distance(pi_p, I);  // the same in either working frame
  Mat3 Q = P;
  Vec3 Iw = I;
  if (delta < 0.0) {  // rotation about the smallest axis: reverse (proper: e3, −e2, e1)
    Q.col(0) = P.col(2);
    Q.col(1) = -P.col(1);
    Q.col(2) = P.col(0);
    Iw = Vec3(I(2), I(1), I(0));
  }
  if ((Q.transpose() * pi0)(2) < 0.0) {  // Π3 > 0: rotate by π about the first axis
    Q.col(1) = -Q.col(1);
    Q.col(2) = -Q.col(2);
  }
  Q_ = Q;
  const Vec3 pw = Q.transpose() * pi0;
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
  double s = pw(1) / b_, c = pw(0) / a1_;
  const double h = std::hypot(s, c);
  s /= h;
  c /= h;

  if (kc2_ < std::numeric_limits<double>::min()) {
    // k'² = 0, or so small (Δ/G² below 1e-308) that dn² could underflow: the
    // homoclinic orbit, which the elliptic one follows for |λt| < ln(4/k') > 350.
    kc2_ = 0.0;
    regime_ = Regime::separatrix;
    sep_root_ = std::sqrt(-n_);
    u0_ = std::asinh(s / c);
    psi_rate_ = G / I2;
    c_pi_ *= sep_root_ / (1.0 - n_);
  } else {
    regime_ = Regime::elliptic;
    K_ = carlson_rf(0.0, kc2_, 1.0);
    half_K_ = 0.5 * K_;
    two_K_ = 2.0 * K_;
    two_zc_ = 2.0 * n_third_ * carlson_rj(0.0, kc2_, 1.0, 1.0 - n_);
    u0_ = s * carlson_rf(c * c, c * c + kc2_ * s * s, 1.0);
    psi_rate_ = G / I1;
    momentum_period_ = 4.0 * K_ / lambda_;
    // AGM table: a0 = 1, b0 = k', a_{i+1} = (a_i + b_i)/2, b_{i+1} = √(a_i b_i), until
    // c_i/a_i = k_i (c_{i+1} = c_i²/(4 a_{i+1}), c0 = k) is below 2⁻⁵⁴.
    double a = 1.0, bb = kc_, cc = std::sqrt(k2_);
    int i = 0;
    while (i < kMaxAgm && cc > 0x1p-54 * a) {
      const double an = 0.5 * (a + bb);
      const double bn = std::sqrt(a * bb);
      cc = cc * cc / (4.0 * an);
      agm_a_[static_cast<std::size_t>(i)] = an;          // a_{i+1}
      agm_b_[static_cast<std::size_t>(i)] = bb;          // b_i
      agm_ratio_[static_cast<std::size_t>(i)] = a / an;  // a_i/a_{i+1}
      a = an;
      bb = bn;
      ++i;
    }
    agm_n_ = i;
    agm_scale_ = a;  // a_N = π/(2K)
  }

  Vec3 pi_w0;
  momentum_and_angle(u0_, pi_w0, z0_);
  L_ = initial.R * Q_ * alignment(pi_w0).transpose();
}

FreeBodyExactFlow::Jacobi FreeBodyExactFlow::jacobi_agm(double v) const {
  // Descending Gauss transformation (DLMF 22.7.1–3) along the AGM chain, in the
  // rational form of Bulirsch (Numer. Math. 7 (1965) 78): at level i the modulus
  // is k_i = c_i/a_i and the argument a_i v; with y_i = sn/cn and D_i = dn there,
  //   D_i = (a_{i+1} + b_i y_{i+1}²)/(a_{i+1} + a_i y_{i+1}²),
  //   y_i = y_{i+1} (a_i/a_{i+1})/D_{i+1},
  // from y_N = tan(a_N v), D_N = 1 (k_N < 2⁻⁵⁴). Every step is a product or a sum
  // of positive numbers, so sn, cn and dn keep their relative accuracy even as
  // k → 1 (unlike the arcsine recurrence of A&S 16.4.3, which loses digits there).
  // For 0 ≤ v ≤ K/2: a_N v ≤ π/4 and y_0 ≤ 1/√k'.
  double y = std::tan(agm_scale_ * v);
  double d = 1.0;
  for (int i = agm_n_ - 1; i >= 0; --i) {
    const auto iu = static_cast<std::size_t>(i);
    const double y2 = y * y;
    const double a_next = agm_a_[iu];
    y = y * agm_ratio_[iu] / d;
    d = (a_next + agm_b_[iu] * y2) / (a_next + agm_a_[iu] * agm_ratio_[iu] * y2);
  }
  const double cn = 1.0 / std::sqrt(1.0 + y * y);
  return {y * cn, cn, d};
}

FreeBodyExactFlow::Jacobi FreeBodyExactFlow::jacobi_reduced(double r) const {
  const double ar = std::abs(r);
  if (ar <= half_K_) {
    const Jacobi j = jacobi_agm(ar);
    return {std::copysign(j.sn, r), j.cn, j.dn};
  }
  // DLMF Table 22.4.3: sn(K − v) = cn v/dn v, cn(K − v) = k' sn v/dn v, dn(K − v) = k'/dn v.
  const double v = std::max(K_ - ar, 0.0);
  const Jacobi j = jacobi_agm(v);
  return {std::copysign(j.cn / j.dn, r), kc_ * j.sn / j.dn, kc_ / j.dn};
}

void FreeBodyExactFlow::momentum_and_angle(double u, Vec3& pi_w, double& z) const {
  if (regime_ == Regime::separatrix) {
    const double th = std::tanh(u);
    const double se = 1.0 / std::cosh(u);
    pi_w = Vec3(a1_ * se, b_ * th, a3_ * se);
    z = std::atan(sep_root_ * th);
    return;
  }
  // u = 2K j + r, |r| ≤ K; sn, cn change sign with j odd, dn does not; am u = jπ + am r.
  const double j = std::nearbyint(u / two_K_);
  const double r = u - j * two_K_;
  const Jacobi f = jacobi_reduced(r);
  const double sign = std::fmod(j, 2.0) == 0.0 ? 1.0 : -1.0;
  pi_w = Vec3(a1_ * sign * f.cn, b_ * sign * f.sn, a3_ * f.dn);
  // Z(am r) = (n/3) sn³ R_J(cn², dn², 1, 1 − n sn²), plus j (2 Zc) for the whole half-periods.
  const double s2 = f.sn * f.sn;
  z = j * two_zc_ + n_third_ * s2 * f.sn * carlson_rj(f.cn * f.cn, f.dn * f.dn, 1.0, 1.0 - n_ * s2);
}

Mat3 FreeBodyExactFlow::alignment(const Vec3& pi_w) {
  // B = Rx(θ) Rz(φ) with third row Π_w/|Π_w| (header).
  const double g = pi_w.norm();
  const double rho = std::hypot(pi_w(0), pi_w(1));
  const double n1 = pi_w(0) / g, n2 = pi_w(1) / g, n3 = pi_w(2) / g;
  const double sp = pi_w(0) / rho, cp = pi_w(1) / rho;  // sin φ, cos φ
  const double st = rho / g;                            // sin θ
  Mat3 B;
  B << cp, -sp, 0.0,           //
      n3 * sp, n3 * cp, -st,   //
      n1, n2, n3;
  return B;
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
  const Mat3 B = alignment(pi_w);
  const double cs = std::cos(psi), sn = std::sin(psi);
  Mat3 RB;  // Rz(ψ) B
  RB.row(0) = cs * B.row(0) - sn * B.row(1);
  RB.row(1) = sn * B.row(0) + cs * B.row(1);
  RB.row(2) = B.row(2);
  return {L_ * RB * Q_.transpose(), Q_ * pi_w};
}

}  // namespace lgi::system
