#pragma once
// The invariants of docs/conventions.md §6, each reported only for the scenes where
// it is one:
//   free body:        H, |Π|, m = RΠ (three components)
//   heavy top:        H, Π·Γ (vertical angular momentum)
//   Lagrange top:     + Π3           (J1 = J2, χ ∥ e3)
//   Kovalevskaya top: + K = (Ω1² − Ω2² − cΓ1)² + (2Ω1Ω2 − cΓ2)², c = m g ℓ/J3
//                     (J1 = J2 = 2 J3, χ = (ℓ, 0, 0))
//   undamped spring:  H
//   every scene:      RᵀR = I (reported as the orthogonality error)
// Energy is always computed as an observable; it is an invariant only where
// no damping or drive acts.
#include <array>
#include <string>
#include <vector>

#include "integrators/system/model.hpp"

namespace lgi::system {

struct InvariantValues {
  static constexpr std::size_t capacity = 4;
  double energy = 0.0;
  Vec3 space_momentum = Vec3::Zero();
  std::array<double, capacity> scalars{};  // in the order of SceneInvariants::scalar_names()
  double orthogonality_error = 0.0;
};

class SceneInvariants {
 public:
  SceneInvariants(const Scene& scene, const AnyModel& model);

  bool free_body() const { return free_body_; }
  bool heavy_top() const { return heavy_top_; }
  bool lagrange_top() const { return lagrange_; }
  bool kovalevskaya_top() const { return kovalevskaya_; }
  bool energy_conserved() const { return energy_conserved_; }
  /// Scalar invariants besides energy, by their /observables names.
  const std::vector<std::string>& scalar_names() const { return names_; }
  /// Every invariant's name, energy and the spatial momentum included, for listings.
  std::vector<std::string> all_names() const;

  /// The quantities whose errors a run reports, in a fixed order: "energy"
  /// (where conserved), each scalar invariant, "angular_momentum_space"
  /// (free body), "orthogonality". Output layouts prefix or suffix them.
  std::vector<std::string> error_names() const;
  /// Their errors at `v` against `initial`, in the order of error_names():
  /// relative (relative_error; the spatial momentum as |m − m0|/|m0|), the
  /// orthogonality error as it is. Writes into `out` (sized here; no
  /// allocation once it has the size).
  void errors(const InvariantValues& initial, const InvariantValues& v, std::vector<double>& out) const;

  InvariantValues evaluate(const State& s) const;
  double energy(const State& s) const;
  Vec3 omega(const State& s) const;

 private:
  const AnyModel* model_;
  bool free_body_ = false, heavy_top_ = false, lagrange_ = false, kovalevskaya_ = false;
  bool magnetic_only_ = false;  // a dipole in a uniform field and no other torque: Π·RᵀB is a Casimir
  Vec3 field_ = Vec3::Zero();
  bool energy_conserved_ = false;
  double kovalevskaya_c_ = 0.0;
  std::vector<std::string> names_;
};

/// Relative invariant error |I − I0|/|I0|, absolute where I0 = 0 (docs/conventions.md §7).
inline double relative_error(double value, double initial) {
  const double d = std::abs(value - initial);
  return initial != 0.0 ? d / std::abs(initial) : d;
}

}  // namespace lgi::system
