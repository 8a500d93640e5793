#pragma once
// The face that split-axes and split-symmetric share: a Strang splitting
//   Φ_h = A_s(h/2) ∘ inner(h) ∘ A_s(h/2),
// whose outermost part A_s is the rotation about the principal axis of the
// smallest moment, with coefficient c_s (rotation_flows.hpp). Offering
// outer() and inner() lets composition.hpp merge the outer rotations of
// neighbouring stages (flows of one Hamiltonian compose additively).
//
// CRTP: Derived provides set_up(const system::Inertia&), which sets axes_,
// s_, c_s_ and ready_, and inner(model, s, t, h, work).
#include "integrators/rotation_flows.hpp"
#include "integrators/scheme_interface.hpp"

namespace lgi::integrators {

template <class Derived>
class OuterRotationSplitting {
 public:
  // Resume (scheme_interface.hpp): start() depends on the inertia only; a step carries nothing.
  static constexpr bool memoryless_steps = true;

  template <class Model>
  void start(const Model& model, const State& /*initial*/, double /*t0*/) {
    self().set_up(model.inertia);
  }

  template <class Model>
  void outer(const Model& model, State& s, double /*t*/, double length, WorkCounters& /*work*/) {
    if (!ready_) self().set_up(model.inertia);
    axes_.flow(s, s_, c_s_, length);
  }

  template <class Model>
  StepStatus step(const Model& model, State& s, double t, double h, WorkCounters& work) {
    outer(model, s, t, 0.5 * h, work);
    self().inner(model, s, t, h, work);
    outer(model, s, t + h, 0.5 * h, work);
    return {};
  }

 protected:
  rotation_flows::PrincipalAxisFlows axes_;
  int s_ = 0;          // the axis of the smallest moment
  double c_s_ = 0.0;   // its rotation's coefficient
  bool ready_ = false;

 private:
  Derived& self() { return static_cast<Derived&>(*this); }
};

}  // namespace lgi::integrators
