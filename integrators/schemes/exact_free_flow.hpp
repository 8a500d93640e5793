#pragma once
// Scheme `exact`: the exact flow of the free rigid body (system/free_body_exact.hpp),
// evaluated at each output time from the initial state, so no error
// accumulates from step to step. Free bodies only; the registry refuses
// other scenes. Conserves H, |Π| and m = RΠ to round-off.
#include <optional>

#include "integrators/core/scheme_interface.hpp"
#include "integrators/system/free_body_exact.hpp"

namespace lgi::integrators {

class ExactFreeFlow {
 public:
  static constexpr SchemeFacts facts{
      .order = 0,
      .properties = {.symmetric = true, .conserves_energy = true, .conserves_momentum_norm = true,
                     .conserves_spatial_momentum = true},
      .support = SceneSupport::free_body_only,
      .reference = "Jacobi elliptic functions for Pi; elliptic integral of the third kind for R (Celledoni, Fasso, "
                   "Safstrom & Zanna, SIAM J. Sci. Comput. 30 (2008))"};
  void start(const system::FreeBody& model, const State& initial, double t0) {
    flow_.emplace(model.inertia, initial);
    t0_ = t0;
  }
  StepStatus step(const system::FreeBody& /*model*/, State& s, double t, double h, WorkCounters& /*work*/) const {
    s = flow_->at(t + h - t0_);
    return {};
  }

 private:
  std::optional<system::FreeBodyExactFlow> flow_;
  double t0_ = 0.0;
};

}  // namespace lgi::integrators
