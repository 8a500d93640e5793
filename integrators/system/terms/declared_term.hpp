#pragma once
// A term a scene may or may not declare: the term and a run-time switch. The
// scene model (scene_terms.hpp) holds one of these per scene term, so a single
// model type serves every combination of declared terms (one instantiation
// of each scheme instead of one per subset). An undeclared term contributes
// exact zeros, which leave every sum bit-for-bit as without it (x + 0 = x).
// Declared<T> is itself a TorqueTerm with T's traits and capabilities.
#include <type_traits>

#include "integrators/system/terms/discrete_gradient_term.hpp"
#include "integrators/system/terms/frozen_kick_term.hpp"
#include "integrators/system/terms/time_derivative_term.hpp"

namespace lgi::system {

namespace detail {
template <class T>
struct discrete_start_of {
  struct type {};
};
template <DiscreteGradientTerm T>
struct discrete_start_of<T> {
  using type = typename T::DiscreteStart;
};
}  // namespace detail

template <TorqueTerm T>
struct Declared {
  using Term = T;
  T term{};
  bool active = false;

  static constexpr TermTraits traits = T::traits;
  /// The rows of R the torque reads (TermTraits::attitude_rows, or the term's
  /// own attitude_rows() where its parameters narrow them): none when inactive.
  unsigned attitude_rows() const { return active ? attitude_rows_of(term) : 0u; }

  Vec3 torque(const Mat3& R, const Vec3& Pi, const Vec3& Omega, double t) const {
    return active ? term.torque(R, Pi, Omega, t) : Vec3::Zero();
  }
  Vec3 potential_torque(const Mat3& R) const { return active ? term.potential_torque(R) : Vec3::Zero(); }
  double potential(const Mat3& R) const { return active ? term.potential(R) : 0.0; }
  bool is_conservative() const { return !active || term.is_conservative(); }
  Mat3 torque_jacobian_attitude(const Mat3& R, const Vec3& Pi, const Vec3& Omega, double t) const {
    return active ? term.torque_jacobian_attitude(R, Pi, Omega, t) : Mat3::Zero();
  }
  Mat3 torque_jacobian_momentum(const Mat3& R, const Vec3& Pi, const Vec3& Omega, double t, const Mat3& J_inv) const {
    return active ? term.torque_jacobian_momentum(R, Pi, Omega, t, J_inv) : Mat3::Zero();
  }

  Vec3 torque_time_derivative(const Mat3& R, const Vec3& Pi, const Vec3& Omega, double t) const
    requires TimeDerivativeTerm<T>
  {
    return active ? term.torque_time_derivative(R, Pi, Omega, t) : Vec3::Zero();
  }

  Vec3 frozen_torque(const Mat3& R, double t) const
    requires FrozenKickTerm<T>
  {
    return active ? term.frozen_torque(R, t) : Vec3::Zero();
  }
  double damping() const
    requires FrozenKickTerm<T>
  {
    return active ? term.damping() : 0.0;
  }

  using DiscreteStart = typename detail::discrete_start_of<T>::type;
  DiscreteStart discrete_start(const Mat3& R) const
    requires DiscreteGradientTerm<T>
  {
    return active ? term.discrete_start(R) : DiscreteStart{};
  }
  void add_discrete_torque(const DiscreteStart& start, const CayleyStep& step, DiscreteTorque& out) const
    requires DiscreteGradientTerm<T>
  {
    if (active) term.add_discrete_torque(start, step, out);
  }
};

}  // namespace lgi::system
