#pragma once
// Scheme `split-axes`: symmetric splitting of the kinetic energy into the
// three principal-axis terms, T = Σ Π_i²/(2 I_i), each flow a closed-form
// rotation (rotation_flows.hpp), with the torque kick of split-exact
// (splitting.hpp) Strang-composed around the middle one.
//
// Dullweber, Leimkuhler & McLachlan, "Symplectic splitting methods for rigid
// body molecular dynamics", J. Chem. Phys. 107 (1997) 5840–5851, §III (the
// symmetric splitting R1(h/2) R2(h/2) R3(h) R2(h/2) R1(h/2)); Fassò,
// "Comparison of splitting algorithms for the rigid body", J. Comput. Phys.
// 189 (2003) 527–538 (the error depends on the ordering of the axes);
// docs/math.md §7. One step (t → t + h), with s, m, l the principal axes
// of the smallest, intermediate and largest moment:
//   A_s(h/2) A_m(h/2) K(t, h/2) A_l(h) K(t + h, h/2) A_m(h/2) A_s(h/2),
// A_i(τ): the exact flow of Π_i²/(2 I_i) over τ (rotation about p_i by
// τ Π_i/I_i); K(t, τ): split-exact's kick, the exact flow over τ of Ṙ = 0,
// Π̇ = τ(R, Π, t) at frozen R and t. Time advances during A_l, so the kicks
// see t and t + h (the autonomised splitting; symmetric).
// The ordering (smallest moment outermost, largest in the middle) was chosen
// by the mean local error of the free-body part over random directions of Π
// for seven bodies (docs/math.md §7): it was the best of the six orderings on
// four and within a factor 4 of the best on the others, and it is the
// ordering that is of order 4 for the flat body I ∝ (1, 0.75, 0.25), the
// special case Fassò (2003) points out. The kick sits next to A_l: for a top whose centre
// of mass lies on the axis of largest moment (HLW's heavy top) the two
// commute and the splitting has three parts, not four.
//
// Order 2; symmetric; symplectic where the torque derives from a potential
// (a composition of exact Hamiltonian flows). In exact arithmetic conserved:
//   free body: |Π| and m = RΠ (every rotation conserves both);
//   heavy top: Π·Γ = m·e3 (the kick adds a multiple of Γ × mgχ ⊥ Γ at frozen Γ).
// Not conserved: the energy (bounded error, no drift, for a potential torque).
// Cost per step: 5 rotations (4 in a composition, where neighbouring A_s
// merge), i.e. 5 sincos, and 2 kicks. Supports what split-exact's kick
// supports (every term with frozen_torque and damping: gravity, spring and
// damper, drive, magnet; system/terms/frozen_kick_term.hpp); compositions
// run a damper backward over part of a step (composition.hpp).
#include "integrators/schemes/outer_rotation_splitting.hpp"
#include "integrators/schemes/rotation_flows.hpp"
#include "integrators/core/scheme_interface.hpp"

namespace lgi::integrators {

class SplitAxes : public OuterRotationSplitting<SplitAxes> {
 public:
  static constexpr SchemeFacts facts = facts_with(
      "Dullweber, Leimkuhler & McLachlan, J. Chem. Phys. 107 (1997) 5840-5851; axis ordering: "
      "Fasso, J. Comput. Phys. 189 (2003) 527-538");

  // The part between the outer rotations, with the kicks (outer_rotation_splitting.hpp).
  template <class Model>
  void middle(const Model& model, State& s, double t, double h) {
    axes_.flow(s, m_, c_m_, 0.5 * h);
    rotation_flows::kick(model, s, t, 0.5 * h);
    axes_.flow(s, l_, c_l_, h);
    rotation_flows::kick(model, s, t + h, 0.5 * h);
    axes_.flow(s, m_, c_m_, 0.5 * h);
  }

 private:
  friend class OuterRotationSplitting<SplitAxes>;
  void set_up(const system::Inertia& inertia) {
    const auto order = set_up_axes(inertia);
    m_ = order[1];
    l_ = order[2];
    c_s_ = 1.0 / inertia.principal(s_);
    c_m_ = 1.0 / inertia.principal(m_);
    c_l_ = 1.0 / inertia.principal(l_);
    ready_ = true;
  }

  int m_ = 1, l_ = 2;             // axes of the intermediate and the largest moment
  double c_m_ = 1.0, c_l_ = 1.0;  // 1/I of each
};

}  // namespace lgi::integrators
