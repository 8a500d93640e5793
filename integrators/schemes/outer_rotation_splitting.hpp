#pragma once
// The face that split-axes and split-symmetric share: a Strang splitting
//   Φ_h = A_s(h/2) ∘ inner(h) ∘ A_s(h/2),
// whose outermost part A_s is the rotation about the principal axis of the
// smallest moment, with coefficient c_s (rotation_flows.hpp). Offering
// outer() and inner() lets composition.hpp merge the outer rotations of
// neighbouring stages (flows of one Hamiltonian compose additively).
//
// CRTP: Derived provides set_up(const system::Inertia&), which calls
// set_up_axes() and sets c_s_ and ready_, and middle(model, s, t, h): the
// inner part, which holds the two torque kicks.
#include <array>

#include "integrators/schemes/rotation_flows.hpp"
#include "integrators/core/scheme_facts.hpp"
#include "integrators/core/scheme_interface.hpp"

namespace lgi::integrators {

template <class Derived>
class OuterRotationSplitting {
 public:
  // Resume (scheme_interface.hpp): start() depends on the inertia only; a step carries nothing.
  static constexpr bool memoryless_steps = true;

  // The facts both schemes have (their headers say why): order 2, symplectic where the torque
  // derives from a potential, symmetric, and conserving what every rotation and the frozen kick
  // conserve.
  static constexpr SchemeFacts facts_with(const char* reference) {
    return {.order = 2,
            .properties = {.symplectic = true,
                           .symmetric = true,
                           .conserves_momentum_norm = true,
                           .conserves_spatial_momentum = true,
                           .conserves_vertical_momentum = true},
            .reference = reference};
  }

  template <class Model>
  void start(const Model& model, const State& /*initial*/, double /*t0*/) {
    self().set_up(model.inertia);
  }

  template <class Model>
  void outer(const Model& model, State& s, double /*t*/, double length, WorkCounters& /*work*/) {
    if (!ready_) self().set_up(model.inertia);
    axes_.flow(s, s_, c_s_, length);
  }

  // The part between the outer rotations.
  template <class Model>
  StepStatus inner(const Model& model, State& s, double t, double h, WorkCounters& work) {
    if (!ready_) self().set_up(model.inertia);
    self().middle(model, s, t, h);
    work.rhs_evaluations += Model::has_torque ? 2 : 0;  // the two kicks
    return {};
  }

  template <class Model>
  StepStatus step(const Model& model, State& s, double t, double h, WorkCounters& work) {
    outer(model, s, t, 0.5 * h, work);
    inner(model, s, t, h, work);
    outer(model, s, t + h, 0.5 * h, work);
    return {};
  }

 protected:
  // Sets axes_ and s_; returns the principal axes in ascending order of moment (s, m, l).
  std::array<int, 3> set_up_axes(const system::Inertia& inertia) {
    axes_ = rotation_flows::PrincipalAxisFlows(inertia);
    const auto order = rotation_flows::ascending_axes(inertia.principal);
    s_ = order[0];
    return order;
  }

  rotation_flows::PrincipalAxisFlows axes_;
  int s_ = 0;          // the axis of the smallest moment
  double c_s_ = 0.0;   // its rotation's coefficient
  bool ready_ = false;

 private:
  Derived& self() { return static_cast<Derived&>(*this); }
};

}  // namespace lgi::integrators
