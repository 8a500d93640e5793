#pragma once
// An independent reference for tests: Boost.Odeint's controlled
// runge_kutta_fehlberg78 on (q, Π) ∈ ℝ⁴ × ℝ³ with q̇ = ½ q ⊗ (0, Ω),
// sharing only the model's Π̇ with the code under test (no lie/ maps, no
// scheme). The quaternion is renormalised only when handed to the model.
#include <array>
// odeint copies its steppers' scratch arrays before their first use, which
// GCC reports (-Wuninitialized) once inlined into this file; the copies are
// overwritten before they are read.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <boost/numeric/odeint.hpp>
#pragma GCC diagnostic pop

#include "integrators/system/rigid_body.hpp"
#include "lie/quaternion.hpp"

namespace lgi::testing {

using ReferenceVector = std::array<double, 7>;  // w, x, y, z, Π1, Π2, Π3

template <class Model>
system::State reference_solution(const Model& model, const system::State& initial, double t0, double t1,
                                 double tol = 1e-14) {
  namespace odeint = boost::numeric::odeint;
  const Eigen::Quaterniond q0 = lie::quat_from_matrix(initial.R);
  ReferenceVector x{q0.w(), q0.x(), q0.y(), q0.z(), initial.Pi.x(), initial.Pi.y(), initial.Pi.z()};
  auto field = [&](const ReferenceVector& y, ReferenceVector& dy, double t) {
    const Eigen::Quaterniond q(y[0], y[1], y[2], y[3]);
    const Eigen::Vector3d Pi(y[4], y[5], y[6]);
    const Eigen::Vector3d W = model.omega(Pi);
    // q̇ = ½ q ⊗ (0, Ω)
    dy[0] = -0.5 * (q.x() * W.x() + q.y() * W.y() + q.z() * W.z());
    dy[1] = 0.5 * (q.w() * W.x() + q.y() * W.z() - q.z() * W.y());
    dy[2] = 0.5 * (q.w() * W.y() + q.z() * W.x() - q.x() * W.z());
    dy[3] = 0.5 * (q.w() * W.z() + q.x() * W.y() - q.y() * W.x());
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    if constexpr (Model::has_torque) R = lie::matrix_from_quat(q.normalized());
    const Eigen::Vector3d dPi = model.momentum_rate(R, Pi, W, t);
    dy[4] = dPi.x();
    dy[5] = dPi.y();
    dy[6] = dPi.z();
  };
  auto stepper = odeint::make_controlled<odeint::runge_kutta_fehlberg78<ReferenceVector>>(tol, tol);
  odeint::integrate_adaptive(stepper, field, x, t0, t1, 1e-4);
  const Eigen::Quaterniond q(x[0], x[1], x[2], x[3]);
  return {lie::matrix_from_quat(q.normalized()), Eigen::Vector3d(x[4], x[5], x[6])};
}

}  // namespace lgi::testing
