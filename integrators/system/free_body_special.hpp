#pragma once
// Internal: the pieces of the exact free flow that FreeBodyExactFlow
// (free_body_exact.cpp, one initial state, many times) and FreeBodyFlowStepper
// (free_body_flow_stepper.cpp, one step from any state) both use, kept in one
// copy so that the two evaluate the same formulas in the same order.
// Formulas, frames and references: free_body_exact.hpp.
#include <array>

#include "lie/so3.hpp"

namespace lgi::system::free_body_detail {

using lie::Mat3;
using lie::Vec3;

// ── Special functions ───────────────────────────────────────────────────────
/// Carlson's R_F and R_J (Boost.Math, duplication algorithm) in plain double.
double carlson_rf(double x, double y, double z);
double carlson_rj(double x, double y, double z, double p);

/// Δ = G² − 2T I2 from Π and the moments I in the ascending principal frame,
/// correct to a few ulps (numerator in double-double).
double separatrix_distance(const Vec3& pi, const Vec3& I);

// ── Frames ──────────────────────────────────────────────────────────────────
struct PrincipalFrame {
  Vec3 I;  // moments, ascending
  Mat3 P;  // x_body = P x_principal, det +1
};
/// The principal moments sorted ascending with their axes as a proper rotation.
PrincipalFrame sorted_principal_frame(const Vec3& principal, const Mat3& axes);

struct WorkingFrame {
  Mat3 Q;  // x_body = Q x_w
  Vec3 I;  // (I1, I2, I3)
};
/// The working frame for Δ ≥ 0 (the principal one) or, `reversed`, for Δ < 0:
/// (e3, −e2, e1) with the moments reversed.
WorkingFrame working_frame(const PrincipalFrame& principal, bool reversed);
/// Q rotated by π about its first axis (turns Π3 < 0 into Π3 > 0).
Mat3 half_turn(const Mat3& Q);

/// The principal axis (0, 1, 2) Π lies along, if two of its principal
/// components are exactly 0 (steady rotation); otherwise −1.
int steady_axis(const Vec3& pi_p);

/// B(Π_w) = Rx(θ) Rz(φ), third row Π_w/|Π_w| (free_body_exact.hpp, "R(t)").
Mat3 alignment(const Vec3& pi_w);
/// Rz(ψ) B.
Mat3 precessed(double psi, const Mat3& B);

// ── Jacobi elliptic functions from k' (AGM chain, Bulirsch's Gauss steps) ───
constexpr int kMaxAgm = 24;

struct Jacobi {
  double sn, cn, dn;
};
/// AGM table (level i = 0 … n−1): a_{i+1}, b_i, a_i/a_{i+1}; scale = a_N = π/(2K).
struct Agm {
  int n = 0;
  double scale = 1.0;
  std::array<double, kMaxAgm> a{}, b{}, ratio{};
};
Agm build_agm(double k, double kc);
Jacobi jacobi_small(const Agm& agm, double v);                         // 0 ≤ v ≤ K/2
Jacobi jacobi_reduced(const Agm& agm, double K, double kc, double r);  // |r| ≤ K (cn ≥ 0)

/// u = 2K j + r, |r| ≤ K: the functions at r; sn(u), cn(u) are `sign` times theirs.
struct ReducedPhase {
  double j, sign;
  Jacobi f;
};
ReducedPhase reduce_phase(const Agm& agm, double K, double kc, double u);

/// (sn u0, cn u0) ∝ (Π2/b, Π1/a1), normalised (cn u0 ≥ 0 as a1 carries Π1's sign).
struct SinCos {
  double s, c;
};
SinCos phase_angle(const Vec3& pi_w, double a1, double b);
/// u0 = F(φ0) = sin φ0 R_F(cos²φ0, cos²φ0 + k'² sin²φ0, 1), φ0 ∈ [−π/2, π/2].
double incomplete_first(const SinCos& phi, double kc2);
/// Z(am u) = Π(n; am u) − u = (n/3) sn³ R_J(cn², dn², 1, 1 − n sn²), |am u| ≤ π/2.
double z_am(const Jacobi& f, double n, double n_third);

}  // namespace lgi::system::free_body_detail
