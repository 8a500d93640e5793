#pragma once
// Charts of SO(3) used only by the baselines (the Lie-group schemes never
// integrate angles): Euler angles ZXZ and the rotation vector.
//
// Euler ZXZ (Goldstein; Trindade & Sampaio 2001, eq. 12):
//   R = Rz(ψ) Rx(θ) Rz(φ), ψ precession, θ nutation, φ spin.
//   Ω = (ψ̇ sinθ sinφ + θ̇ cosφ, ψ̇ sinθ cosφ − θ̇ sinφ, ψ̇ cosθ + φ̇)   (body)
//   Inverse (Trindade & Sampaio eq. 27), singular where sinθ = 0.
// Rotation vector Ψ: R = exp(Ψ̂), Ψ̇ = dexpinv_body(Ψ) Ω, singular at |Ψ| = 2π.
#include <cmath>
#include <numbers>

#include "lie/so3.hpp"

namespace lgi::lie {

struct EulerZXZ {
  double psi = 0.0;    // precession
  double theta = 0.0;  // nutation
  double phi = 0.0;    // spin
};

inline Mat3 rot_z(double a) {
  Mat3 m;
  m << std::cos(a), -std::sin(a), 0.0, std::sin(a), std::cos(a), 0.0, 0.0, 0.0, 1.0;
  return m;
}
inline Mat3 rot_x(double a) {
  Mat3 m;
  m << 1.0, 0.0, 0.0, 0.0, std::cos(a), -std::sin(a), 0.0, std::sin(a), std::cos(a);
  return m;
}

inline Mat3 matrix_from_euler_zxz(const EulerZXZ& e) { return rot_z(e.psi) * rot_x(e.theta) * rot_z(e.phi); }

/// Result of extracting Euler angles: the angles, and whether R sat so close
/// to a singular attitude (sinθ below the threshold) that ψ and φ are not
/// separately defined there.
struct EulerZXZExtraction {
  EulerZXZ angles;
  bool singular = false;
};

/// Singular-aware extraction, θ ∈ [0, π]. Regular case: third row of R is
/// Γ = (sinθ sinφ, sinθ cosφ, cosθ), third column is (sinψ sinθ, −cosψ sinθ, cosθ).
/// Where sinθ < singular_threshold only ψ ± φ is defined (R = Rz(ψ ± φ) Rx(θ));
/// then φ is set to phi_hint (default 0, or the caller's previous spin angle
/// for continuity) and ψ absorbs the rest, and `singular` is set.
inline EulerZXZExtraction euler_zxz_from_matrix(const Mat3& R, double phi_hint = 0.0,
                                                double singular_threshold = 1e-9) {
  EulerZXZExtraction out;
  const double s = std::hypot(R(2, 0), R(2, 1));  // sinθ ≥ 0
  out.angles.theta = std::atan2(s, R(2, 2));
  if (s >= singular_threshold) {
    out.angles.phi = std::atan2(R(2, 0), R(2, 1));
    // ψ from the third column, atan2(R02, −R12), carries an error ε/sinθ that
    // does not cancel against φ's, so R was reproduced only to ~ε/sinθ (5e-7
    // just above the threshold). ψ ± φ are well conditioned:
    //   R00 + R11 = (1 + cosθ) cos(ψ + φ),  R10 − R01 = (1 + cosθ) sin(ψ + φ),
    //   R00 − R11 = (1 − cosθ) cos(ψ − φ),  R10 + R01 = (1 − cosθ) sin(ψ − φ);
    // taking ψ = (ψ ± φ) ∓ φ makes φ's error only tilt the axis of the small
    // rotation by θ (or π − θ), which costs O(ε) in R.
    const double psi = R(2, 2) >= 0.0 ? std::atan2(R(1, 0) - R(0, 1), R(0, 0) + R(1, 1)) - out.angles.phi
                                      : std::atan2(R(1, 0) + R(0, 1), R(0, 0) - R(1, 1)) + out.angles.phi;
    out.angles.psi = std::remainder(psi, 2.0 * std::numbers::pi);  // in [−π, π]
    return out;
  }
  out.singular = true;
  out.angles.phi = phi_hint;
  // θ ≈ 0: R ≈ Rz(ψ + φ); θ ≈ π: R ≈ Rz(ψ − φ) Rx(π). Both give
  // atan2(R10, R00) = ψ ± φ.
  const double combined = std::atan2(R(1, 0), R(0, 0));
  out.angles.psi = R(2, 2) > 0.0 ? combined - phi_hint : combined + phi_hint;
  return out;
}

/// Body angular velocity from Euler angle rates (docs/conventions.md §2).
inline Vec3 omega_from_euler_zxz_rates(const EulerZXZ& e, const Vec3& rates) {
  const double psid = rates.x(), thetad = rates.y(), phid = rates.z();
  const double st = std::sin(e.theta), ct = std::cos(e.theta);
  const double sp = std::sin(e.phi), cp = std::cos(e.phi);
  return {psid * st * sp + thetad * cp, psid * st * cp - thetad * sp, psid * ct + phid};
}

/// Euler angle rates from the body angular velocity (Trindade & Sampaio eq. 27).
/// Divides by sinθ: the caller must keep away from θ ∈ {0, π}.
inline Vec3 euler_zxz_rates_from_omega(const EulerZXZ& e, const Vec3& omega) {
  const double st = std::sin(e.theta), ct = std::cos(e.theta);
  const double sp = std::sin(e.phi), cp = std::cos(e.phi);
  const double a = (omega.x() * sp + omega.y() * cp) / st;
  return {a, omega.x() * cp - omega.y() * sp, omega.z() - ct * a};
}

/// Rotation vector chart: Ψ = log R with |Ψ| ≤ π, and its kinematics.
inline Vec3 rotation_vector_from_matrix(const Mat3& R) { return log_so3(R); }
inline Mat3 matrix_from_rotation_vector(const Vec3& psi) { return exp_so3(psi); }
inline Vec3 rotation_vector_rate(const Vec3& psi, const Vec3& omega) { return dexpinv_body(psi, omega); }

}  // namespace lgi::lie
