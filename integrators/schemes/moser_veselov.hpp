#pragma once
// Schemes `dmv` and `lgvi`: the discrete Moser–Veselov algorithm and its Lie
// group variational form with a potential, and the step they share with the
// preprocessed (modified-inertia) high-order versions `dmv-pre4` … `dmv-pre10`
// (moser_veselov_preprocessed.hpp).
//
// ── DMV / LGVI ──────────────────────────────────────────────────────────────
// Lee, Leok & McClamroch, "A Lie group variational integrator for the
// attitude dynamics of a rigid body with applications to the 3D pendulum",
// Proc. IEEE Conf. Control Applications (2005); and CMAME 196 (2007)
// (docs/math.md §5, which states the scheme in this project's
// body-form conventions). With M(R) the body torque of the
// potential terms only (gravity m g Γ × χ, the spring −k log(R_restᵀR)) and
// the non-standard inertia J_d = ½ tr(J) I − J:
//   h (Π_k + ½ h M_k)^ = F_k J_d − J_d F_kᵀ,
//   R_{k+1} = R_k F_k,
//   Π_{k+1} = F_kᵀ Π_k + ½ h F_kᵀ M_k + ½ h M_{k+1}.
// This is kick(½h) ∘ DMV(h) ∘ kick(½h) with kick(τ): Π += τ M(R), which the
// class exposes (kick, free_step) so compositions can merge half kicks.
// With M = 0 it is the discrete Moser–Veselov algorithm (Moser & Veselov,
// Commun. Math. Phys. 139 (1991) 217–243) in the form of Hairer & Vilmart
// (2006) eqs. (3)–(4) with Ω_nᵀ = F_k and D = J_d (their eq. (5)).
// Writing F = cay(2f) = (I + f̂)(I − f̂)⁻¹, the first equation is the
// 3-vector equation (docs/math.md §5 ✓; Hairer–Vilmart §5, eqs. (16)–(18), solve
// the same step for diagonal J by a fixed-point iteration on a quaternion
// form; the tests check that both give the same numbers)
//   φ(f) = h g + h g × f + (h g·f) f − 2 J f = 0,   g = Π_k + ½ h M_k,
//   ∂φ/∂f = (h g)^ + (h g·f) I + f (h g)ᵀ − 2 J,
// solved for a diagonal J by the fast path of moser_veselov_diagonal.hpp (the
// equivalent quadratic form 2(I + f̂)Jf = (1 + |f|²) hg, componentwise, a
// Gauss–Seidel starting guess, or along a run of equal steps an extrapolation
// of the last six solutions, Newton by Cramer's rule, no square root; one
// Newton correction per step at moderate h|Ω|), and otherwise (J the full
// tensor, non-diagonal) by Newton from f₀ = ½ h J⁻¹ g
// to |φ| ≤ 4ε·(|hg| + |hg × f| + |hg·f||f| + 2|Jf|), the sum
// of the magnitudes of its terms, at most 50 iterations, followed by one more
// correction with the last inverse Jacobian: an iterate that merely passes the
// test keeps an error of the tolerance's size, of a sign that repeats along a
// trajectory, and drifts the energy (10⁸ steps on the book at dt = 0.01:
// 6.5e-12 without it, 5.5e-13 with it and the compensated updates below). For F the
// rotation by θ about the unit vector n, F J_d − J_d Fᵀ =
// (sin θ J n + (1 − cos θ) n × J n)^, so |hg| ≤ 2 sin(θ/2) |J n|, and a spin
// about a principal axis has sin θ = h|Ω| exactly: there no solution exists
// once h|Ω| > 1, and none anywhere once |hg| > 2 λ_max(J). A Cayley step
// cannot rotate by π or more (|f| = tan(θ/2) → ∞). Newton then
// fails within its limit and the step returns converged = false with the
// iterations and the final relative residual |φ|/scale, leaving the state
// untouched. A step with |h| |J⁻¹g| ≥ π, which the exact flow would turn by
// about π or more, is refused the same way before any iteration (0
// iterations, residual reported as inf), as a solution the equations may
// still have there approximates nothing.
// Order 2; symplectic and symmetric (a variational integrator; DMV is
// RATTLE for the constrained formulation, HLW GNI §VII.5.3). Conserves to
// round-off: |Π| (F orthogonal), the spatial momentum R Π of a free body,
// Π·Γ of any potential invariant about the vertical (the kick is ⊥ Γ and
// Γ_{k+1} = F_kᵀ Γ_k), the free body's energy ½ Π·J⁻¹Π (Hairer–Vilmart §1),
// and RᵀR = I up to round-off accumulation (no renormalisation).
// Round-off: the updates are applied as increments, R ← R + R(F − I) and
// Π ← Π + (F − I)ᵀΠ with F − I = 2/(1 + |f|²)(f̂ + f̂²) (the Cayley map's
// closed form, lie/so3.hpp), and the kicks as Π ← Π + τM, all summed with
// compensation (compensated_sum.hpp; Hairer, McLachlan & Razakarivony,
// BIT 48 (2008)), the carries kept per run by the scheme. The carries and the
// predictor's history are the scheme's memory in a checkpoint (save_memory),
// so a resumed run goes on bit for bit (tests/test_resume.cpp). With the final
// Newton correction above, on the book at dt = 0.01 (tests/test_round_off.cpp)
// the energy error of 10⁶ / 10⁸ steps is 7.2e-15 / 5.5e-13 (1.9e-13 / 7.0e-12
// before), |Π| 4.7e-15 / 2.2e-14 (1.3e-13 at 10⁶ before); the energy still
// grew nearly linearly, from a level twelve times lower. The diagonal path
// then also took the residual's own rounding error out of the final correction
// (moser_veselov_diagonal.hpp): 3.1e-14 after 10⁸ steps, growing like √n.
#include <array>
#include <bit>
#include <cstdint>
#include <cmath>
#include <limits>
#include <numbers>
#include <span>
#include <vector>

#include "integrators/core/compensated_sum.hpp"
#include "integrators/schemes/moser_veselov_diagonal.hpp"
#include "integrators/core/scheme_interface.hpp"

namespace lgi::integrators {

namespace moser_veselov {

/// Whether the model has any torque; its potential part M(R) is
/// model.potential_torque(R), the sum of the terms' potential torques (a drive
/// and a damper contribute none: schemes using M run on conservative scenes).
template <class Model>
inline constexpr bool has_potential = Model::has_torque;

/// Newton solve of φ(f) = hg + hg × f + (hg·f) f − 2 J f = 0 (header
/// comment). On return f holds the last iterate; the status has the Newton
/// iterations performed and the relative residual |φ|/scale.
inline StepStatus solve_cayley_parameter(const Mat3& J, const Mat3& J_inv, const Vec3& hg, Vec3& f) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  StepStatus st{false, 0, 0.0};
  f = 0.5 * (J_inv * hg);
  const double hg_norm = hg.norm();
  Mat3 D_inv = Mat3::Zero();  // the last Newton step's inverse Jacobian
  for (int it = 0;; ++it) {
    const Vec3 Jf = J * f;
    const Vec3 cross = hg.cross(f);
    const double dot = hg.dot(f);
    const Vec3 r = hg + cross + dot * f - 2.0 * Jf;
    const double scale = hg_norm + cross.norm() + std::abs(dot) * f.norm() + 2.0 * Jf.norm();
    const double rn = r.norm();
    st.iterations = it;
    st.residual = scale > 0.0 ? rn / scale : rn;
    if (!std::isfinite(rn) || !std::isfinite(scale)) return st;  // diverged: not converged
    if (rn <= 4.0 * eps * scale) {
      // One more correction with the last inverse Jacobian (header comment:
      // the stopping test alone leaves an error whose sign repeats from step
      // to step, an energy drift).
      if (it > 0) f -= D_inv * r;
      st.converged = true;
      return st;
    }
    if (it == max_newton_iterations) return st;
    Mat3 D = lie::hat(hg) + f * hg.transpose() - 2.0 * J;
    D.diagonal().array() += dot;
    D_inv = D.inverse();  // closed-form 3×3 inverse; a singular D gives non-finite f, caught above
    f -= D_inv * r;
  }
}

/// The status of a step refused before any Newton iteration (see
/// turns_too_far and the modified-inertia check): not converged, 0
/// iterations, an infinite residual, and the reason.
inline StepStatus refused_step(const char* reason) {
  return {false, 0, std::numeric_limits<double>::infinity(), reason};
}
inline constexpr const char* turns_too_far_reason =
    "step refused: it would turn the body by pi or more (|h Omega| >= pi), which no Cayley step represents; "
    "reduce --dt";

/// Whether the exact flow would turn the body by π or more in this step
/// (|h| |Ω| ≥ π, Ω = J⁻¹Π): no Cayley step F = cay(2f), whose angle is
/// 2 atan|f| < π, can represent that, and any solution the equations still
/// have there is not an approximation of the flow; such a step is refused.
inline bool turns_too_far(const Mat3& J_inv, const Vec3& Pi, double h) {
  return !(std::abs(h) * (J_inv * Pi).norm() < std::numbers::pi);
}

/// One DMV step of length h with inertia J (inverse J_inv) on the state as
/// it is (no kicks): R ← R F, Π ← Fᵀ Π, F = cay(2f), applied as compensated
/// increments (header comment). The state and the carry are left untouched
/// if the solve fails. With an attitude, the step rotates it and leaves s.R
/// (cayley_quaternion.hpp).
inline StepStatus dmv_step(const Mat3& J, const Mat3& J_inv, State& s, Carry& carry, double h,
                           CayleyQuaternion* attitude = nullptr) {
  Vec3 f;
  const StepStatus st = solve_cayley_parameter(J, J_inv, h * s.Pi, f);
  if (st.converged) {
    if (attitude) apply_cayley_step(f, s, carry, *attitude);
    else apply_cayley_step(f, s, carry);
  }
  return st;
}

/// The modified moments of a free body for the last few step lengths h, a
/// direct-mapped table on a hash of h's bits. A fixed-step run's
/// h = t_{k+1} − t_k takes a dozen or so values that differ in the last bits
/// (t_k = t0 + k dt is computed, not accumulated), so a one-entry cache missed
/// most steps and the series and three divisions were redone at ~17 ns a step.
/// A hit returns the moments computed from the same h, so the run's numbers do
/// not depend on what the table holds.
struct MomentsByStep {
  static constexpr std::size_t size = 8;
  std::array<double, size> h = [] {  // NaN: an empty slot (equal to no step)
    std::array<double, size> a{};
    a.fill(std::numeric_limits<double>::quiet_NaN());
    return a;
  }();
  std::array<DiagonalMoments, size> moments{};
  // Fibonacci hashing of h's bits (Knuth, TAOCP 3, §6.4): the h of one run share
  // their low mantissa bits (they differ by multiples of ulp(t)), so those alone would collide.
  static std::size_t slot(double step) {
    return static_cast<std::size_t>((std::bit_cast<std::uint64_t>(step) * 0x9E3779B97F4A7C15ull) >> 61);
  }
  const DiagonalMoments* find(double step) const {
    const std::size_t i = slot(step);
    return h[i] == step ? &moments[i] : nullptr;
  }
  void insert(double step, const DiagonalMoments& m) {
    const std::size_t i = slot(step);
    h[i] = step;
    moments[i] = m;
  }
};

/// The per-run constants of the diagonal fast path (moser_veselov_diagonal.hpp):
/// whether J is diagonal, its moments and their inverses.
struct DiagonalInertia {
  bool diagonal = false;
  Vec3 I = Vec3::Ones(), J_inv = Vec3::Ones();
  DiagonalMoments moments{};
  DiagonalInertia() = default;
  template <class InertiaT>
  explicit DiagonalInertia(const InertiaT& inertia)
      : diagonal(is_diagonal(inertia.J)), I(inertia.J.diagonal()), J_inv(inertia.J_inv.diagonal()),
        moments(I, I.cwiseInverse()) {}
  /// |h Ω|² < π² with Ω = J⁻¹Π (turns_too_far for a diagonal J, without a square root).
  bool turns_too_far(const Vec3& Pi, double h) const {
    return !((h * h) * J_inv.cwiseProduct(Pi).squaredNorm() < std::numbers::pi * std::numbers::pi);
  }
};

}  // namespace moser_veselov

namespace moser_veselov {
/// kick(½h) ∘ free_step(h) ∘ kick(½h) for lgvi and the preprocessed DMV
/// schemes; the state is left untouched if the free step fails. One field
/// evaluation per step is counted (the implicit stage; the potential torque
/// at the new attitude is the next step's first kick).
template <class Scheme, class Model>
StepStatus strang_step(Scheme& scheme, const Model& model, State& s, Carry& carry, double t, double h,
                       WorkCounters& work) {
  if constexpr (!has_potential<Model>) {  // no kicks: the free step alone, which leaves s untouched on failure
    const StepStatus st = scheme.free_step(model, s, carry, h);
    if (st.converged) work.rhs_evaluations += 1;
    return st;
  }
  State x = s;
  Carry c = carry;
  scheme.kick(model, x, c, t, 0.5 * h);
  const StepStatus st = scheme.free_step(model, x, c, h);
  if (!st.converged) return st;
  scheme.kick(model, x, c, t + h, 0.5 * h);
  s = x;
  carry = c;
  work.rhs_evaluations += 1;
  return st;
}
}  // namespace moser_veselov

/// `lgvi` (and `dmv`, the same algorithm, which the registry keeps to free
/// bodies): kick(½h) ∘ DMV(h) ∘ kick(½h).
class Lgvi {
 public:
  static constexpr SchemeFacts facts{
      .order = 2,
      .properties = {.symplectic = true, .symmetric = true, .conserves_momentum_norm = true,
                     .conserves_spatial_momentum = true, .conserves_vertical_momentum = true, .implicit = true},
      .support = SceneSupport::conservative_only,
      .reference = "Lee, Leok & McClamroch, IEEE CCA (2005) and CMAME 196 (2007); Moser & Veselov, Commun. Math. "
                   "Phys. 139 (1991)",
      .lane_kernel = LaneKernel::dmv_diagonal};
  /// A run starts with no carried rounding error.
  template <class Model>
  void start(const Model& model, const State& /*initial*/, double /*t0*/) {
    memory_.reset();
    diag_ = moser_veselov::DiagonalInertia(model.inertia);
    ready_ = true;
  }
  /// The carries and the predictor's history (a checkpoint's scheme memory).
  void save_memory(std::vector<double>& out) const { memory_.save(out); }
  bool restore_memory(std::span<const double> in) { return memory_.restore(in); }
  /// Π ← Π + τ M(R), the potential torque only (nothing for a free body), compensated.
  template <class Model>
  static void kick(const Model& model, State& s, moser_veselov::Carry& carry, double /*t*/, double tau) {
    if constexpr (moser_veselov::has_potential<Model>) add_compensated(s.Pi, Vec3(tau * model.potential_torque(s.R)), carry.Pi);
  }
  /// The free DMV step of length h (no kicks); the diagonal fast path when J is diagonal.
  template <class Model>
  StepStatus free_step(const Model& model, State& s, moser_veselov::Carry& carry, double h) {
    if (!ready_) {
      diag_ = moser_veselov::DiagonalInertia(model.inertia);
      ready_ = true;
    }
    if (diag_.diagonal) {
      if (diag_.turns_too_far(s.Pi, h)) return moser_veselov::refused_step(moser_veselov::turns_too_far_reason);
      return moser_veselov::dmv_step_diagonal(diag_.moments, s, carry, h, &memory_.predictor);
    }
    if (moser_veselov::turns_too_far(model.inertia.J_inv, s.Pi, h))
      return moser_veselov::refused_step(moser_veselov::turns_too_far_reason);
    return moser_veselov::dmv_step(model.inertia.J, model.inertia.J_inv, s, carry, h);
  }

  template <class Model>
  StepStatus step(const Model& model, State& s, double t, double h, WorkCounters& work) {
    return moser_veselov::strang_step(*this, model, s, memory_.carry, t, h, work);
  }

  // The kick/flow face that composition.hpp uses to merge neighbouring half kicks.
  template <class Model>
  void kick(const Model& model, State& s, double t, double tau, WorkCounters& /*work*/) {
    kick(model, s, memory_.carry, t, tau);
  }
  template <class Model>
  StepStatus flow(const Model& model, State& s, double /*t*/, double h, WorkCounters& work) {
    work.rhs_evaluations += 1;
    return free_step(model, s, memory_.carry, h);
  }

 private:
  moser_veselov::StepMemory memory_{};     // carries and the diagonal path's predictor
  moser_veselov::DiagonalInertia diag_{};  // per run (start), or at the first step without one
  bool ready_ = false;
};

/// `dmv`: the same step, kept to free bodies, where it also conserves the energy.
class Dmv : public Lgvi {
 public:
  static constexpr SchemeFacts facts{
      .order = 2,
      .properties = {.symplectic = true, .symmetric = true, .conserves_energy = true,
                     .conserves_momentum_norm = true, .conserves_spatial_momentum = true, .implicit = true},
      .support = SceneSupport::free_body_only,
      .reference = Lgvi::facts.reference,
      .lane_kernel = LaneKernel::dmv_diagonal};
};

}  // namespace lgi::integrators
