#pragma once
// The attitude of a given vertical direction Γ = Rᵀe3 in the body frame, with
// the rotation about the vertical fixed (ψ = 0): the one rule of the sweep
// specs' initial.gamma, the scenes' [initial] gamma and the state files of
// lgi indicators (experiments/SWEEPS.md, experiments/scenes/README.md).
#include <algorithm>
#include <cmath>

#include "lie/charts.hpp"

namespace lgi::experiments {

/// R with Γ = Rᵀe3 = γ (a unit vector) and ψ = 0: R = Rx(θ) Rz(φ),
/// γ = (sinθ sinφ, sinθ cosφ, cosθ).
inline lie::Mat3 attitude_from_gamma(const lie::Vec3& gamma) {
  const double theta = std::acos(std::clamp(gamma.z(), -1.0, 1.0));
  const double phi = std::atan2(gamma.x(), gamma.y());
  return lie::matrix_from_euler_zxz({0.0, theta, phi});
}

}  // namespace lgi::experiments
