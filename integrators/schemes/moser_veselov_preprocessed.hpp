#pragma once
// Schemes `dmv-pre4` … `dmv-pre10`: the preprocessed (modified-inertia)
// discrete Moser–Veselov algorithm, high-order versions of the DMV step of
// moser_veselov.hpp, whose header states the step, its solve and its round-off.
//
// ── Preprocessed DMV (`dmv-pre2r`, r = 2…5) ─────────────────────────────────
// E. Hairer & G. Vilmart, "Preprocessed discrete Moser–Veselov algorithm for
// the full dynamics of a rigid body", J. Phys. A 39 (2006) 13225–13235,
// Algorithm 2.2: apply DMV with modified moments of inertia, eq. (6),
//   1/Ĩ_j = (1/I_j)(1 + h² s₃ + h⁴ s₅ + …) + h² d₃ + h⁴ d₅ + …,
// truncated after the h^{2r−2} terms, where s_k, d_k are homogeneous
// polynomials in H = ½ Σ y_j²/I_j (the kinetic energy) and C = ½ |y|²
// evaluated at the current momentum y_n (Theorem 2.1). For a free body the
// scheme conserves H and C exactly (below), so they are taken once per run,
// from the initial state in start(), and the series is kept as two
// polynomials in h² (evaluated by Horner's rule at each step, as h may vary);
// with a potential the kicks change H and C and the series is evaluated at
// every step. (With H and C frozen the map is DMV with constant modified
// moments for a given h; the registry still claims no symplecticity.) No other pre- or
// post-processing is involved: the "preprocessing" is the modification of
// the vector field (their ref. [2]). As the relation is basis-free,
// J̃⁻¹ = s J⁻¹ + d I, so it holds for a non-diagonal J too (the constants
// below are symmetric functions of the principal moments).
// Coefficients (moser_veselov_series.hpp): s₃…s₇ and d₃…d₇ from Table 1 of the paper; s₉, d₉ (order
// 10) from the authors' code DMV10.f (version of 29 Aug 2006, corrected
// 28 Dec 2007; mirrored in ja72/RB_DiscreteMoserVeselov, DMV_F77/DMV10.FI).
// Notation of Table 1: δ = I₁I₂I₃, σ_a = I₁^a + I₂^a + I₃^a,
// τ_{b,c} = Σ_{i≠j} I_i^b / I_j^c.
// The attitude as a quaternion: on a free body these schemes keep R as a unit
// quaternion q (cayley_quaternion.hpp), R ← R F being q ← q ⊗ p, summed
// with compensation, and R = R(q) is formed only where the run reads it
// (stepper_loop.hpp, "Kept attitude"; step() forms it after every step).
// Π's update is the same to the bit. With a potential the kicks read R at
// every step, and R is summed as above; so is it for dmv and lgvi, which
// compositions step through flow(), out of the loop's sight.
// Order 2r for the free body (Proposition 2.3); symmetric; conserves y·y,
// H and the spatial momentum exactly (Prop. 2.3); a Poisson integrator for
// y but NOT symplectic for r > 1 (their Table 2 and §4.3). With a potential
// the authors' code, and this one, use Strang splitting kick(½h) ∘
// preDMV(h) ∘ kick(½h): order 2, Π·Γ still conserved exactly.
// The truncated series is only meaningful for moderate h|Ω|: besides DMV's
// h|Ω| ≥ π refusal (moser_veselov.hpp), a step whose modified moments css/λ_j + cdd are
// not all positive is refused (converged = false, 0 iterations). Between
// DMV's own limit (h|Ω| ≈ 1) and those refusals the modified equation may
// still be solvable, with an error of order one, like any scheme there.
#include <array>
#include <span>
#include <vector>

#include "integrators/schemes/moser_veselov.hpp"
#include "integrators/schemes/moser_veselov_series.hpp"

namespace lgi::integrators {

/// `dmv-pre4` … `dmv-pre10`: Hairer–Vilmart Algorithm 2.2, with a potential
/// in Strang splitting kick(½h) ∘ preDMV(h) ∘ kick(½h) (order 2 then).
template <int Order>
class DmvPreprocessed {
 public:
  static constexpr int order = Order;
  /// The highest power of h² of the modified-inertia series (the ensemble kernel's, dmv_fallback.hpp).
  static constexpr int series_degrees = moser_veselov::ModifiedInertiaSeries<Order>::degrees;
  // Not symplectic for order > 2 (Hairer-Vilmart Table 2, Sect. 4.3): a Poisson integrator for Pi.
  static constexpr SchemeFacts facts{
      .order = Order,
      .order_with_torque = 2,
      .properties = {.symmetric = true, .conserves_momentum_norm = true, .conserves_spatial_momentum = true,
                     .conserves_vertical_momentum = true, .implicit = true},
      .support = SceneSupport::conservative_only,
      .reference = "Hairer & Vilmart, J. Phys. A 39 (2006) 13225-13235, Algorithm 2.2; modified inertia: Table 1 "
                   "and the authors' DMV10.f",
      .lane_kernel = LaneKernel::dmv_diagonal};

  /// Per run: the series constants, the diagonal path's constants and, for a
  /// free body, the series as polynomials in h² at the initial H and |Π|²/2
  /// and the attitude as a quaternion.
  template <class Model>
  void start(const Model& model, const State& initial, double /*t0*/) {
    prepare(model, initial);
  }
  /// The carries and the predictor's history (StepMemory::save); a free body's
  /// run, which sums q instead of R, has q and its carry where R's carry was:
  /// carry of Π (3), q (4), q's carry (4), 0, the predictor.
  void save_memory(std::vector<double>& out) const {
    if (!keeps_quaternion_) return memory_.save(out);
    out.insert(out.end(), memory_.carry.Pi.data(), memory_.carry.Pi.data() + 3);
    out.insert(out.end(), attitude_.q, attitude_.q + 4);
    out.insert(out.end(), attitude_.carry, attitude_.carry + 4);
    out.push_back(0.0);
    memory_.predictor.save(out);
  }
  bool restore_memory(std::span<const double> in) {
    if (!keeps_quaternion_) return memory_.restore(in);
    if (in.size() != 12 + moser_veselov::CayleyPredictor::memory_size ||
        !memory_.predictor.restore(in.subspan(12)))
      return false;
    memory_.carry.Pi = Vec3(in[0], in[1], in[2]);
    for (std::size_t i = 0; i < 4; ++i) attitude_.q[i] = in[3 + i], attitude_.carry[i] = in[7 + i];
    return true;
  }
  /// A free body's css and cdd as polynomials in h² (after start()), for the
  /// ensemble kernel (integrators/ensemble/dmv_kernel.hpp).
  const std::array<double, 4>& css_in_h2() const { return css_in_h2_; }
  const std::array<double, 4>& cdd_in_h2() const { return cdd_in_h2_; }

  template <class Model>
  static void kick(const Model& model, State& s, moser_veselov::Carry& carry, double t, double tau) {
    Lgvi::kick(model, s, carry, t, tau);
  }

  /// The preprocessed DMV step of length h (no kicks): DMV with the modified
  /// inertia J̃⁻¹ = css J⁻¹ + cdd I at the current H and |Π|²/2 (for a free
  /// body, the initial ones: the scheme conserves both, header comment).
  template <class Model>
  StepStatus free_step(const Model& model, State& s, moser_veselov::Carry& carry, double h) {
    if (!ready_) prepare(model, s);
    const Mat3& J_inv = model.inertia.J_inv;
    if (diag_.diagonal ? diag_.turns_too_far(s.Pi, h) : moser_veselov::turns_too_far(J_inv, s.Pi, h))
      return moser_veselov::refused_step(moser_veselov::turns_too_far_reason);
    if constexpr (!moser_veselov::has_potential<Model>) {
      // Free body, diagonal J: the modified moments depend on h alone (H and C are the run's).
      if (diag_.diagonal) {
        if (const moser_veselov::DiagonalMoments* m = moments_by_h_.find(h))
          return moser_veselov::dmv_step_diagonal(*m, s, carry, h, &memory_.predictor, kept_attitude<Model>());
      }
    }
    double css = 1.0, cdd = 0.0;
    const double x = h * h;
    if constexpr (moser_veselov::has_potential<Model>) {
      const double H = 0.5 * s.Pi.dot(J_inv * s.Pi);
      const double C = 0.5 * s.Pi.squaredNorm();
      series_.evaluate(x * H, x * C, css, cdd);
    } else {
      constexpr int degrees = moser_veselov::ModifiedInertiaSeries<Order>::degrees;
      css = moser_veselov::horner_in_h2(css_in_h2_, degrees, x, 1.0);
      cdd = moser_veselov::horner_in_h2(cdd_in_h2_, degrees, x, 0.0);
    }
    // J̃⁻¹ shares J's principal axes, with moments css/λ_j + cdd: refuse a step
    // where the truncated series has left them non-positive (h far too large).
    const Vec3 moments_inv = css * (diag_.diagonal ? diag_.J_inv : principal_inv_) + Vec3::Constant(cdd);
    if (!(moments_inv.minCoeff() > 0.0))
      return moser_veselov::refused_step(
          "step refused: the truncated modified-inertia series is not positive at this h|Omega|; reduce --dt");
    if (diag_.diagonal) {  // moments_inv = 1/Ĩ_j in J's own order
      const moser_veselov::DiagonalMoments m(moments_inv.cwiseInverse(), moments_inv);
      if constexpr (!moser_veselov::has_potential<Model>) moments_by_h_.insert(h, m);
      return moser_veselov::dmv_step_diagonal(m, s, carry, h, &memory_.predictor, kept_attitude<Model>());
    }
    Mat3 Jt_inv = css * J_inv;
    Jt_inv.diagonal().array() += cdd;
    return moser_veselov::dmv_step(Jt_inv.inverse(), Jt_inv, s, carry, h, kept_attitude<Model>());
  }

  /// With a potential: kick(½h) ∘ preDMV(h) ∘ kick(½h) on (R, Π). A free body's
  /// step is step_keeping_attitude() followed by write_attitude(); an R other
  /// than R(q) (a state the caller set) is taken up as the attitude first.
  template <class Model>
  StepStatus step(const Model& model, State& s, double t, double h, WorkCounters& work) {
    if constexpr (moser_veselov::has_potential<Model>) {
      return moser_veselov::strang_step(*this, model, s, memory_.carry, t, h, work);
    } else {
      if (!ready_) prepare(model, s);
      Mat3 kept;
      attitude_.write(kept);
      if (!(s.R.array() == kept.array()).all()) attitude_.set_from(s.R);
      const StepStatus st = step_keeping_attitude(model, s, t, h, work);
      if (st.converged) write_attitude(s);
      return st;
    }
  }
  /// A free body's step on Π and the scheme's quaternion q, s.R left as it
  /// was (stepper_loop.hpp, "Kept attitude"; cayley_quaternion.hpp).
  template <class Model>
    requires(!moser_veselov::has_potential<Model>)
  StepStatus step_keeping_attitude(const Model& model, State& s, double t, double h, WorkCounters& work) {
    return moser_veselov::strang_step(*this, model, s, memory_.carry, t, h, work);
  }
  /// s.R ← R(q), the attitude the free body's steps have kept.
  void write_attitude(State& s) const { attitude_.write(s.R); }

 private:
  template <class Model>
  void prepare(const Model& model, const State& x) {
    series_ = moser_veselov::ModifiedInertiaSeries<Order>(model.inertia.principal);
    principal_inv_ = model.inertia.principal.cwiseInverse();
    diag_ = moser_veselov::DiagonalInertia(model.inertia);
    if constexpr (!moser_veselov::has_potential<Model>) {
      const double H = 0.5 * x.Pi.dot(model.inertia.J_inv * x.Pi);
      const double C = 0.5 * x.Pi.squaredNorm();
      series_.coefficients_in_h2(H, C, css_in_h2_, cdd_in_h2_);
    }
    moments_by_h_ = {};
    memory_.reset();
    keeps_quaternion_ = !moser_veselov::has_potential<Model>;
    attitude_.set_from(x.R);
    ready_ = true;
  }
  /// The quaternion a free body's step rotates (nullptr with a potential: R F).
  template <class Model>
  moser_veselov::CayleyQuaternion* kept_attitude() {
    if constexpr (moser_veselov::has_potential<Model>) return nullptr;
    else return &attitude_;
  }

  moser_veselov::ModifiedInertiaSeries<Order> series_{};
  moser_veselov::MomentsByStep moments_by_h_{};  // free body: the modified moments of recent h
  std::array<double, 4> css_in_h2_{}, cdd_in_h2_{};  // free body: the series in h² (prepare)
  Vec3 principal_inv_ = Vec3::Ones();
  moser_veselov::DiagonalInertia diag_{};
  bool ready_ = false;
  moser_veselov::StepMemory memory_{};  // carries and the diagonal path's predictor
  moser_veselov::CayleyQuaternion attitude_{};  // a free body's attitude (save_memory)
  bool keeps_quaternion_ = false;               // a free body's run (prepare)
};

using DmvPre4 = DmvPreprocessed<4>;
using DmvPre6 = DmvPreprocessed<6>;
using DmvPre8 = DmvPreprocessed<8>;
using DmvPre10 = DmvPreprocessed<10>;

}  // namespace lgi::integrators
