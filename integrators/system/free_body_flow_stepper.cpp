// The exact free flow as a stepper; formulas and references in
// free_body_flow_stepper.hpp and free_body_exact.hpp; the pieces it shares
// with FreeBodyExactFlow in free_body_special.cpp.
#include "integrators/system/free_body_flow_stepper.hpp"

#include <cmath>
#include <numbers>

#include "integrators/system/free_body_special.hpp"

namespace lgi::system {

using lie::Mat3;
using lie::Vec3;
namespace fb = free_body_detail;

FreeBodyFlowStepper::FreeBodyFlowStepper(const Inertia& inertia) {
  const fb::PrincipalFrame pf = fb::sorted_principal_frame(inertia.principal, inertia.principal_axes);
  I_ = pf.I;
  P_ = pf.P;

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
    const fb::WorkingFrame w = fb::working_frame(pf, fi == 1);
    const Vec3& Iw = w.I;
    f.Q[0] = w.Q;
    f.Q[1] = fb::half_turn(w.Q);  // makes Π3 > 0
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
  if (const int i = fb::steady_axis(pp); i >= 0) {  // steady rotation about a principal axis (any of the three)
    s.R = s.R * lie::exp_so3((h / I_(i)) * s.Pi);
    return;
  }
  const double G = std::sqrt(G2);

  // Working frame: by the sign of Δ, then Π3 > 0.
  const double delta = fb::separatrix_distance(pp, I_);
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
  const fb::SinCos phi0 = fb::phase_angle(pw, a1, b);
  const double s0 = phi0.s, c0 = phi0.c;
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
    const fb::Agm agm = fb::build_agm(std::sqrt(k2), std::sqrt(kc2));
    const double K = 0.5 * std::numbers::pi / agm.scale;  // a_N = π/(2K)
    auto z_of = [&](const fb::Jacobi& j) { return fb::z_am(j, f.n, f.n_third); };
    double dz;  // Z(u1) − Z(u0), Z(u) = ∫₀^u n sn²/(1 − n sn²) (continued through ±K)
    if (std::abs(v) <= 0.5 * K) {
      const fb::Jacobi jv = fb::jacobi_small(agm, std::abs(v));
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
      dz = z_of({s2, c2, d2}) - A;
    } else {
      // Coarse step (more than an eighth of Π's period): the phase itself,
      // u0 = F(φ0) = sin φ0 R_F(cos² φ0, 1 − k² sin² φ0, 1), then reduction mod 2K:
      // Z(u1) = 2j Zc + Z(am r), Zc = (n/3) R_J(0, k'², 1, 1 − n) (DLMF 19.25.14, 22.16.2).
      const double u1 = fb::incomplete_first(phi0, kc2) + v;
      const fb::ReducedPhase p = fb::reduce_phase(agm, K, std::sqrt(kc2), u1);
      s1 = p.sign * p.f.sn;
      c1 = p.sign * p.f.cn;
      d1 = p.f.dn;
      const double zc = f.n_third * fb::carlson_rj(0.0, kc2, 1.0, 1.0 - f.n);
      dz = 2.0 * p.j * zc + z_of(p.f) - z_of({s0, c0, d0});
    }
    dpsi = (G / f.I1) * h + c_pi * dz;
  }

  const Vec3 pw1(a1 * c1, b * s1, a3 * d1);
  const Mat3 B0 = fb::alignment(pw);
  const Mat3 RB = fb::precessed(dpsi, fb::alignment(pw1));  // Rz(Δψ) B1
  const Mat3 increment = Q * (B0.transpose() * RB) * Q.transpose();
  s.R = s.R * increment;
  s.Pi = Q * pw1;
}

}  // namespace lgi::system
