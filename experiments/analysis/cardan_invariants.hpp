#pragma once
// The invariants of a Cardan top whose errors a long run reports (lgi
// long-time on T³ × ℝ³, docs/cardan.md §7): the mechanism's energy H, and
// the momentum p1 where it is an integral (a vertical outer axis, or no
// potential: CardanTop::outer_angle_cyclic). The counterpart of
// system::SceneInvariants on SO(3) × ℝ³, with the same interface
// (error_names, evaluate, errors) and the same relative errors.
#include <string>
#include <vector>

#include "integrators/system/cardan.hpp"
#include "integrators/system/invariants.hpp"

namespace lgi::experiments {

class CardanInvariants {
 public:
  struct Values {
    double energy = 0.0;
    double p1 = 0.0;
  };

  explicit CardanInvariants(const system::CardanTop& top) : top_(top), p1_conserved_(top.outer_angle_cyclic()) {}

  /// "energy", then "cardan_momentum_1" where p1 is an integral.
  std::vector<std::string> error_names() const {
    if (p1_conserved_) return {"energy", "cardan_momentum_1"};
    return {"energy"};
  }
  Values evaluate(const system::TorusState& x) const { return {top_.energy(x), x.p(0)}; }
  /// The relative errors (system::relative_error) in the order of error_names().
  void errors(const Values& initial, const Values& v, std::vector<double>& out) const {
    out.resize(p1_conserved_ ? 2 : 1);
    out[0] = system::relative_error(v.energy, initial.energy);
    if (p1_conserved_) out[1] = system::relative_error(v.p1, initial.p1);
  }

 private:
  const system::CardanTop& top_;
  bool p1_conserved_;
};

}  // namespace lgi::experiments
