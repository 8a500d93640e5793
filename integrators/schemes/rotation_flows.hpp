#pragma once
// Closed-form sub-flows of the free rigid body's kinetic energy, for the
// splittings `split-axes` (split_axes.hpp) and `split-symmetric`
// (split_symmetric.hpp). Each is the exact flow of a Hamiltonian of Π alone
// (docs/math.md §7; Dullweber, Leimkuhler & McLachlan, J. Chem. Phys. 107
// (1997) 5840–5851, §III; Touma & Wisdom, Astron. J. 107 (1994) 1189–1202):
//
//   axis flow  H = ½ c Π_i²  (Π_i = p_i·Π, p_i the unit principal axis i):
//       ω = c Π_i (constant: Π_i is conserved),
//       R ← R exp(t ω p̂_i),   Π ← exp(−t ω p̂_i) Π.
//     Check against docs/conventions.md §1, Ṙ = R Ω̂ and Π̇ = Π × Ω with
//     Ω = ∂H/∂Π = ω p_i: d/dt exp(−tω p̂)Π = −ω p × Π = Π × ω p. ✓
//     For a diagonal J (p_i = e_i) this is a plane rotation: with (j, k) the
//     cyclic successors of i, (c, s) = (cos, sin)(t ω),
//       R_:j ← c R_:j + s R_:k,    R_:k ← −s R_:j + c R_:k     (columns),
//       Π_j  ← c Π_j + s Π_k,      Π_k  ← −s Π_j + c Π_k,
//     one sincos, 16 products. A non-diagonal J takes Rodrigues' formula
//     about p_i (its p̂_i, p̂_i² are kept per run).
//   sphere flow  H = |Π|²/(2A):
//       Π unchanged,  R ← R exp(t Π̂/A),
//     Rodrigues' formula applied to the rows of R (sphere_flow below).
//     |Π|² is a Casimir: this flow commutes with every function of Π, i.e.
//     with every axis flow (both conserve m = RΠ).
//
// Every sub-flow conserves the spatial momentum m = RΠ and |Π|, exactly in
// exact arithmetic; each is an exact Hamiltonian flow, so a composition of
// them is symplectic and, composed symmetrically, symmetric. Angles of
// opposite sign give the inverse flow; flows of one Hamiltonian merge:
// flow(a) ∘ flow(b) = flow(a + b).
#include <array>
#include <cmath>
#include <cstddef>
#include <utility>

#include "integrators/schemes/splitting.hpp"
#include "integrators/system/inertia.hpp"
#include "lie/product_state.hpp"

namespace lgi::integrators::rotation_flows {

using lie::Mat3;
using lie::Vec3;
using State = lie::SO3xR3;

struct SinCos {
  double sin = 0.0;
  double cos = 1.0;
};

namespace detail {
/// (sin x, cos x) on |x| ≤ π/4 by the Taylor polynomials, sin to x¹⁷ and cos
/// to x¹⁶ (to x¹³ and x¹² on |x| ≤ 1/4), in u = x² by Estrin's scheme. The
/// first omitted terms are below 2e-18 relative on either range.
inline SinCos sin_cos_taylor(double x) {
  // 1/k! for k = 2 … 17.
  constexpr double f2 = 1.0 / 2.0, f3 = 1.0 / 6.0, f4 = 1.0 / 24.0, f5 = 1.0 / 120.0, f6 = 1.0 / 720.0,
                   f7 = 1.0 / 5040.0, f8 = 1.0 / 40320.0, f9 = 1.0 / 362880.0, f10 = 1.0 / 3628800.0,
                   f11 = 1.0 / 39916800.0, f12 = 1.0 / 479001600.0, f13 = 1.0 / 6227020800.0,
                   f14 = 1.0 / 87178291200.0, f15 = 1.0 / 1307674368000.0, f16 = 1.0 / 20922789888000.0,
                   f17 = 1.0 / 355687428096000.0;
  const double u = x * x, u2 = u * u, u4 = u2 * u2;
  // sin x = x (1 − u/3! + u²/5! − …),  cos x = 1 − u/2! + u²/4! − …
  if (u <= 0.0625) {
    const double s = ((1.0 - f3 * u) + u2 * (f5 - f7 * u)) + u4 * ((f9 - f11 * u) + u2 * f13);
    const double c = ((1.0 - f2 * u) + u2 * (f4 - f6 * u)) + u4 * ((f8 - f10 * u) + u2 * f12);
    return {x * s, c};
  }
  const double u8 = u4 * u4;
  const double s = ((1.0 - f3 * u) + u2 * (f5 - f7 * u)) + u4 * ((f9 - f11 * u) + u2 * (f13 - f15 * u)) + u8 * f17;
  const double c = ((1.0 - f2 * u) + u2 * (f4 - f6 * u)) + u4 * ((f8 - f10 * u) + u2 * (f12 - f14 * u)) + u8 * f16;
  return {x * s, c};
}
}  // namespace detail

/// (sin x, cos x), what the rotations' cost is mostly made of. On |x| ≤ π/4
/// by detail::sin_cos_taylor; up to |x| ≤ 1e5 from the remainder
/// r = x − k π/2, |r| ≤ π/4, with π/2 = P1 + P2 (P1 its first 33 bits, so
/// k P1 is exact; Cody & Waite's reduction), and the quadrant's swap of sin
/// and cos; beyond, the C library's. Agrees with std::sin and std::cos to
/// about an ulp (tests/test_rotation_splitting.cpp) at about half their cost.
inline SinCos sin_cos(double x) {
  constexpr double quarter_pi = 0.78539816339744831;
  const double a = std::abs(x);
  if (a <= quarter_pi) return detail::sin_cos_taylor(x);
  if (!(a <= 1e5)) return {std::sin(x), std::cos(x)};
  constexpr double two_over_pi = 0.6366197723675814;
  constexpr double P1 = 1.5707963267341256, P2 = 6.077100506506192e-11;  // P1 + P2 = π/2 to 4e-27
  const double kd = static_cast<double>(static_cast<long>(x * two_over_pi + (x < 0.0 ? -0.5 : 0.5)));
  const SinCos r = detail::sin_cos_taylor((x - kd * P1) - kd * P2);
  switch (static_cast<long>(kd) & 3) {
    case 0: return r;
    case 1: return {r.cos, -r.sin};
    case 2: return {-r.sin, -r.cos};
    default: return {-r.cos, r.sin};
  }
}

/// The principal axes in ascending order of their moments: {smallest,
/// intermediate, largest}; ties keep the body-axis order.
inline std::array<int, 3> ascending_axes(const Vec3& principal) {
  std::array<int, 3> order{0, 1, 2};
  // Insertion sort of three: stable, and allocates nothing (std::stable_sort may).
  for (std::size_t i = 1; i < 3; ++i)
    for (std::size_t j = i; j > 0 && principal(order[j]) < principal(order[j - 1]); --j) std::swap(order[j], order[j - 1]);
  return order;
}

/// The axis flows about the principal axes of one inertia (set up per run).
class PrincipalAxisFlows {
 public:
  PrincipalAxisFlows() = default;
  explicit PrincipalAxisFlows(const system::Inertia& inertia)
      : diagonal_(inertia.diagonal), axes_(inertia.principal_axes), moments_(inertia.principal) {
    for (int i = 0; i < 3; ++i) {
      hat_[i] = lie::hat(axes_.col(i));
      hat2_[i] = hat_[i] * hat_[i];
    }
  }

  const Vec3& moments() const { return moments_; }

  /// Π_i = p_i·Π.
  double component(const State& s, int axis) const {
    return diagonal_ ? s.Pi(axis) : axes_.col(axis).dot(s.Pi);
  }

  /// Exact flow over t of H = ½ c Π_axis² (see the top of this file).
  void flow(State& s, int axis, double c, double t) const {
    if (c == 0.0) return;  // a zero coefficient (equal moments): the identity
    const double angle = t * c * component(s, axis);
    const SinCos sc = sin_cos(angle);
    const double cs = sc.cos, sn = sc.sin;
    if (diagonal_) {
      const int j = axis == 2 ? 0 : axis + 1;
      const int k = axis == 0 ? 2 : axis - 1;
      for (int r = 0; r < 3; ++r) {
        const double a = s.R(r, j), b = s.R(r, k);
        s.R(r, j) = cs * a + sn * b;
        s.R(r, k) = cs * b - sn * a;
      }
      const double a = s.Pi(j), b = s.Pi(k);
      s.Pi(j) = cs * a + sn * b;
      s.Pi(k) = cs * b - sn * a;
    } else {
      // exp(angle p̂) = I + sin p̂ + (1 − cos) p̂², 1 − cos = 2 sin²(angle/2).
      const double half = sin_cos(0.5 * angle).sin;
      const Mat3 E = Mat3::Identity() + sn * hat_[axis] + (2.0 * half * half) * hat2_[axis];
      s.R = (s.R * E).eval();
      s.Pi = (E.transpose() * s.Pi).eval();
    }
  }

 private:
  bool diagonal_ = true;
  Mat3 axes_ = Mat3::Identity();  // columns p_i (body coordinates)
  Vec3 moments_ = Vec3::Ones();
  Mat3 hat_[3] = {Mat3::Zero(), Mat3::Zero(), Mat3::Zero()};   // p̂_i
  Mat3 hat2_[3] = {Mat3::Zero(), Mat3::Zero(), Mat3::Zero()};  // p̂_i²
};

namespace detail {
/// a = sin θ/θ and b = (1 − cos θ)/θ² from u = θ² ≤ (π/4)², by their Taylor
/// series Σ (−u)^k/(2k+1)! and Σ (−u)^k/(2k+2)! to u⁸ (u⁶ for u ≤ 1/16);
/// the first omitted terms are below 1e-18 relative. No square root.
inline void rotation_coefficients(double u, double& a, double& b) {
  constexpr double f2 = 1.0 / 2.0, f3 = 1.0 / 6.0, f4 = 1.0 / 24.0, f5 = 1.0 / 120.0, f6 = 1.0 / 720.0,
                   f7 = 1.0 / 5040.0, f8 = 1.0 / 40320.0, f9 = 1.0 / 362880.0, f10 = 1.0 / 3628800.0,
                   f11 = 1.0 / 39916800.0, f12 = 1.0 / 479001600.0, f13 = 1.0 / 6227020800.0,
                   f14 = 1.0 / 87178291200.0, f15 = 1.0 / 1307674368000.0, f16 = 1.0 / 20922789888000.0,
                   f17 = 1.0 / 355687428096000.0, f18 = 1.0 / 6402373705728000.0;
  const double u2 = u * u, u4 = u2 * u2;
  if (u <= 0.0625) {
    a = ((1.0 - f3 * u) + u2 * (f5 - f7 * u)) + u4 * ((f9 - f11 * u) + u2 * f13);
    b = ((f2 - f4 * u) + u2 * (f6 - f8 * u)) + u4 * ((f10 - f12 * u) + u2 * f14);
    return;
  }
  const double u8 = u4 * u4;
  a = ((1.0 - f3 * u) + u2 * (f5 - f7 * u)) + u4 * ((f9 - f11 * u) + u2 * (f13 - f15 * u)) + u8 * f17;
  b = ((f2 - f4 * u) + u2 * (f6 - f8 * u)) + u4 * ((f10 - f12 * u) + u2 * (f14 - f16 * u)) + u8 * f18;
}
}  // namespace detail

/// Exact flow over t of H = |Π|²/(2A), with inverse_moment = 1/A: R ← R exp(ŵ),
/// w = tΠ/A, θ = |w|. Each row r of R becomes
///   r ← r (1 − b θ²) + a (r × w) + b (r·w) w,   a = sin θ/θ, b = (1 − cos θ)/θ²
/// (r ŵ = r × w, r ŵ² = (r·w) w − θ² r), with a, b from θ² without a square
/// root for θ ≤ π/4 (detail::rotation_coefficients), else from sin_cos(θ).
inline void sphere_flow(State& s, double inverse_moment, double t) {
  const double scale = t * inverse_moment;
  const double w0 = scale * s.Pi(0), w1 = scale * s.Pi(1), w2 = scale * s.Pi(2);
  const double u = w0 * w0 + w1 * w1 + w2 * w2;  // θ²
  double a, b;
  if (u <= 0.61685027506808491) {  // (π/4)²
    detail::rotation_coefficients(u, a, b);
  } else {
    const double theta = std::sqrt(u);
    const SinCos half = sin_cos(0.5 * theta);
    a = 2.0 * half.sin * half.cos / theta;
    const double sinc_half = half.sin / theta;
    b = 2.0 * sinc_half * sinc_half;
  }
  const double c = 1.0 - b * u;  // cos θ
  for (int r = 0; r < 3; ++r) {
    const double x = s.R(r, 0), y = s.R(r, 1), z = s.R(r, 2);
    const double along = b * (x * w0 + y * w1 + z * w2);
    s.R(r, 0) = c * x + a * (y * w2 - z * w1) + along * w0;
    s.R(r, 1) = c * y + a * (z * w0 - x * w2) + along * w1;
    s.R(r, 2) = c * z + a * (x * w1 - y * w0) + along * w2;
  }
}

/// split-exact's kick (SplitExact::kick, splitting.hpp): the exact flow over
/// `length` of Ṙ = 0, Π̇ = τ(R, Π, t) at frozen R and t. Without a damper
/// (Π += length f, f the frozen torque) it is written here to be inlined:
/// a step of these schemes is one chain of dependent sub-flows, and the call
/// cost a quarter of a stage (measured); with a damper it is split-exact's
/// damped_kick.
template <class Model>
inline void kick(const Model& model, State& s, double t, double length) {
  static_assert(Model::frozen_kick,
                "split-axes and split-symmetric need every torque term to have a frozen kick (FrozenKickTerm)");
  if constexpr (Model::has_torque) {
    const SplitExact::FrozenTorque k = SplitExact::frozen_torque(model, s, t);
    if (k.damping == 0.0) {
      s.Pi += length * k.f;
    } else {
      SplitExact::damped_kick(model.inertia, s, k, length);
    }
  }
}

}  // namespace lgi::integrators::rotation_flows
