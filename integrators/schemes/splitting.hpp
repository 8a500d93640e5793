#pragma once
// Scheme `split-exact`: Strang splitting of the Euler–Poisson field into the
// free rigid body and the torque, each part solved exactly.
//
// Celledoni, Fassò, Säfström & Zanna, "The exact computation of the free rigid
// body motion and its use in splitting methods", SIAM J. Sci. Comput. 30
// (2008) 2084–2112, §4 (splitting with the exact free flow); Strang splitting
// as in Hairer, Lubich & Wanner, GNI (2006), §II.5 / §VII.4; docs/math.md §7,
// "Splitting with the exact free flow". One step (t → t + h):
//   kick(t, h/2):   Π ← exact flow over h/2 of  Ṙ = 0, Π̇ = τ(R, Π, t)   (R and t frozen)
//   flow(h):        (R, Π) ← exact free-body flow over h  (system/free_body_flow_stepper.hpp)
//   kick(t + h, h/2)
// For torques from a potential (gravity, an undamped spring) the kick is
// Π ← Π + (h/2) τ(R). The kick field also carries the torques a scene may add
// (SceneSupport::any):
//   - a harmonic drive τ(t): the time is frozen during a kick and advanced by
//     the free flow (the usual autonomisation, ṫ = 1 in the free part), so the
//     two half kicks use t and t + h; the scheme stays symmetric and of order 2;
//   - the spring's damper −c J⁻¹Π: with R frozen the kick is linear in Π,
//       Π̇ = f − c J⁻¹ Π,  f = −k log(R_restᵀR) + gravity + drive,
//     solved exactly in the principal frame J = P diag(I_i) Pᵀ:
//       Π_i ← e^{−c s/I_i} Π_i + (I_i/c)(1 − e^{−c s/I_i}) f_i   (s the kick length),
//     (−expm1 for 1 − e^{−x}), unconditionally stable however stiff the damper.
//   Both keep the kick an exact flow, so consecutive half kicks (of a
//   composition, or of two steps) merge: kick(t, a) ∘ kick(t, b) = kick(t, a + b).
// kick() and flow() are exposed for compositions; step() is the composition.
//
// The kick asks each term for its frozen torque f(R, t) and damper c
// (system/terms/frozen_kick_term.hpp); any model whose terms all have them runs.
//
// Order 2; symmetric (Φ₋ₕ ∘ Φₕ = id); symplectic where the torque derives from
// a potential (composition of exact Hamiltonian flows). For a free body the
// kick vanishes and the scheme IS the exact flow (re-started every step).
// Exactly conserved (to round-off) where they are invariants of the scene:
//   free body: H, |Π|, m = RΠ (exact flow);
//   heavy top (any J, χ): Π·Γ = m·e3 — the kick changes Π by a multiple of
//     Γ × mgχ ⊥ Γ with Γ frozen, and the free flow conserves m = RΠ;
//   Lagrange top: also Π3 (the kick's Γ × mgχ has no e3 component when χ ∥ e3,
//     and the symmetric free flow conserves Π3).
// Not conserved: the energy of a scene with a torque (bounded error, no drift:
// backward error analysis of a symplectic map; tests/test_splitting.cpp).
// Cost: one torque evaluation per step (the second half kick and the next
// step's first half kick are computed separately here, as the state is handed
// back to the stepper loop in between) and one free-flow step; see
// free_body_flow_stepper.hpp for what the free flow evaluates.
#include <cmath>
#include <optional>

#include "integrators/core/scheme_interface.hpp"
#include "integrators/system/free_body_flow_stepper.hpp"

namespace lgi::integrators {

class SplitExact {
 public:
  // Conservation flags mean "exact where the quantity is an invariant of the scene":
  // Pi.Gamma for a heavy top (kick along Gamma x m g chi, free flow conserves m).
  // |Pi| and m are not claimed: the per-step elliptic-function flow keeps them
  // only to ~1e-12 over 1e5 steps (measured 1.3e-12 and 9.7e-12), not to round-off.
  // The energy of a torqued scene is not conserved exactly (symplectic: bounded, no drift).
  static constexpr SchemeFacts facts{
      .order = 2,
      .properties = {.symplectic = true, .symmetric = true, .conserves_vertical_momentum = true},
      .reference = "Celledoni, Fasso, Safstrom & Zanna, SIAM J. Sci. Comput. 30 (2008) 2084-2112 (Strang "
                   "splitting with the exact free flow)"};
  template <class Model>
  void start(const Model& model, const State& /*initial*/, double /*t0*/) {
    flow_.emplace(model.inertia);
  }
  // Resume (scheme_interface.hpp): start() sets the flow up from the inertia; a step changes nothing else.
  static constexpr bool memoryless_steps = true;

  /// The exact flow over `length` (either sign) of Ṙ = 0, Π̇ = τ(R, Π, t) at frozen R and t.
  template <class Model>
  static void kick(const Model& model, State& s, double t, double length) {
    static_assert(Model::frozen_kick,
                  "split-exact needs every torque term to be affine in Omega at frozen attitude (FrozenKickTerm)");
    if constexpr (Model::has_torque) {
      const FrozenTorque k = frozen_torque(model, s, t);
      if (k.damping == 0.0) {
        s.Pi += length * k.f;
      } else {
        damped_kick(model.inertia, s, k, length);
      }
    }
  }

  /// τ at frozen R and t, τ = f − c Ω: the part f that does not depend on Π and
  /// the summed damping c of the terms.
  struct FrozenTorque {
    Vec3 f = Vec3::Zero();
    double damping = 0.0;
  };
  template <class Model>
  static FrozenTorque frozen_torque(const Model& model, const State& s, double t) {
    FrozenTorque k;
    model.for_each_term([&](const auto& term) {
      k.f += term.frozen_torque(s.R, t);
      k.damping += term.damping();
    });
    return k;
  }

  /// The kick with a damper (k.damping ≠ 0): in the principal frame each
  /// component relaxes exponentially towards I_i f_i / c.
  static void damped_kick(const system::Inertia& in, State& s, const FrozenTorque& k, double length) {
    Vec3 pi_p = in.principal_axes.transpose() * s.Pi;
    const Vec3 f_p = in.principal_axes.transpose() * k.f;
    for (int i = 0; i < 3; ++i) {
      const double x = -k.damping * length / in.principal(i);
      pi_p(i) = std::exp(x) * pi_p(i) - std::expm1(x) * (in.principal(i) / k.damping) * f_p(i);
    }
    s.Pi = in.principal_axes * pi_p;
  }

  /// The exact free-body flow over h (either sign). Needs start().
  template <class Model>
  void flow(const Model& /*model*/, State& s, double h) const {
    flow_->advance(s, h);
  }

  // The kick/flow face that composition.hpp uses to merge neighbouring half
  // kicks (exact kicks at frozen R and t compose: kick(a) ∘ kick(b) = kick(a + b)).
  template <class Model>
  void kick(const Model& model, State& s, double t, double length, WorkCounters& work) const {
    kick(model, s, t, length);
    work.rhs_evaluations += Model::has_torque ? 1 : 0;
  }
  template <class Model>
  StepStatus flow(const Model& model, State& s, double /*t*/, double h, WorkCounters& /*work*/) {
    if (!flow_) flow_.emplace(model.inertia);  // used without start(): set up once
    flow_->advance(s, h);
    return {};
  }

  template <class Model>
  StepStatus step(const Model& model, State& s, double t, double h, WorkCounters& work) {
    if (!flow_) flow_.emplace(model.inertia);  // used without start(): set up once
    kick(model, s, t, 0.5 * h);
    flow(model, s, h);
    kick(model, s, t + h, 0.5 * h);
    work.rhs_evaluations += Model::has_torque ? 2 : 0;
    return {};
  }

 private:
  std::optional<system::FreeBodyFlowStepper> flow_;
};

}  // namespace lgi::integrators
