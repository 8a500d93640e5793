#pragma once
// A term with a closed-form ∂τ/∂t (the Rosenbrock baselines' time column);
// other time-dependent terms fall back to a central difference there.
#include <concepts>

#include "integrators/system/terms/torque_term.hpp"

namespace lgi::system {

template <class T>
concept TimeDerivativeTerm = TorqueTerm<T> && requires(const T& term, const Mat3& R, const Vec3& v, double t) {
  { term.torque_time_derivative(R, v, v, t) } -> std::same_as<Vec3>;
};

}  // namespace lgi::system
