// The shared pieces of the exact free flow; see free_body_special.hpp.
#include "integrators/system/free_body_special.hpp"

#include <algorithm>
#include <boost/math/policies/policy.hpp>
#include <boost/math/special_functions/ellint_rf.hpp>
#include <boost/math/special_functions/ellint_rj.hpp>
#include <cmath>
#include <cstddef>

namespace lgi::system::free_body_detail {

namespace {

// Carlson's integrals in plain double (Boost otherwise promotes to long double,
// which costs time and is not needed: both are accurate to a few ulps), and
// without exceptions (the arguments are valid by construction: at most one of
// x, y is 0 since dn² ≥ k'² > 0, z = 1, p = 1 − n sn² ≥ 1). This is the policy
// free_body_exact.cpp used; the stepper's own copy threw instead, which only
// differs for invalid arguments.
namespace policies = boost::math::policies;
using CarlsonPolicy =
    policies::policy<policies::promote_double<false>, policies::domain_error<policies::errno_on_error>,
                     policies::evaluation_error<policies::errno_on_error>>;

// Double-double arithmetic (error-free transformations: Knuth's TwoSum, TwoProd
// through an explicit fma; Dekker 1971), used once per set-up (exact flow) or
// per step (stepper) for Δ.
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

}  // namespace

double carlson_rf(double x, double y, double z) { return boost::math::ellint_rf(x, y, z, CarlsonPolicy()); }
double carlson_rj(double x, double y, double z, double p) {
  return boost::math::ellint_rj(x, y, z, p, CarlsonPolicy());
}

/// Δ = G² − 2T I2 = −Π1² (I2 − I1)/I1 + Π3² (I3 − I2)/I3 (principal frame). Its
/// two terms cancel near the separatrix planes, and its relative error becomes
/// that of k'² and hence of the period K ~ ln(4/k'): the numerator
/// Δ I1 I3 = Π3² (I3 − I2) I1 − Π1² (I2 − I1) I3 is formed in double-double, so
/// Δ is correct to a few ulps for any (double) Π and I. The same in either
/// working frame.
double separatrix_distance(const Vec3& pi, const Vec3& I) {
  const DoubleDouble d21 = two_sum(I(1), -I(0)), d32 = two_sum(I(2), -I(1));
  const DoubleDouble t3 = mul(mul(two_prod(pi(2), pi(2)), d32), {I(0), 0.0});
  const DoubleDouble t1 = mul(mul(two_prod(pi(0), pi(0)), d21), {-I(2), 0.0});
  const DoubleDouble num = add(t3, t1);
  return (num.hi + num.lo) / (I(0) * I(2));
}

PrincipalFrame sorted_principal_frame(const Vec3& principal, const Mat3& axes) {
  std::array<int, 3> order{0, 1, 2};
  std::sort(order.begin(), order.end(), [&](int i, int j) { return principal(i) < principal(j); });
  PrincipalFrame f;
  for (int i = 0; i < 3; ++i) {
    f.I(i) = principal(order[static_cast<std::size_t>(i)]);
    f.P.col(i) = axes.col(order[static_cast<std::size_t>(i)]);
  }
  if (f.P.determinant() < 0.0) f.P.col(2) = -f.P.col(2);
  return f;
}

WorkingFrame working_frame(const PrincipalFrame& principal, bool reversed) {
  const Mat3& P = principal.P;
  const Vec3& I = principal.I;
  WorkingFrame w{P, I};
  if (reversed) {  // rotation about the smallest axis: (e3, −e2, e1), a proper rotation
    w.Q.col(0) = P.col(2);
    w.Q.col(1) = -P.col(1);
    w.Q.col(2) = P.col(0);
    w.I = Vec3(I(2), I(1), I(0));
  }
  return w;
}

Mat3 half_turn(const Mat3& Q) {
  Mat3 turned = Q;
  turned.col(1) = -Q.col(1);
  turned.col(2) = -Q.col(2);
  return turned;
}

int steady_axis(const Vec3& pi_p) {
  const int zeros = (pi_p(0) == 0.0) + (pi_p(1) == 0.0) + (pi_p(2) == 0.0);
  if (zeros < 2) return -1;
  return pi_p(0) != 0.0 ? 0 : (pi_p(1) != 0.0 ? 1 : 2);
}

Mat3 alignment(const Vec3& pi_w) {
  const double g = pi_w.norm();  // its own norm, so that B is orthogonal to round-off
  const double rho = std::hypot(pi_w(0), pi_w(1));
  const double n1 = pi_w(0) / g, n2 = pi_w(1) / g, n3 = pi_w(2) / g;
  const double sp = pi_w(0) / rho, cp = pi_w(1) / rho;  // sin φ, cos φ
  const double st = rho / g;                            // sin θ
  Mat3 B;
  B << cp, -sp, 0.0,          //
      n3 * sp, n3 * cp, -st,  //
      n1, n2, n3;
  return B;
}

Mat3 precessed(double psi, const Mat3& B) {
  const double cs = std::cos(psi), sn = std::sin(psi);
  Mat3 RB;
  RB.row(0) = cs * B.row(0) - sn * B.row(1);
  RB.row(1) = sn * B.row(0) + cs * B.row(1);
  RB.row(2) = B.row(2);
  return RB;
}

Agm build_agm(double k, double kc) {
  // a0 = 1, b0 = k', c0 = k; a_{i+1} = (a_i + b_i)/2, b_{i+1} = √(a_i b_i),
  // c_{i+1} = c_i²/(4 a_{i+1}), until c_i/a_i = k_i is below 2⁻⁵⁴ (A&S 16.4;
  // DLMF 22.20(ii)).
  Agm agm;
  double a = 1.0, bb = kc, cc = k;
  int i = 0;
  while (i < kMaxAgm && cc > 0x1p-54 * a) {
    const double an = 0.5 * (a + bb);
    const double bn = std::sqrt(a * bb);
    cc = cc * cc / (4.0 * an);
    const auto iu = static_cast<std::size_t>(i);
    agm.a[iu] = an;          // a_{i+1}
    agm.b[iu] = bb;          // b_i
    agm.ratio[iu] = a / an;  // a_i/a_{i+1}
    a = an;
    bb = bn;
    ++i;
  }
  agm.n = i;
  agm.scale = a;  // a_N = π/(2K)
  return agm;
}

Jacobi jacobi_small(const Agm& agm, double v) {
  // Descending Gauss transformation (DLMF 22.7.1–3) along the AGM chain, in the
  // rational form of Bulirsch (Numer. Math. 7 (1965) 78): at level i the modulus
  // is k_i = c_i/a_i and the argument a_i v; with y_i = sn/cn and D_i = dn there,
  //   D_i = (a_{i+1} + b_i y_{i+1}²)/(a_{i+1} + a_i y_{i+1}²),
  //   y_i = y_{i+1} (a_i/a_{i+1})/D_{i+1},
  // from y_N = tan(a_N v), D_N = 1 (k_N < 2⁻⁵⁴). Every step is a product or a sum
  // of positive numbers, so sn, cn and dn keep their relative accuracy even as
  // k → 1 (unlike the arcsine recurrence of A&S 16.4.3, which loses digits there).
  // For 0 ≤ v ≤ K/2: a_N v ≤ π/4 and y_0 ≤ 1/√k'.
  double y = std::tan(agm.scale * v);
  double d = 1.0;
  for (int i = agm.n - 1; i >= 0; --i) {
    const auto iu = static_cast<std::size_t>(i);
    const double y2 = y * y;
    const double a_next = agm.a[iu];
    y = y * agm.ratio[iu] / d;
    d = (a_next + agm.b[iu] * y2) / (a_next + a_next * agm.ratio[iu] * y2);
  }
  const double cn = 1.0 / std::sqrt(1.0 + y * y);
  return {y * cn, cn, d};
}

Jacobi jacobi_reduced(const Agm& agm, double K, double kc, double r) {
  const double ar = std::abs(r);
  if (ar <= 0.5 * K) {
    const Jacobi j = jacobi_small(agm, ar);
    return {std::copysign(j.sn, r), j.cn, j.dn};
  }
  // DLMF Table 22.4.3: sn(K − v) = cn v/dn v, cn(K − v) = k' sn v/dn v, dn(K − v) = k'/dn v.
  const Jacobi j = jacobi_small(agm, std::max(K - ar, 0.0));
  return {std::copysign(j.cn / j.dn, r), kc * j.sn / j.dn, kc / j.dn};
}

ReducedPhase reduce_phase(const Agm& agm, double K, double kc, double u) {
  // sn, cn change sign with j odd, dn does not; am u = jπ + am r (DLMF 22.16.2).
  const double j = std::nearbyint(u / (2.0 * K));
  const double r = u - j * (2.0 * K);
  return {j, std::fmod(j, 2.0) == 0.0 ? 1.0 : -1.0, jacobi_reduced(agm, K, kc, r)};
}

SinCos phase_angle(const Vec3& pi_w, double a1, double b) {
  double s = pi_w(1) / b, c = pi_w(0) / a1;
  const double h = std::hypot(s, c);
  s /= h;
  c /= h;
  return {s, c};
}

double incomplete_first(const SinCos& phi, double kc2) {
  return phi.s * carlson_rf(phi.c * phi.c, phi.c * phi.c + kc2 * phi.s * phi.s, 1.0);
}

double z_am(const Jacobi& f, double n, double n_third) {
  const double s2 = f.sn * f.sn;
  return n_third * s2 * f.sn * carlson_rj(f.cn * f.cn, f.dn * f.dn, 1.0, 1.0 - n * s2);
}

}  // namespace lgi::system::free_body_detail
