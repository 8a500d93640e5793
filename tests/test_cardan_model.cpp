// The Cardan top's closed forms (integrators/system/cardan.hpp, derived in
// docs/cardan.md §2–§4) against automatic differentiation of the
// mechanism itself: the three frames' rotation matrices R_o = Ry(α)Rz(q1),
// R_i = R_o Rx(q2), R_b = R_i Rz(q3), differentiated by dual numbers
// (tests/support/dual.hpp). Angular velocities come from Rᵀ ∂R/∂q_k (no
// E or F matrix), the mass matrix from T = Σ ½ ωᵀ I ω, ∂M/∂q from nested
// duals, ∇V from duals of the centres of mass' heights. Then the canonical
// field ṗ = ½ vᵀ ∂M v − ∇V, v = M⁻¹p, is compared with CardanTop::field().
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <random>

#include <Eigen/Eigenvalues>

#include "integrators/system/cardan.hpp"
#include "lie/charts.hpp"
#include "support/dual.hpp"

namespace test_cardan_model {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
using testing::Dual;
using testing::Mat3S;
using testing::Vec3S;

namespace {

struct Mechanism {
  system::CardanTop top;
  lie::Vec3 outer_moments;  // the outer ring's three moments (only the third may enter T)
};

template <class S>
testing::Arr<Mat3S<S>, 3> frames(double alpha, const Vec3S<S>& q) {
  const Mat3S<S> ro = testing::mul(testing::rotation<S>(1, S(alpha)), testing::rotation<S>(2, q[0]));
  const Mat3S<S> ri = testing::mul(ro, testing::rotation<S>(0, q[1]));
  return {ro, ri, testing::mul(ri, testing::rotation<S>(2, q[2]))};
}

/// W_f with ω_f = W_f q̇ in frame f's own axes: column k is vee(R_fᵀ ∂R_f/∂q_k).
template <class S>
testing::Arr<Mat3S<S>, 3> angular_jacobians(double alpha, const Vec3S<S>& q) {
  testing::Arr<Mat3S<S>, 3> W{};
  for (int k = 0; k < 3; ++k) {
    Vec3S<Dual<S>> x;
    for (int i = 0; i < 3; ++i) x[i] = Dual<S>(q[i], S(i == k ? 1.0 : 0.0));
    const auto F = frames<Dual<S>>(alpha, x);
    for (int f = 0; f < 3; ++f) {
      Mat3S<S> A{};
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          S sum(0.0);
          for (int m = 0; m < 3; ++m) sum = sum + F[f][m][i].v * F[f][m][j].d;
          A[i][j] = sum;
        }
      W[f][0][k] = A[2][1];
      W[f][1][k] = A[0][2];
      W[f][2][k] = A[1][0];
    }
  }
  return W;
}

/// M = Σ_f W_fᵀ I_f W_f.
template <class S>
Mat3S<S> mass_matrix_ad(const Mechanism& mech, const Vec3S<S>& q) {
  const auto W = angular_jacobians<S>(mech.top.suspension.tilt, q);
  lie::Mat3 inertia[3] = {mech.outer_moments.asDiagonal(), mech.top.suspension.inner_inertia.asDiagonal(),
                          mech.top.J};
  Mat3S<S> M{};
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      S sum(0.0);
      for (int f = 0; f < 3; ++f)
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) sum = sum + inertia[f](i, j) * (W[f][i][a] * W[f][j][b]);
      M[a][b] = sum;
    }
  return M;
}

/// V = g Σ_f m_f (R_f c_f)·e3.
template <class S>
S potential_ad(const Mechanism& mech, const Vec3S<S>& q) {
  const auto F = frames<S>(mech.top.suspension.tilt, q);
  const auto& s = mech.top.suspension;
  const lie::Vec3 mc[3] = {s.outer_mass * s.outer_center, s.inner_mass * s.inner_center, mech.top.mass * mech.top.chi};
  S v(0.0);
  for (int f = 0; f < 3; ++f)
    for (int j = 0; j < 3; ++j) v = v + mc[f][j] * F[f][2][j];
  return mech.top.g * v;
}

lie::Mat3 to_eigen(const Mat3S<double>& m) {
  lie::Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r(i, j) = m[i][j];
  return r;
}

Mechanism sample_mechanism(std::mt19937& rng, bool massive_rings) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.2, 1.0);
  Mechanism mech;
  lie::Mat3 A = lie::Mat3::Random();
  mech.top.J = A * A.transpose() + lie::Mat3::Identity();
  mech.top.mass = pos(rng);
  mech.top.chi = lie::Vec3(u(rng), u(rng), u(rng));
  mech.top.g = 9.81;
  mech.top.suspension.tilt = std::acos(u(rng));
  if (massive_rings) {
    mech.top.suspension.outer_inertia = pos(rng);
    mech.top.suspension.inner_inertia = lie::Vec3(pos(rng), pos(rng), pos(rng));
    mech.top.suspension.outer_mass = pos(rng);
    mech.top.suspension.outer_center = lie::Vec3(u(rng), u(rng), u(rng));
    mech.top.suspension.inner_mass = pos(rng);
    mech.top.suspension.inner_center = lie::Vec3(u(rng), u(rng), u(rng));
  }
  // The outer ring's moments about axes other than its own must not enter T.
  mech.outer_moments = lie::Vec3(3.0 * pos(rng), 5.0 * pos(rng), mech.top.suspension.outer_inertia);
  return mech;
}

}  // namespace

TEST_CASE("Cardan top: M(q), dM/dq, grad V and the canonical field agree with automatic differentiation",
          "[cardan][model]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-3.0, 3.0), mom(-2.0, 2.0);
  for (int trial = 0; trial < 20; ++trial) {
    const Mechanism mech = sample_mechanism(rng, trial % 2 == 0);
    const system::CardanTop& top = mech.top;
    const lie::Vec3 q(angle(rng), 0.3 + 2.5 * (angle(rng) + 3.0) / 6.0, angle(rng));  // q2 in (0.3, 2.8)
    const Vec3S<double> qs{q[0], q[1], q[2]};
    const lie::Mat3 M_ad = to_eigen(mass_matrix_ad<double>(mech, qs));
    CHECK((top.mass_matrix(q) - M_ad).norm() <= 1e-13 * M_ad.norm());

    const auto dM = top.mass_matrix_derivatives(q);
    lie::Vec3 grad_V_ad;
    std::array<lie::Mat3, 3> dM_ad;
    for (int j = 0; j < 3; ++j) {
      Vec3S<Dual<double>> x;
      for (int i = 0; i < 3; ++i) x[i] = Dual<double>(q[i], i == j ? 1.0 : 0.0);
      const Mat3S<Dual<double>> Md = mass_matrix_ad<Dual<double>>(mech, x);
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) dM_ad[static_cast<std::size_t>(j)](a, b) = Md[a][b].d;
      grad_V_ad[j] = potential_ad<Dual<double>>(mech, x).d;
      CHECK((dM[static_cast<std::size_t>(j)] - dM_ad[static_cast<std::size_t>(j)]).norm() <= 1e-12 * M_ad.norm());
    }
    CHECK(std::abs(top.potential(q) - potential_ad<double>(mech, qs)) <= 1e-13 * (1.0 + grad_V_ad.norm()));
    CHECK((top.potential_gradient(q) - grad_V_ad).norm() <= 1e-12 * (1.0 + grad_V_ad.norm()));

    const system::TorusState s{q, lie::Vec3(mom(rng), mom(rng), mom(rng))};
    const lie::Vec3 v = M_ad.inverse() * s.p;
    lie::Vec3 pdot;
    for (int k = 0; k < 3; ++k) pdot[k] = 0.5 * v.dot(dM_ad[static_cast<std::size_t>(k)] * v) - grad_V_ad[k];
    const system::Vec6 f = top.field(s);
    CHECK((f.head<3>() - v).norm() <= 1e-11 * (1.0 + v.norm()));
    CHECK((f.tail<3>() - pdot).norm() <= 1e-10 * (1.0 + pdot.norm()));
    // The body's Ω = E q̇ is the AD angular velocity of the body frame.
    const lie::Mat3 Wb = to_eigen(angular_jacobians<double>(top.suspension.tilt, qs)[2]);
    CHECK((system::CardanTop::body_rate_matrix(q) - Wb).norm() <= 1e-13);
    CHECK((top.attitude(q) - to_eigen(frames<double>(top.suspension.tilt, qs)[2])).norm() <= 1e-14);
  }
}

TEST_CASE("Cardan top: with a vertical outer axis the Cardan angles are the ZXZ Euler angles", "[cardan][model]") {
  system::CardanTop top;
  top.J = lie::Vec3(0.8, 0.9, 1.1).asDiagonal();
  const lie::Vec3 q(0.4, 1.1, -2.0), qdot(0.3, -0.7, 5.0);
  const lie::EulerZXZ e{q[0], q[1], q[2]};
  CHECK((top.attitude(q) - lie::matrix_from_euler_zxz(e)).norm() <= 1e-15);
  CHECK((system::CardanTop::body_rate_matrix(q) * qdot - lie::omega_from_euler_zxz_rates(e, qdot)).norm() <= 1e-14);
}

TEST_CASE("Cardan top: massless rings make M singular at gimbal lock, massive rings do not", "[cardan][model]") {
  system::CardanTop top;
  top.J = lie::Vec3(0.8, 0.9, 1.1).asDiagonal();
  for (double q2 : {0.3, 1.0, 2.5})
    CHECK(top.mass_matrix(lie::Vec3(0.2, q2, 0.7)).determinant() ==
          Approx(top.J.determinant() * std::sin(q2) * std::sin(q2)).epsilon(1e-12));
  CHECK(std::abs(top.mass_matrix(lie::Vec3(0.2, 0.0, 0.7)).determinant()) <= 1e-15);
  top.suspension.outer_inertia = 0.1;
  top.suspension.inner_inertia = lie::Vec3(0.05, 0.1, 0.05);
  for (double q2 : {0.0, std::numbers::pi})
    CHECK(Eigen::SelfAdjointEigenSolver<lie::Mat3>(top.mass_matrix(lie::Vec3(0.2, q2, 0.7))).eigenvalues().minCoeff() >
          0.04);
}

}  // namespace test_cardan_model
