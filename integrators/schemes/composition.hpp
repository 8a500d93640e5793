#pragma once
// Composition methods BASE@yoshida4, @suzuki4, @kahan-li6, @kahan-li8.
//
// Ψ_h = Φ_{γ_s h} ∘ ⋯ ∘ Φ_{γ_1 h} for a symmetric method Φ of order 2
// (Hairer, Lubich & Wanner, GNI, §II.4 and §V.3, Theorem V.3.1/V.3.2): the
// result is symmetric, of the coefficients' order (4, 4, 6, 8), and keeps
// every property of Φ that survives composition (symplecticity, exact
// conservation of first integrals, the Casimirs).
// Where Φ is a Strang splitting kick(½h) ∘ flow(h) ∘ kick(½h) (lgvi,
// split-exact), consecutive half kicks of neighbouring stages are merged into
// one kick by (γ_i + γ_{i+1}) h / 2 ("first same as last"), saving s − 1
// torque evaluations per step (HLW §V.3.1, remark after (3.4)); likewise the
// outer rotations of outer(½h) ∘ inner(h) ∘ outer(½h) (split-axes,
// split-symmetric).
// Every coefficient set here has negative γ_i (order > 2 needs them: Sheng,
// IMA J. Numer. Anal. 9 (1989) 199–212; Suzuki, J. Math. Phys. 32 (1991)
// 400–407): a damped scene is then integrated backward over part
// of each step, where the damper amplifies. Compositions are for conservative
// and mildly dissipative scenes; on stiff_damped_spring use rkmk-radau5.
#include <algorithm>
#include <array>
#include <concepts>
#include <cstddef>

#include "integrators/core/scheme_interface.hpp"
#include "integrators/core/stepper_loop.hpp"
#include "integrators/tableaus/composition.hpp"

namespace lgi::integrators {

/// A Strang splitting that exposes its parts: kick(h) adds h τ(R) to Π;
/// flow(h) is the symmetric free part. step(h) = kick(½h) ∘ flow(h) ∘ kick(½h).
template <class Scheme, class Model>
concept kick_flow_splitting = requires(Scheme& scheme, const Model& model, State& s, WorkCounters& w) {
  scheme.kick(model, s, 0.0, 0.0, w);
  { scheme.flow(model, s, 0.0, 0.0, w) } -> std::same_as<StepStatus>;
};

/// The same for a splitting whose outermost part is another exact flow that
/// merges (split-axes, split-symmetric: a rotation about one axis):
/// step(h) = outer(½h) ∘ inner(h) ∘ outer(½h), outer(a) ∘ outer(b) = outer(a + b).
template <class Scheme, class Model>
concept outer_inner_splitting = requires(Scheme& scheme, const Model& model, State& s, WorkCounters& w) {
  scheme.outer(model, s, 0.0, 0.0, w);
  { scheme.inner(model, s, 0.0, 0.0, w) } -> std::same_as<StepStatus>;
};

/// Φ_{γ_n h} ∘ ⋯ ∘ Φ_{γ_1 h} (γ_1 first) of the symmetric base, from time t:
/// the stages of a composition, or of a processor (processed_composition.hpp).
/// Neighbouring half kicks (outer rotations) of a splitting are merged (top of
/// this file). Stops at the first stage whose solve fails.
template <class Base, class Model, std::size_t N>
StepStatus compose_stages(Base& base, const Model& model, State& s, double t, double h,
                          const std::array<double, N>& gamma, WorkCounters& work) {
  StepStatus total;
  auto merge = [&](const StepStatus& st) {
    total.converged = total.converged && st.converged;
    total.iterations = std::max(total.iterations, st.iterations);
    total.residual = std::max(total.residual, st.residual);
    if (!st.converged && !total.reason) total.reason = st.reason;
  };
  constexpr bool kick_flow = kick_flow_splitting<Base, Model>;
  if constexpr (kick_flow || outer_inner_splitting<Base, Model>) {
    auto outer = [&](double tau, double length) {
      if constexpr (kick_flow) base.kick(model, s, tau, length, work);
      else base.outer(model, s, tau, length, work);
    };
    auto inner = [&](double tau, double hi) {
      if constexpr (kick_flow) return base.flow(model, s, tau, hi, work);
      else return base.inner(model, s, tau, hi, work);
    };
    double tau = t;
    outer(tau, 0.5 * gamma[0] * h);
    for (std::size_t i = 0; i < N; ++i) {
      const double hi = gamma[i] * h;
      merge(inner(tau, hi));
      if (!total.converged) return total;
      tau += hi;
      const double next = i + 1 < N ? gamma[i + 1] : 0.0;
      outer(tau, 0.5 * (gamma[i] + next) * h);
    }
  } else {
    double tau = t;
    for (std::size_t i = 0; i < N; ++i) {
      const double hi = gamma[i] * h;
      merge(base.step(model, s, tau, hi, work));
      if (!total.converged) return total;
      tau += hi;
    }
  }
  return total;
}

/// The facts of a composition of Base (processed or not) of the given order:
/// the coefficients raise a symmetric order-2 base to their order; a base that
/// drops to order 2 with torques stays at 2 there; the base's properties.
template <class Base>
constexpr SchemeFacts composed_facts(int order, const char* citation, SceneSupport support = Base::facts.support) {
  static_assert(Base::facts.order == 2 && Base::facts.properties.symmetric,
                "compositions raise the order of a symmetric scheme of order 2");
  return {.order = order,
          .order_with_torque = Base::facts.order_with_torque ? 2 : 0,
          .properties = Base::facts.properties,
          .support = support,
          .reference = citation};
}

template <class Base, const auto& Coefficients>
class Composition {
 public:
  static constexpr auto& coefficients = Coefficients;
  static constexpr std::size_t stages = std::remove_cvref_t<decltype(Coefficients)>::stages;
  static constexpr SchemeFacts facts = composed_facts<Base>(Coefficients.order, Coefficients.citation);

  template <class Model>
  StepStatus start(const Model& model, const State& initial, double t0) {
    return detail::start(base_, model, initial, t0);
  }

  // Resume (scheme_interface.hpp): a composition keeps between steps what its base keeps.
  using base_scheme_type = Base;
  void save_memory(std::vector<double>& out) const
    requires saves_step_memory<Base>
  {
    base_.save_memory(out);
  }
  bool restore_memory(std::span<const double> in)
    requires saves_step_memory<Base>
  {
    return base_.restore_memory(in);
  }

  template <class Model>
  StepStatus step(const Model& model, State& s, double t, double h, WorkCounters& work) {
    return compose_stages(base_, model, s, t, h, Coefficients.gamma, work);
  }

 private:
  Base base_{};
};

}  // namespace lgi::integrators
