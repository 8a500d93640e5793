// The exact free flow as a stepper; formulas and references in
// free_body_flow_stepper.hpp and free_body_exact.hpp.
#include "integrators/system/free_body_flow_stepper.hpp"

#include <algorithm>
#include <boost/math/policies/policy.hpp>
#include <boost/math/special_functions/ellint_rf.hpp>
#include <boost/math/special_functions/ellint_rj.hpp>
#include <cmath>
#include <numbers>

namespace lgi::system {

using lie::Mat3;
using lie::Vec3;

namespace {

// Carlson's integrals in plain double (no promotion to long double), as in
// free_body_exact.cpp.
using CarlsonPolicy = boost::math::policies::policy<boost::math::policies::promote_double<false>>;
double carlson_rf(double x, double y, double z) { return boost::math::ellint_rf(x, y, z, CarlsonPolicy()); }
double carlson_rj(double x, double y, double z, double p) {
  return boost::math::ellint_rj(x, y, z, p, CarlsonPolicy());
}

// Δ = G² − 2T I2 in the ascending principal frame, with its numerator
// Π3² (I3 − I2) I1 − Π1² (I2 − I1) I3 formed in double-double (Knuth's TwoSum,
// Dekker's TwoProd through fma), so that Δ, and with it k'², keeps its
// relative accuracy near the separatrix (the same quantity, and the same
// reason, as in free_body_exact.cpp; re-implemented here, ~30 flops a step).
struct DD {
  double hi, lo;
};
DD two_sum(double a, double b) {
  const double s = a + b;
  const double bb = s - a;
  return {s, (a - (s - bb)) + (b - bb)};
}
DD two_prod(double a, double b) {
  const double p = a * b;
  return {p, std::fma(a, b, -p)};
}
DD renorm(double hi, double lo) {
  const double s = hi + lo;
  return {s, lo - (s - hi)};
}
DD mul(const DD& a, const DD& b) {
  const DD p = two_prod(a.hi, b.hi);
  return renorm(p.hi, p.lo + (a.hi * b.lo + a.lo * b.hi));
}
DD add(const DD& a, const DD& b) {
  const DD s = two_sum(a.hi, b.hi);
  return renorm(s.hi, s.lo + (a.lo + b.lo));
}
double separatrix_distance(const Vec3& pi, const Vec3& I) {
  const DD d21 = two_sum(I(1), -I(0)), d32 = two_sum(I(2), -I(1));
  const DD t3 = mul(mul(two_prod(pi(2), pi(2)), d32), {I(0), 0.0});
  const DD t1 = mul(mul(two_prod(pi(0), pi(0)), d21), {-I(2), 0.0});
  const DD num = add(t3, t1);
  return (num.hi + num.lo) / (I(0) * I(2));
}

/// B(Π_w) = Rx(θ) Rz(φ), third row Π_w/|Π_w| (free_body_exact.hpp, "R(t)").
Mat3 alignment(const Vec3& pi_w) {
  const double g = pi_w.norm();  // its own norm, so that B is orthogonal to round-off
  const double rho = std::hypot(pi_w(0), pi_w(1));
  const double n1 = pi_w(0) / g, n2 = pi_w(1) / g, n3 = pi_w(2) / g;
  const double sp = pi_w(0) / rho, cp = pi_w(1) / rho;
  const double st = rho / g;
  Mat3 B;
  B << cp, -sp, 0.0,          //
      n3 * sp, n3 * cp, -st,  //
      n1, n2, n3;
  return B;
}

}  // namespace

FreeBodyFlowStepper::FreeBodyFlowStepper(const Inertia& inertia) {
  std::array<int, 3> order{0, 1, 2};
  std::sort(order.begin(), order.end(), [&](int i, int j) { return inertia.principal(i) < inertia.principal(j); });
  for (int i = 0; i < 3; ++i) {
    I_(i) = inertia.principal(order[static_cast<std::size_t>(i)]);
    P_.col(i) = inertia.principal_axes.col(order[static_cast<std::size_t>(i)]);
  }
  if (P_.determinant() < 0.0) P_.col(2) = -P_.col(2);

  if (I_(0) == I_(2)) {
    shape_ = Shape::spherical;
    sym_A_ = I_(0);
    return;
  }
  if (I_(0) == I_(1) || I_(1) == I_(2)) {
    shape_ = Shape::symmetric;
    const int d = I_(0) == I_(1) ? 2 : 0;
    sym_A_ = I_(1);
    sym_C_ = I_(d);
    sym_axis_ = P_.col(d);
    return;
  }
  shape_ = Shape::asymmetric;
  for (int fi = 0; fi < 2; ++fi) {
    Frame& f = frame_[fi];
    Mat3 Q = P_;
    Vec3 Iw = I_;
    if (fi == 1) {  // rotation about the smallest axis: (e3, −e2, e1), a proper rotation
      Q.col(0) = P_.col(2);
      Q.col(1) = -P_.col(1);
      Q.col(2) = P_.col(0);
      Iw = Vec3(I_(2), I_(1), I_(0));
    }
    f.Q[0] = Q;
    Q.col(1) = -Q.col(1);  // rotation by π about the first working axis: makes Π3 > 0
    Q.col(2) = -Q.col(2);
    f.Q[1] = Q;
    f.I1 = Iw(0);
    f.I2 = Iw(1);
    f.I3 = Iw(2);
    f.I21 = f.I2 - f.I1;
    f.I31 = f.I3 - f.I1;
    f.I32 = f.I3 - f.I2;
    f.c13_1 = f.I31 / f.I1;
    f.c13_2 = f.I32 / f.I2;
    f.c31_2 = f.I21 / f.I2;
    f.c31_3 = f.I31 / f.I3;
    f.a1_sq = f.I1 / f.I31;
    f.a3_sq = f.I3 / f.I31;
    f.lambda_sq = f.I32 / (f.I1 * f.I2 * f.I3);
    f.b_coef = f.I31 / (f.I1 * f.I3);
    f.k2_coef = f.I21 / f.I32;
    f.kc2_coef = f.I31 / f.I32;
    f.n = -f.I3 * f.I21 / (f.I1 * f.I32);
    f.n_third = f.n / 3.0;
    f.cpi_coef = f.I31 / (f.I1 * f.I3);
    f.minus_n = -f.n;
    f.one_minus_n = 1.0 - f.n;
    f.sep_root = std::sqrt(-f.n);
    f.sep_coef = f.sep_root / (1.0 - f.n);
  }
}

void FreeBodyFlowStepper::build_agm(double k, double kc, Agm& agm) {
  // a0 = 1, b0 = k', c0 = k; a_{i+1} = (a_i + b_i)/2, b_{i+1} = √(a_i b_i),
  // c_{i+1} = c_i²/(4 a_{i+1}), until c_i/a_i < 2⁻⁵⁴ (A&S 16.4; DLMF 22.20(ii)).
  double a = 1.0, bb = kc, cc = k;
  int i = 0;
  while (i < kMaxAgm && cc > 0x1p-54 * a) {
    const double an = 0.5 * (a + bb);
    const double bn = std::sqrt(a * bb);
    cc = cc * cc / (4.0 * an);
    const auto iu = static_cast<std::size_t>(i);
    agm.a[iu] = an;
    agm.b[iu] = bb;
    agm.ratio[iu] = a / an;
    a = an;
    bb = bn;
    ++i;
  }
  agm.n = i;
  agm.scale = a;
}

FreeBodyFlowStepper::Jacobi FreeBodyFlowStepper::jacobi_small(const Agm& agm, double v) {
  // Descending Gauss transformation in Bulirsch's rational form (Numer. Math. 7
  // (1965) 78), as in free_body_exact.cpp: from y_N = tan(a_N v), D_N = 1,
  //   y_i = y_{i+1} (a_i/a_{i+1})/D_{i+1},
  //   D_i = (a_{i+1} + b_i y_{i+1}²)/(a_{i+1} + a_i y_{i+1}²),
  // then sn = y_0/√(1 + y_0²), cn = 1/√(1 + y_0²), dn = D_0. Needs a_N v ≤ π/4.
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

FreeBodyFlowStepper::Jacobi FreeBodyFlowStepper::jacobi_reduced(const Agm& agm, double K, double kc, double r) {
  const double ar = std::abs(r);
  if (ar <= 0.5 * K) {
    const Jacobi j = jacobi_small(agm, ar);
    return {std::copysign(j.sn, r), j.cn, j.dn};
  }
  // DLMF Table 22.4.3: sn(K − v) = cd v, cn(K − v) = k' sd v, dn(K − v) = k' nd v.
  const Jacobi j = jacobi_small(agm, std::max(K - ar, 0.0));
  return {std::copysign(j.cn / j.dn, r), kc * j.sn / j.dn, kc / j.dn};
}

void FreeBodyFlowStepper::advance(lie::SO3xR3& s, double h) const {
  switch (shape_) {
    case Shape::spherical:
      s.R = s.R * lie::exp_so3((h / sym_A_) * s.Pi);
      return;
    case Shape::symmetric: {
      // Π(h) = exp(−νh d̂)Π, R(h) = R exp(hΠ̂/A) exp(νh d̂), ν = (1/C − 1/A) Π·d.
      const double nu = (1.0 / sym_C_ - 1.0 / sym_A_) * s.Pi.dot(sym_axis_);
      const Mat3 spin = lie::exp_so3((nu * h) * sym_axis_);
      s.R = s.R * lie::exp_so3((h / sym_A_) * s.Pi) * spin;
      s.Pi = spin.transpose() * s.Pi;
      return;
    }
    case Shape::asymmetric:
      advance_asymmetric(s, h);
      return;
  }
}

void FreeBodyFlowStepper::advance_asymmetric(lie::SO3xR3& s, double h) const {
  const double G2 = s.Pi.squaredNorm();
  if (G2 == 0.0) return;  // at rest
  const Vec3 pp = P_.transpose() * s.Pi;
  const int zeros = (pp(0) == 0.0) + (pp(1) == 0.0) + (pp(2) == 0.0);
  if (zeros >= 2) {  // steady rotation about a principal axis (any of the three)
    const int i = pp(0) != 0.0 ? 0 : (pp(1) != 0.0 ? 1 : 2);
    s.R = s.R * lie::exp_so3((h / I_(i)) * s.Pi);
    return;
  }
  const double G = std::sqrt(G2);

  // Working frame: by the sign of Δ, then Π3 > 0.
  const double delta = separatrix_distance(pp, I_);
  const int fi = delta < 0.0 ? 1 : 0;
  const Frame& f = frame_[fi];
  Vec3 pw = fi == 0 ? pp : Vec3(pp(2), -pp(1), pp(0));
  const int flip = pw(2) < 0.0 ? 1 : 0;
  if (flip) {
    pw(1) = -pw(1);
    pw(2) = -pw(2);
  }
  const Mat3& Q = f.Q[flip];

  const double p1s = pw(0) * pw(0), p2s = pw(1) * pw(1), p3s = pw(2) * pw(2);
  const double C13 = p1s * f.c13_1 + p2s * f.c13_2;
  const double C31 = p2s * f.c31_2 + p3s * f.c31_3;
  const double lambda = std::sqrt(C31 * f.lambda_sq);
  const double a1 = std::copysign(std::sqrt(C13 * f.a1_sq), pw(0));
  const double a3 = std::sqrt(C31 * f.a3_sq);
  const double b = a1 * a3 * f.b_coef / lambda;
  const double k2 = C13 / C31 * f.k2_coef;
  const double kc2 = delta / C31 * f.kc2_coef;
  const double c_pi = G * f.cpi_coef / lambda;

  // Phase at the start of the step, read off Π (cn ≥ 0, so u0 ∈ [−K, K]).
  double s0 = pw(1) / b, c0 = pw(0) / a1;
  {
    const double hyp = std::hypot(s0, c0);
    s0 /= hyp;
    c0 /= hyp;
  }
  const double d0 = pw(2) / a3;
  const double v = lambda * h;

  double s1, c1, d1, dpsi;
  if (kc2 == 0.0) {
    // Separatrix: sn = tanh, cn = dn = sech; Π(n; gd u, 1) in closed form.
    const double u1 = std::asinh(s0 / c0) + v;
    s1 = std::tanh(u1);
    c1 = d1 = 1.0 / std::cosh(u1);
    dpsi = (G / f.I2) * h + c_pi * f.sep_coef * (std::atan(f.sep_root * s1) - std::atan(f.sep_root * s0));
  } else {
    Agm agm;
    build_agm(std::sqrt(k2), std::sqrt(kc2), agm);
    const double K = 0.5 * std::numbers::pi / agm.scale;  // a_N = π/(2K)
    auto z_of = [&](double sn, double cn, double dn) {   // Z(am u) for |am u| ≤ π/2
      const double sn2 = sn * sn;
      return f.n_third * sn2 * sn * carlson_rj(cn * cn, dn * dn, 1.0, 1.0 - f.n * sn2);
    };
    double dz;  // Z(u1) − Z(u0), Z(u) = ∫₀^u n sn²/(1 − n sn²) (continued through ±K)
    if (std::abs(v) <= 0.5 * K) {
      const Jacobi jv = jacobi_small(agm, std::abs(v));
      const double s2 = std::copysign(jv.sn, v), c2 = jv.cn, d2 = jv.dn;
      const double D = 1.0 - k2 * (s0 * s0) * (s2 * s2);
      s1 = (s0 * c2 * d2 + s2 * c0 * d0) / D;
      c1 = (c0 * c2 - s0 * d0 * s2 * d2) / D;
      d1 = (d0 * d2 - k2 * s0 * c0 * s2 * c2) / D;
      // Addition theorem of the third kind (header): Z(u0 + v) − Z(u0) = Z(v) − A,
      //   A = (−n/ρ) atan2(ρ s0 s2 s1, 1 − n s1² + n s0 s2 c1 d1),  ρ = √(−n (k² − n)(1 − n)).
      // Z(v) has |am v| ≤ π/4-ish, so its R_J has nearly equal arguments (cheap);
      // A is formed directly as the small quantity it is (no difference of O(1) terms).
      const double rho = std::sqrt(f.minus_n * (k2 + f.minus_n) * f.one_minus_n);
      const double A = (f.minus_n / rho) *
                       std::atan2(rho * s0 * s2 * s1, 1.0 - f.n * s1 * s1 + f.n * s0 * s2 * c1 * d1);
      dz = z_of(s2, c2, d2) - A;
    } else {
      // Coarse step (more than an eighth of Π's period): the phase itself,
      // u0 = F(φ0) = sin φ0 R_F(cos² φ0, 1 − k² sin² φ0, 1), then reduction mod 2K:
      // Z(u1) = 2j Zc + Z(am r), Zc = (n/3) R_J(0, k'², 1, 1 − n) (DLMF 19.25.14, 22.16.2).
      const double u0 = s0 * carlson_rf(c0 * c0, c0 * c0 + kc2 * s0 * s0, 1.0);
      const double u1 = u0 + v;
      const double j = std::nearbyint(u1 / (2.0 * K));
      const double r = u1 - j * (2.0 * K);
      const Jacobi jr = jacobi_reduced(agm, K, std::sqrt(kc2), r);
      const double sign = std::fmod(j, 2.0) == 0.0 ? 1.0 : -1.0;
      s1 = sign * jr.sn;
      c1 = sign * jr.cn;
      d1 = jr.dn;
      const double zc = f.n_third * carlson_rj(0.0, kc2, 1.0, 1.0 - f.n);
      dz = 2.0 * j * zc + z_of(jr.sn, jr.cn, jr.dn) - z_of(s0, c0, d0);
    }
    dpsi = (G / f.I1) * h + c_pi * dz;
  }

  const Vec3 pw1(a1 * c1, b * s1, a3 * d1);
  const Mat3 B0 = alignment(pw);
  const Mat3 B1 = alignment(pw1);
  const double cs = std::cos(dpsi), sn = std::sin(dpsi);
  Mat3 RB;  // Rz(Δψ) B1
  RB.row(0) = cs * B1.row(0) - sn * B1.row(1);
  RB.row(1) = sn * B1.row(0) + cs * B1.row(1);
  RB.row(2) = B1.row(2);
  const Mat3 increment = Q * (B0.transpose() * RB) * Q.transpose();
  s.R = s.R * increment;
  s.Pi = Q * pw1;
}

}  // namespace lgi::system
