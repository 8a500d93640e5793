#pragma once
// The diagonal-inertia fast path of the DMV / LGVI / preprocessed DMV step
// (moser_veselov.hpp states the schemes; this file only solves their
// implicit equation more cheaply when the inertia tensor is diagonal).
//
// With F = cay(2f) = (I + f̂)(I − f̂)⁻¹ and a = h g (g = Π_k + ½ h M_k), the
// DMV equation φ(f) = a + a × f + (a·f) f − 2 J f = 0 of moser_veselov.hpp
// is (I − f̂ + f fᵀ) a = 2 J f, and as (I + f̂)(I − f̂ + f fᵀ) = (1 + |f|²) I,
// it is equivalent to the quadratic equation
//   2 w + 2 f × w − α a = 0,   w = J f,  α = 1 + |f|².
// For J = diag(I₁, I₂, I₃) divided by 2 I_i it reads
//   f_i = α b_i + k_i f_j f_k,   b_i = a_i / (2 I_i),  k₁ = (I₂ − I₃)/I₁ (cyclic),
// the form of Hairer & Vilmart, J. Phys. A 39 (2006) 13225, §5 (the
// quaternion form of DMV, c = f), which the authors iterate as a fixed point.
//
// The unknown here is w = J f, not f: with μ = J⁻¹ (the moments' inverses as
// stored, μ_i = 1/I_i rounded once per run, or the preprocessed schemes' 1/Ĩ_j
// as their series gives them) and f = μ ∘ w,
//   ψ(w) = 2 w + 2 f × w − α a = 0,   f = μ ∘ w,
//   ∂ψ_i/∂w_i = 2 − a_i g_i,  ∂ψ_i/∂w_j = d_i w_k − a_i g_j,  ∂ψ_i/∂w_k = d_i w_j − a_i g_k,
//   g = 2 μ ∘ f,  d_i = 2 (μ_j − μ_k)   ((i, j, k) cyclic),
// as ψ_i = 2 w_i + 2 (μ_j − μ_k) w_j w_k − α a_i. Near the root 2 w_i and a_i
// agree to within O(|f|), so 2 w_i − a_i is exact (Sterbenz), and ψ evaluated
// as ψ_i = (2 w_i − a_i) + (2 (f × w)_i − |f|² a_i) has a rounding error of ε
// times the cross terms, ε |f| |a|, not ε |a|. Solving for f instead, w = fl(J f)
// carries a rounding error of ε |a| into ψ, which an exact product (Dekker's,
// 36 operations a step) had to take out; solving for w needs none, and the
// step is 1/μ's DMV step (the body's moments to their last bit) with f rounded
// once, like every other product of the step. That rounding is independent
// from step to step: the energy error still grows like √n (tests/test_round_off.cpp:
// the energy of 10⁸ steps of the book, the growth exponent over 8 books and the
// bias of the solve's energy change; Hairer, McLachlan & Razakarivony, BIT 48 (2008)).
// ψ, not the divided form, is the equation solved: rounded quotients k_i
// would solve the equation of a slightly inconsistent body, whose energy
// drifts (10⁶ steps on the book: 3.7e-14 with the divided form, 2.7e-15 with ψ).
//
// A cold start takes two Gauss–Seidel sweeps of the divided fixed point
// from f = b as its guess, then Newton on ψ, whose Jacobian is solved by
// Cramer's rule (an adjugate and one division) and kept while the
// corrections shrink at least tenfold (simplified Newton). The guess always
// gets one Newton correction; from then on the stopping test, componentwise
// and without square roots, is |ψ_i| ≤ 4ε (2|w_i| + 2|f_j w_k| + 2|f_k w_j| + α|a_i|),
// the sum of the magnitudes of ψ_i's terms; then one more correction with
// the kept inverse Jacobian, as in the general solve (its header comment:
// without it the accepted iterate keeps an error of one sign that drifts the
// energy). At h|Ω| = 0.03 (Hairer & Vilmart's body at h = 0.01) the guess is
// within ~1e-9 and one Newton correction passes the test.
// Along a run of steps of one length the schemes start instead from an
// extrapolation of the last six solutions over their step lengths
// (CayleyPredictor, within ~3e-12 there): one Newton correction, accepted
// when the error it leaves is below 1e-19 |w| (solve_cayley_parameter_predicted). This takes
// the sweeps, a Jacobian and a residual off the step's dependent chain
// (docs/performance.md §3). The status has the corrections made before the test
// passed and the relative residual max_i |ψ_i| / max_i (sum of magnitudes)_i
// (for an accepted prediction, max_i |ψ_i| / (2 max_i |a_i|), the same to
// O(|f|) without forming the sums); a non-finite residual (diverged) or 50
// iterations end the solve unconverged. Same solution as the general path to
// round-off (tests/test_moser_veselov_diagonal.cpp).
//
// The preprocessed schemes use it with the modified moments Ĩ_j (1/Ĩ_j =
// css/I_j + cdd, moser_veselov.hpp), which are diagonal with J.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

#include "integrators/schemes/cayley_increment.hpp"
#include "integrators/schemes/cayley_quaternion.hpp"
#include "integrators/core/compensated_sum.hpp"
#include "integrators/core/scheme_interface.hpp"

namespace lgi::integrators::moser_veselov {

inline constexpr int max_newton_iterations = 50;

/// Whether J has exactly zero off-diagonal entries (then the fast path applies).
inline bool is_diagonal(const Mat3& J) {
  return J(0, 1) == 0.0 && J(0, 2) == 0.0 && J(1, 0) == 0.0 && J(1, 2) == 0.0 && J(2, 0) == 0.0 && J(2, 1) == 0.0;
}

/// The moments I, their inverses μ (the body the step solves for: f = μ ∘ w,
/// header comment) and the constants derived from them: k_i = (I_j − I_k) μ_i
/// for the cold start's guess, 2μ_i and d_i = 2 (μ_j − μ_k) for the Jacobian, and
/// the bound c = 2 (μ₁ + μ₂ + μ₃) ≥ 2 max μ of Newton's next error, |e| ≤ c |δ|²
/// (solve_cayley_parameter_predicted).
struct DiagonalMoments {
  Vec3 I = Vec3::Ones();
  Vec3 mu = Vec3::Ones();
  Vec3 two_mu = 2.0 * Vec3::Ones();
  Vec3 k = Vec3::Zero();
  Vec3 d = Vec3::Zero();
  double newton_bound = 6.0;
  DiagonalMoments() = default;
  DiagonalMoments(const Vec3& moments, const Vec3& inverse)
      : I(moments),
        mu(inverse),
        two_mu(2.0 * inverse),
        k((I.y() - I.z()) * mu.x(), (I.z() - I.x()) * mu.y(), (I.x() - I.y()) * mu.z()),
        d(2.0 * (mu.y() - mu.z()), 2.0 * (mu.z() - mu.x()), 2.0 * (mu.x() - mu.y())),
        newton_bound((two_mu.x() + two_mu.y()) + two_mu.z()) {}
};

/// The inverse of a 3×3 matrix a (row-major) by Cramer's rule, kept as its
/// adjugate and 1/det: x = A⁻¹ r is det_inv · (adj r).
struct Cramer3 {
  double adj[9] = {};
  double det_inv = 0.0;
  explicit Cramer3(const double (&a)[9]) {
    adj[0] = a[4] * a[8] - a[5] * a[7];
    adj[3] = a[5] * a[6] - a[3] * a[8];
    adj[6] = a[3] * a[7] - a[4] * a[6];
    det_inv = 1.0 / (a[0] * adj[0] + a[1] * adj[3] + a[2] * adj[6]);
    adj[1] = a[2] * a[7] - a[1] * a[8];
    adj[2] = a[1] * a[5] - a[2] * a[4];
    adj[4] = a[0] * a[8] - a[2] * a[6];
    adj[5] = a[2] * a[3] - a[0] * a[5];
    adj[7] = a[1] * a[6] - a[0] * a[7];
    adj[8] = a[0] * a[4] - a[1] * a[3];
  }
  void solve(double r0, double r1, double r2, double& x0, double& x1, double& x2) const {
    x0 = det_inv * (adj[0] * r0 + adj[1] * r1 + adj[2] * r2);
    x1 = det_inv * (adj[3] * r0 + adj[4] * r1 + adj[5] * r2);
    x2 = det_inv * (adj[6] * r0 + adj[7] * r1 + adj[8] * r2);
  }
};

/// ∂ψ/∂w at w with f = μ ∘ w (header comment), row-major.
inline Cramer3 diagonal_jacobian(const DiagonalMoments& m, const double (&a)[3], double w0, double w1, double w2,
                                 double f0, double f1, double f2) {
  const double g0 = m.two_mu.x() * f0, g1 = m.two_mu.y() * f1, g2 = m.two_mu.z() * f2;
  const double d0 = m.d.x(), d1 = m.d.y(), d2 = m.d.z();
  const double j[9] = {2.0 - a[0] * g0,     d0 * w2 - a[0] * g1, d0 * w1 - a[0] * g2,
                       d1 * w2 - a[1] * g0, 2.0 - a[1] * g1,     d1 * w0 - a[1] * g2,
                       d2 * w1 - a[2] * g0, d2 * w0 - a[2] * g1, 2.0 - a[2] * g2};
  return Cramer3(j);
}

/// ψ(w) (header comment) at one iterate, with the terms its stopping test weighs.
struct DiagonalPsi {
  double r0, r1, r2;                  // ψ(w), rounding error O(ε |f × w|) (header comment)
  double f0, f1, f2, ff;              // f = μ ∘ w, |f|²
  double w0, w1, w2;                  // the iterate
  double p01, p10, p02, p20, p12, p21;  // f_i w_j
  DiagonalPsi(const DiagonalMoments& m, const double (&a)[3], double x0, double x1, double x2)
      : f0(m.mu.x() * x0), f1(m.mu.y() * x1), f2(m.mu.z() * x2), w0(x0), w1(x1), w2(x2) {
    ff = (f0 * f0 + f1 * f1) + f2 * f2;
    p01 = f0 * w1, p10 = f1 * w0, p02 = f0 * w2, p20 = f2 * w0, p12 = f1 * w2, p21 = f2 * w1;
    // (2 w_i − a_i) exact near the root (header comment)
    r0 = (2.0 * w0 - a[0]) + (2.0 * (p12 - p21) - ff * a[0]);
    r1 = (2.0 * w1 - a[1]) + (2.0 * (p20 - p02) - ff * a[1]);
    r2 = (2.0 * w2 - a[2]) + (2.0 * (p01 - p10) - ff * a[2]);
  }
  Cramer3 jacobian(const DiagonalMoments& m, const double (&a)[3]) const {
    return diagonal_jacobian(m, a, w0, w1, w2, f0, f1, f2);
  }
};

/// ψ(w) and its stopping test at one iterate.
struct DiagonalResidual : DiagonalPsi {
  double scale;  // max_i of the sum of the magnitudes of ψ_i's terms
  bool small;    // |ψ_i| ≤ 4ε (2|w_i| + 2|f_j w_k| + 2|f_k w_j| + α|a_i|) for every i
  DiagonalResidual(const DiagonalMoments& m, const double (&a)[3], double x0, double x1, double x2)
      : DiagonalPsi(m, a, x0, x1, x2) {
    constexpr double tol = 4.0 * std::numeric_limits<double>::epsilon();
    const double alpha = 1.0 + ff;
    const double s0 = 2.0 * (std::abs(w0) + (std::abs(p12) + std::abs(p21))) + alpha * std::abs(a[0]);
    const double s1 = 2.0 * (std::abs(w1) + (std::abs(p20) + std::abs(p02))) + alpha * std::abs(a[1]);
    const double s2 = 2.0 * (std::abs(w2) + (std::abs(p01) + std::abs(p10))) + alpha * std::abs(a[2]);
    small = std::abs(r0) <= tol * s0 && std::abs(r1) <= tol * s1 && std::abs(r2) <= tol * s2;
    scale = std::max({s0, s1, s2});
  }
  /// The status's relative residual: max_i |ψ_i| / max_i (sum of magnitudes)_i.
  double relative() const {
    const double r = std::max({std::abs(r0), std::abs(r1), std::abs(r2)});
    return scale > 0.0 ? r / scale : r;
  }
};

/// The status's residual of an accepted prediction (solve_cayley_parameter_predicted):
/// max_i |ψ_i| / (2 max_i |a_i|). Near the root 2 w ≈ a, so each sum of
/// magnitudes of DiagonalResidual is 2|a_i| (1 + O(|f|)), and this is its
/// relative residual to O(|f|), without the twelve magnitudes and the test
/// (7% of a predicted step's instructions).
inline double prediction_residual(const DiagonalPsi& r, const double (&a)[3]) {
  const double psi = std::max(std::max(std::abs(r.r0), std::abs(r.r1)), std::abs(r.r2));
  const double big = 2.0 * std::max(std::max(std::abs(a[0]), std::abs(a[1])), std::abs(a[2]));
  return big > 0.0 ? psi / big : psi;
}

/// A solution of ψ(w) = 0 and its Cayley parameter f = μ ∘ w, formed where w
/// is (in registers: a Vec3 stored by the solve and reloaded to form f put one
/// more store-to-load forwarding on the step's chain, 3 ns of a 55 ns step).
struct DiagonalSolution {
  Vec3 w = Vec3::Zero(), f = Vec3::Zero();
  void set(const DiagonalMoments& m, double w0, double w1, double w2) {
    w = Vec3(w0, w1, w2);
    f = Vec3(m.mu.x() * w0, m.mu.y() * w1, m.mu.z() * w2);
  }
};

/// Newton on ψ from the iterate (w0, w1, w2) with the inverse Jacobian D, the
/// corrections made so far counted in `done` (header comment: the stopping
/// test, the final correction, simplified Newton); out holds the last iterate on return.
inline StepStatus diagonal_newton(const DiagonalMoments& m, const double (&a)[3], double w0, double w1, double w2,
                                  Cramer3 D, double last_step2, int done, DiagonalSolution& out) {
  bool renew = false;  // the Jacobian at this iterate (simplified Newton, below)
  for (int it = done;; ++it) {
    const DiagonalResidual r(m, a, w0, w1, w2);
    if (renew) D = r.jacobian(m, a);
    double d0, d1, d2;
    D.solve(r.r0, r.r1, r.r2, d0, d1, d2);
    if (r.small || it == max_newton_iterations || !std::isfinite(r.r0 + r.r1 + r.r2)) {
      if (r.small) {  // the final correction (header comment)
        w0 -= d0;
        w1 -= d1;
        w2 -= d2;
      }
      out.set(m, w0, w1, w2);
      return {r.small, it, r.relative()};
    }
    w0 -= d0;
    w1 -= d1;
    w2 -= d2;
    // Simplified Newton: the Jacobian is renewed (at the new iterate) only when the
    // corrections shrink by less than a factor 10 (θ = |δ_n|/|δ_{n−1}| > 0.1).
    const double step2 = d0 * d0 + d1 * d1 + d2 * d2;
    renew = step2 > 0.01 * last_step2;
    last_step2 = step2;
  }
}

/// Newton solve of ψ(w) = 0 for the diagonal moments m, step h and g (a = h g;
/// header comment) from the Gauss–Seidel guess; out holds the last iterate w = J f
/// and its f on return.
inline StepStatus solve_cayley_parameter_diagonal(const DiagonalMoments& m, double h, const Vec3& g,
                                                  DiagonalSolution& out) {
  const double a[3] = {h * g.x(), h * g.y(), h * g.z()};
  // Starting guess: two Gauss–Seidel sweeps of the fixed point f = α b + K(f), b_i = a_i/(2 I_i), from f = b.
  const double b0 = 0.5 * m.mu.x() * a[0], b1 = 0.5 * m.mu.y() * a[1], b2 = 0.5 * m.mu.z() * a[2];
  const double k0 = m.k.x(), k1 = m.k.y(), k2 = m.k.z();
  double f0 = b0, f1 = b1, f2 = b2;
  for (int sweep = 0; sweep < 2; ++sweep) {
    const double alpha = 1.0 + ((f0 * f0 + f1 * f1) + f2 * f2);
    f0 = alpha * b0 + k0 * f1 * f2;
    f1 = alpha * b1 + k1 * f0 * f2;
    f2 = alpha * b2 + k2 * f0 * f1;
  }
  // The guess is not tested: one Newton correction always (then a zero one if it was exact).
  const DiagonalPsi r(m, a, m.I.x() * f0, m.I.y() * f1, m.I.z() * f2);
  const Cramer3 D = r.jacobian(m, a);
  double d0, d1, d2;
  D.solve(r.r0, r.r1, r.r2, d0, d1, d2);
  return diagonal_newton(m, a, r.w0 - d0, r.w1 - d1, r.w2 - d2, D, d0 * d0 + d1 * d1 + d2 * d2, 1, out);
}

/// The same solve from a predicted iterate (CayleyPredictor): one Newton
/// correction δ from ψ and the Jacobian at the prediction. ψ is quadratic, so
/// the corrected iterate's error is e = ∂ψ⁻¹ Q(δ, δ) with Q its quadratic part,
/// 2 (μ_j − μ_k) δ_j δ_k − |μ ∘ δ|² a_i in component i, and ∂ψ = 2 I + O(|f|):
/// |e| ≤ c |δ|² with c = 2 (μ₁ + μ₂ + μ₃) (DiagonalMoments::newton_bound, with
/// a factor 2 to spare). The result is accepted when c |δ|² ≤ 1e-19 |w|,
/// tested as (c |δ|²)² ≤ 1e-38 |w|² (no square root): its Newton error is then
/// below ε/1000 relative, far below the rounding of w itself, whatever the
/// body's shape and step (a test |δ| ≤ 1e-10 |w| alone, the first version's,
/// leaves c |δ|²/|w| = c |w| 1e-20 to the body: at a moment ratio of 1000 and
/// h|Ω| ≈ 1 that is 1e-17; on Hairer & Vilmart's body at h = 0.01 it allows
/// |δ| up to ~1.7e-9 |w| instead of 1e-10, where guesses of 1.1e-10 occur). The
/// correction was computed from a residual whose rounding error is ε |f × w|,
/// as in the final correction of the cold solve (so no bias either). Otherwise
/// Newton goes on from the corrected iterate exactly as the cold solve does.
/// The status of an accepted prediction: 1 correction, and the relative
/// residual of the prediction (the last iterate), max_i |ψ_i| / (2 max_i |a_i|)
/// (prediction_residual: the stopping test's own scale is not formed here).
inline StepStatus solve_cayley_parameter_predicted(const DiagonalMoments& m, double h, const Vec3& g,
                                                   const Vec3& prediction, DiagonalSolution& out) {
  const double a[3] = {h * g.x(), h * g.y(), h * g.z()};
  const double p0 = prediction.x(), p1 = prediction.y(), p2 = prediction.z();
  const DiagonalPsi r(m, a, p0, p1, p2);  // no stopping test: the correction's size decides
  const Cramer3 D = r.jacobian(m, a);
  double d0, d1, d2;
  D.solve(r.r0, r.r1, r.r2, d0, d1, d2);
  const double w0 = p0 - d0, w1 = p1 - d1, w2 = p2 - d2;
  const double step2 = (d0 * d0 + d1 * d1) + d2 * d2;
  const double error_bound = m.newton_bound * step2;
  if (error_bound * error_bound <= 1e-38 * ((w0 * w0 + w1 * w1) + w2 * w2) && std::isfinite(step2)) {
    out.set(m, w0, w1, w2);
    return {true, 1, prediction_residual(r, a)};
  }
  return diagonal_newton(m, a, w0, w1, w2, D, step2, 1, out);
}

/// A guess of the next step's unknown w = J f (header comment) from the last six, by
/// extrapolation with the order-5 backward-difference formula
///   u_{k+1} ≈ 6 u_k − 15 u_{k−1} + 20 u_{k−2} − 15 u_{k−3} + 6 u_{k−4} − u_{k−5},
/// exact for a polynomial of degree 5 in t (Hairer, Nørsett & Wanner I, §III.1,
/// the predictor of Adams methods), of u = w/h; the guess for a step of
/// length h is h u_{k+1}. Along a trajectory w(t) = ½ h Π + O(h³) is smooth, so
/// at h|Ω| = 0.03 (Hairer & Vilmart's body at h = 0.01) the guess is within
/// ~3e-12 of the root, and one Newton correction reaches round-off
/// (solve_cayley_parameter_predicted). It extrapolates u = w/h, not w, because
/// a fixed-step run's h = t_{k+1} − t_k is not constant: the grid t_k = t0 + k dt
/// is rounded, so h jitters by ulp(t), a relative 1.8e-10 at t = 10⁴ for
/// dt = 0.01. Extrapolated w carried that jitter, times the formula's weights,
/// into the guess, which then missed the 1e-10 acceptance and cost more Newton
/// work; past a relative jitter of 1e-9 (t ≥ 2¹⁶ at dt = 0.01) the history was
/// dropped whenever h changed. u = ½ Π + O(h²) moves with h only in its O(h²)
/// part. The guess is computed from the previous steps alone, so it stands off
/// the step's chain of dependent operations (Π → f → Π), where the cold guess's
/// sweeps stood. The history holds steps of one length h to 1e-6 relative (far
/// above the grid's jitter); a step of another length, or a failed step,
/// starts it anew. The guess only decides where Newton starts: it changes the
/// accepted w at the level of its rounding, so the history is part of the
/// scheme's memory in a checkpoint (save/restore), and a resumed run goes on
/// bit for bit.
struct CayleyPredictor {
  static constexpr int points = 6;
  // u[0] = w_k / h_k, u[1] = w_{k−1} / h_{k−1}, … (zeros: Eigen leaves a default Vec3 unset)
  std::array<Vec3, points> u = {Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  int count = 0;                 // valid entries
  double h = 0.0;                // the step length of the history
  bool ready(double step) const { return count == points && same_length(step); }
  bool same_length(double step) const { return std::abs(step - h) <= 1e-6 * std::abs(h); }
  Vec3 guess(double step) const {
    return step * (((6.0 * u[0] - 15.0 * u[1]) + (20.0 * u[2] - 15.0 * u[3])) + (6.0 * u[4] - u[5]));
  }
  void record(double step, const Vec3& value) {
    if (count == 0 || !same_length(step)) count = 0, h = step;
    for (int i = points - 1; i > 0; --i) u[static_cast<std::size_t>(i)] = u[static_cast<std::size_t>(i - 1)];
    u[0] = (1.0 / step) * value;
    count = std::min(count + 1, points);
  }
  void reset() { count = 0; }
  static constexpr std::size_t memory_size = 2 + 3 * points;
  void save(std::vector<double>& out) const {
    out.push_back(static_cast<double>(count));
    out.push_back(h);
    for (const Vec3& v : u) out.insert(out.end(), {v.x(), v.y(), v.z()});
  }
  bool restore(std::span<const double> in) {
    if (in.size() != memory_size || !(in[0] >= 0.0 && in[0] <= points) || in[0] != std::floor(in[0])) return false;
    count = static_cast<int>(in[0]);
    h = in[1];
    for (std::size_t i = 0; i < u.size(); ++i) u[i] = Vec3(in[2 + 3 * i], in[3 + 3 * i], in[4 + 3 * i]);
    return true;
  }
};

/// The rounding errors of a run's compensated state updates (compensated_sum.hpp).
struct Carry {
  Vec3 Pi = Vec3::Zero();
  Mat3 R = Mat3::Zero();
};

/// What a DMV scheme carries from step to step: the carries of its compensated
/// sums and the predictor's history; a checkpoint's scheme memory
/// (scheme_interface.hpp, "Resume"), carries first.
struct StepMemory {
  Carry carry{};
  CayleyPredictor predictor{};
  void reset() {
    carry = {};
    predictor.reset();
  }
  void save(std::vector<double>& out) const {
    out.insert(out.end(), carry.Pi.data(), carry.Pi.data() + 3);
    out.insert(out.end(), carry.R.data(), carry.R.data() + 9);
    predictor.save(out);
  }
  bool restore(std::span<const double> in) {
    if (in.size() != 12 + CayleyPredictor::memory_size || !predictor.restore(in.subspan(12))) return false;
    carry.Pi = Vec3(in[0], in[1], in[2]);
    for (int i = 0; i < 9; ++i) carry.R.data()[i] = in[static_cast<std::size_t>(3 + i)];
    return true;
  }
};

/// R ← R F, Π ← Fᵀ Π for F = cay(2f), applied as compensated increments with
/// F − I = c N (cayley_increment.hpp).
inline void apply_cayley_step(const Vec3& f, State& s, Carry& carry) {
  const double fa[3] = {f.x(), f.y(), f.z()};
  const CayleyIncrement<double> F(fa);
  // The state and the carries are read into locals and written once at the end:
  // through the references the compiler must assume they alias, and reloads
  // them after every store.
  double P[3], cP[3], R[9], cR[9];
  for (int i = 0; i < 3; ++i) P[i] = s.Pi(i), cP[i] = carry.Pi(i);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R[3 * i + j] = s.R(i, j), cR[3 * i + j] = carry.R(i, j);
  double cN[9];
  for (int k = 0; k < 9; ++k) cN[k] = F.c * F.N[k];
  double dP[3], dR[9];  // all increments from the old state, then the compensated sums
  F.momentum_increment(P, dP);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) dR[3 * i + j] = (R[3 * i] * cN[j] + R[3 * i + 1] * cN[3 + j]) + R[3 * i + 2] * cN[6 + j];
  for (int j = 0; j < 3; ++j) add_compensated(P[j], dP[j], cP[j]);
  for (int k = 0; k < 9; ++k) add_compensated(R[k], dR[k], cR[k]);
  for (int i = 0; i < 3; ++i) s.Pi(i) = P[i], carry.Pi(i) = cP[i];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) s.R(i, j) = R[3 * i + j], carry.R(i, j) = cR[3 * i + j];
}

/// The same step with the attitude kept as a quaternion (cayley_quaternion.hpp):
/// Π as above, to the bit, and q ← q ⊗ p; s.R is left as it was.
inline void apply_cayley_step(const Vec3& f, State& s, Carry& carry, CayleyQuaternion& attitude) {
  const double fa[3] = {f.x(), f.y(), f.z()};
  const CayleyIncrement<double> F(fa);
  double P[3], cP[3], dP[3];
  for (int i = 0; i < 3; ++i) P[i] = s.Pi(i), cP[i] = carry.Pi(i);
  F.momentum_increment(P, dP);
  for (int j = 0; j < 3; ++j) add_compensated(P[j], dP[j], cP[j]);
  attitude.rotate(fa, F.ff);
  for (int i = 0; i < 3; ++i) s.Pi(i) = P[i], carry.Pi(i) = cP[i];
}

/// One DMV step of length h with diagonal moments m on the state as it is
/// (no kicks); state and carry are untouched if the solve fails. With a
/// predictor, the solve starts from its guess once it holds six steps of this
/// length, and the accepted w = J f is recorded (a failure starts it anew).
/// With an attitude, the step rotates it and leaves s.R (cayley_quaternion.hpp).
inline StepStatus dmv_step_diagonal(const DiagonalMoments& m, State& s, Carry& carry, double h,
                                    CayleyPredictor* predictor = nullptr, CayleyQuaternion* attitude = nullptr) {
  DiagonalSolution x;
  const StepStatus st = predictor && predictor->ready(h)
                            ? solve_cayley_parameter_predicted(m, h, s.Pi, predictor->guess(h), x)
                            : solve_cayley_parameter_diagonal(m, h, s.Pi, x);
  if (st.converged) {
    if (attitude) apply_cayley_step(x.f, s, carry, *attitude);
    else apply_cayley_step(x.f, s, carry);
  }
  if (predictor) {
    if (st.converged) predictor->record(h, x.w);
    else predictor->reset();
  }
  return st;
}

}  // namespace lgi::integrators::moser_veselov
