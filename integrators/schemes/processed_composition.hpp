#pragma once
// Processed compositions BASE@bcm-processed6, BASE@bcm-processed8.
//
// ψ_h = π_h ∘ K_h ∘ π_h⁻¹ with a symmetric kernel K_h = Φ_{γ_s h} ∘ ⋯ ∘
// Φ_{γ_1 h} of a symmetric order-2 method Φ and a processor π_h, itself a
// composition of Φ (coefficients and their conditions:
// tableaus/processed_composition.hpp; Blanes, Casas & Murua, SIAM J. Sci.
// Comput. 27 (2006) 1817–1843; Acta Numerica 33 (2024) §8). N steps are
// ψ_h^N = π_h ∘ K_h^N ∘ π_h⁻¹: the processor runs once at the start and once
// per output, so a step costs the kernel's s stages only (11 for order 6,
// 13 for order 8, against 9 and 17 for Kahan–Li), and the errors are smaller
// at the same h (HLW's top at h = 0.1: ÷140 against kahan-li6, ÷3.7 against
// kahan-li8; docs/math.md §8).
//
// The loop's state is then the kernel's variable y = π_h⁻¹(x), not the
// trajectory x: observers get observable() = π_h(y) (stepper_loop.hpp,
// detail::observe_step), and the run's final state is π_h(y). The first step
// applies π_h⁻¹ to the initial state; a step whose length differs from the
// processed one by more than 1e-8 relative (the clipped last step of a run, a
// halving retry) first returns to x by π and processes again for the new h.
// The grid's rounding jitter of h (≤ 1e-10 relative up to 10⁶ steps) stays
// below that bound; a processor of length h' for a kernel step h = h'(1 + δ)
// leaves an error O(δ h⁵) per step. The processor uses |h|: for a step −h it
// is π_h, so ψ_{−h} = π_h K_h⁻¹ π_h⁻¹ = ψ_h⁻¹ and the method is symmetric
// (a run backward from a forward run's end returns to its start).
// The theory of processing is that of an autonomous flow: a scene with a
// damper or a drive is refused (SceneSupport::conservative_only).
// ψ keeps what Φ keeps and composition does not break (symplecticity, the
// Casimirs, the free body's |Π|); the energy of x oscillates like the
// kernel's. Events are not located (the run fails with that reason): between
// outputs the loop never holds x.
#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include "integrators/schemes/composition.hpp"
#include "integrators/tableaus/processed_composition.hpp"

namespace lgi::integrators {

template <class Base, const auto& Coefficients>
class ProcessedComposition {
 public:
  static constexpr auto& coefficients = Coefficients;
  static constexpr std::size_t stages = std::remove_cvref_t<decltype(Coefficients)>::stages;
  // Conservative scenes only (top of file).
  static constexpr SchemeFacts facts = composed_facts<Base>(
      Coefficients.order, Coefficients.citation,
      Base::facts.support == SceneSupport::any ? SceneSupport::conservative_only : Base::facts.support);

  template <class Model>
  StepStatus start(const Model& model, const State& initial, double t0) {
    processed_h_ = 0.0;
    return detail::start(base_, model, initial, t0);
  }

  /// One kernel step; the first step (or one of a new length) processes the state first (top of file).
  /// A step that fails leaves the state and the processed length as they were, so that the
  /// loop's retry with h/2 (RunConfig::retry_halving), which restores the state, finds them consistent.
  template <class Model>
  StepStatus step(const Model& model, State& s, double t, double h, WorkCounters& work) {
    if (processed_h_ != 0.0 && std::abs(std::abs(h) - processed_h_) <= 1e-8 * processed_h_)
      return compose_stages(base_, model, s, t, h, Coefficients.gamma, work);
    const State before = s;
    const double was = processed_h_;
    if (processed_h_ != 0.0) {
      const StepStatus back = postprocess(base_, model, s, t, work);
      if (!back.converged) return restore(s, before, was, back);
    }
    processed_h_ = std::abs(h);
    const StepStatus pre = compose_stages(base_, model, s, t, processed_h_, Coefficients.z, work);
    if (!pre.converged) return restore(s, before, was, pre);
    const StepStatus kernel = compose_stages(base_, model, s, t, h, Coefficients.gamma, work);
    return kernel.converged ? kernel : restore(s, before, was, kernel);
  }

  /// The trajectory's state π_h(y) for the loop's state y (y itself before the first step).
  template <class Model>
  State observable(const Model& model, const State& y, WorkCounters& work) const {
    State x = y;
    if (processed_h_ == 0.0) return x;
    Base base = base_;  // the base's memory (a compensated sum's carry) goes on with y, not with x
    postprocess(base, model, x, 0.0, work);
    return x;
  }

  // Resume (scheme_interface.hpp): the processed step length, then what the base keeps.
  using base_scheme_type = Base;
  void save_memory(std::vector<double>& out) const {
    out.push_back(processed_h_);
    if constexpr (saves_step_memory<Base>) base_.save_memory(out);
  }
  bool restore_memory(std::span<const double> in) {
    if (in.empty() || !(in[0] >= 0.0)) return false;
    bool ok = in.size() == 1;
    if constexpr (saves_step_memory<Base>) ok = base_.restore_memory(in.subspan(1));
    if (ok) processed_h_ = in[0];
    return ok;
  }

 private:
  /// π_h: the preprocessing's stages negated, last first (Φ symmetric).
  template <class Model>
  StepStatus postprocess(Base& base, const Model& model, State& s, double t, WorkCounters& work) const {
    return compose_stages(base, model, s, t, processed_h_, inverse_processor, work);
  }
  StepStatus restore(State& s, const State& before, double was, StepStatus failed) {
    s = before;
    processed_h_ = was;
    return failed;
  }
  static constexpr auto inverse_processor = [] {
    auto z = Coefficients.z;
    std::reverse(z.begin(), z.end());
    for (double& v : z) v = -v;
    return z;
  }();

  Base base_{};
  double processed_h_ = 0.0;  // the |h| of the processor applied to the loop's state; 0: not processed
};

}  // namespace lgi::integrators
