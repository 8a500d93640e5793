#pragma once
// Scheme `split-symmetric`: the kinetic energy split into a symmetric top and
// a remainder about one axis, every flow a closed-form rotation
// (rotation_flows.hpp), with the torque kick of split-exact (splitting.hpp).
//
// Touma & Wisdom, "Lie-Poisson integrators for rigid body dynamics in the
// solar system", Astron. J. 107 (1994) 1189–1202 (a symmetric top plus a
// remainder); Fassò, J. Comput. Phys. 189 (2003) 527–538 (the choice of the
// parts decides the error); docs/math.md §7. With s, m, l the principal axes
// of the smallest, intermediate and largest moment,
//   T = |Π|²/(2 I_m) + ½ c_l Π_l² + ½ c_s Π_s²,   c_i = 1/I_i − 1/I_m,
// where the first two terms are the symmetric top with moments (I_m, I_m, I_l),
// whose flow is S(τ) A_l(τ) (the two commute: |Π|² is a Casimir), and the
// third is the remainder. One step (t → t + h):
//   A_s(h/2) K(t, h/2) S(h) A_l(h) K(t + h, h/2) A_s(h/2),
// S(τ): R ← R exp(τ Π̂/I_m), Π unchanged; A_i(τ): rotation about p_i by
// τ c_i Π_i (Π ← the inverse rotation of Π); K: split-exact's kick at frozen
// R and t. Time advances during the central S A_l.
// Why these parts: since S commutes with every function of Π, the free part
// is a splitting of the two axis terms c_s Π_s², c_l Π_l² alone, and the
// intermediate moment in S gives them the smallest coefficients (of opposite
// signs); a body with two equal moments has c_s = 0 or c_l = 0, and the free
// part is its exact flow (this step is then split-exact with the free flow
// in the middle replaced by S A_l, the kick order reversed). Among the
// arrangements measured on seven free bodies and four heavy tops
// (docs/math.md §7), this one had the smallest error or one within a factor
// 2.6 of it, at the lowest cost (one sphere flow, two plane rotations, two
// kicks a stage).
//
// Order 2; symmetric; symplectic where the torque derives from a potential.
// In exact arithmetic conserved: |Π| and m = RΠ for a free body, Π·Γ for a
// heavy top (as split-axes). Not conserved: the energy (bounded error, no
// drift, for a potential torque). Cost per step: one sphere flow (a sqrt and
// a sincos), 3 plane rotations (2 in a composition, where neighbouring A_s
// merge), 2 kicks; a coefficient that is exactly 0 (equal moments) skips its
// rotation. Supports what split-exact's kick supports.
#include "integrators/schemes/outer_rotation_splitting.hpp"
#include "integrators/schemes/rotation_flows.hpp"
#include "integrators/core/scheme_interface.hpp"

namespace lgi::integrators {

class SplitSymmetric : public OuterRotationSplitting<SplitSymmetric> {
 public:
  static constexpr SchemeFacts facts = facts_with(
      "Touma & Wisdom, Astron. J. 107 (1994) 1189-1202 (symmetric top plus remainder); Fasso, "
      "J. Comput. Phys. 189 (2003) 527-538");

  // The part between the outer rotations, with the kicks (outer_rotation_splitting.hpp).
  template <class Model>
  void middle(const Model& model, State& s, double t, double h) {
    rotation_flows::kick(model, s, t, 0.5 * h);
    rotation_flows::sphere_flow(s, inverse_m_, h);
    axes_.flow(s, l_, c_l_, h);
    rotation_flows::kick(model, s, t + h, 0.5 * h);
  }

 private:
  friend class OuterRotationSplitting<SplitSymmetric>;
  void set_up(const system::Inertia& inertia) {
    const auto order = set_up_axes(inertia);
    l_ = order[2];
    inverse_m_ = 1.0 / inertia.principal(order[1]);
    // Exactly 0 for equal moments (the same double): that rotation is skipped.
    c_s_ = 1.0 / inertia.principal(s_) - inverse_m_;
    c_l_ = 1.0 / inertia.principal(l_) - inverse_m_;
    ready_ = true;
  }

  int l_ = 2;               // the axis of the largest moment
  double inverse_m_ = 1.0;  // 1/I_m
  double c_l_ = 0.0;        // 1/I_l − 1/I_m ≤ 0 (c_s_ = 1/I_s − 1/I_m ≥ 0)
};

}  // namespace lgi::integrators
