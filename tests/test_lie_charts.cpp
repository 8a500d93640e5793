// Property tests for lie/charts.hpp: Euler angles ZXZ and the rotation-vector
// chart (docs/conventions.md §2). R = Rz(ψ) Rx(θ) Rz(φ), body Ω with Ω̂ = RᵀṘ.
//
// Set LGI_TEST_REPORT=1 to print the worst error observed for each property.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "lie/charts.hpp"
#include "lie/so3.hpp"
#include "support/rk4.hpp"
#include "support/worst_error.hpp"

namespace test_lie_charts {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

namespace {

using lgi::lie::EulerZXZ;
using lgi::lie::Mat3;
using lgi::lie::Vec3;

constexpr double pi = std::numbers::pi;

double maxabs(const Mat3& m) { return m.cwiseAbs().maxCoeff(); }

using lgi::testing::omega_of_t;
using lgi::testing::rk4;
using lgi::testing::Worst;

std::string describe(const EulerZXZ& e) {
  std::ostringstream o;
  o.precision(17);
  o << "psi = " << e.psi << ", theta = " << e.theta << ", phi = " << e.phi;
  return o.str();
}

/// Distance between two angles modulo 2π.
double angle_diff(double a, double b) { return std::abs(std::remainder(a - b, 2.0 * pi)); }

const std::array<double, 7> kPsi = {-3.0, -1.2, 0.0, 0.7, 2.5, pi, -pi + 1e-3};
const std::array<double, 7> kPhi = {-2.9, -0.4, 0.0, 1.1, 3.0, pi, 1e-7};
const std::array<double, 11> kThetaRegular = {1e-8, 1e-6, 1e-3, 0.3, 1.0, pi / 2, 2.5, pi - 1e-3, pi - 1e-6, pi - 1e-8,
                                              2e-9};

/// A rotation close to `target` whose every entry carries ordinary absolute
/// round-off (as an integrator's output does), unlike a product of
/// elementary rotations, whose third row and column are exact to relative
/// precision even when tiny.
Mat3 roughened(const Mat3& target, const Vec3& a) {
  const Mat3 A = lgi::lie::exp_so3(a);
  return A * lgi::lie::exp_so3(lgi::lie::log_so3(A.transpose() * target));
}

}  // namespace

using namespace lgi::lie;

// ===========================================================================
// Euler angles ZXZ

TEST_CASE("Euler ZXZ: round trip at regular angles", "[lie][charts][euler]") {
  Worst w_R("matrix(euler(R)) - R, R from angles, regular (max entry)");
  Worst w_th("|theta' - theta|, regular");
  Worst w_ang("|psi' - psi|, |phi' - phi| (mod 2pi) * sin(theta)");
  for (double th : kThetaRegular) {
    for (double psi : kPsi) {
      for (double phi : kPhi) {
        const EulerZXZ e{psi, th, phi};
        INFO(describe(e));
        const Mat3 R = matrix_from_euler_zxz(e);
        const EulerZXZExtraction x = euler_zxz_from_matrix(R);
        CHECK_FALSE(x.singular);
        CHECK(x.angles.theta >= 0.0);
        CHECK(x.angles.theta <= pi);
        CHECK(std::abs(x.angles.psi) <= pi);
        CHECK(std::abs(x.angles.phi) <= pi);
        CHECK(w_th(std::abs(x.angles.theta - th), describe(e)) <= 1e-15);
        CHECK(w_R(maxabs(Mat3(matrix_from_euler_zxz(x.angles) - R)), describe(e)) <= 1e-15);
        // ψ and φ themselves are conditioned like 1/sinθ.
        const double st = std::sin(th);
        CHECK(w_ang(angle_diff(x.angles.psi, psi) * st, describe(e)) <= 1e-15);
        CHECK(w_ang(angle_diff(x.angles.phi, phi) * st, describe(e)) <= 1e-15);
      }
    }
  }
}

TEST_CASE("Euler ZXZ: singular attitudes θ = 0, π, 1e-12, π − 1e-12", "[lie][charts][euler]") {
  Worst w_exact("reproduce R at theta in {0, pi}, any hint (max entry)");
  Worst w_hint("reproduce R with phi_hint = true phi (max entry)");
  Worst w_nohint("reproduce R with phi_hint != phi (max entry; bound 2 sin(theta))");
  Worst w_th("|theta' - theta|, singular");
  for (double th : {0.0, pi, 1e-12, pi - 1e-12, 5e-10, pi - 5e-10}) {
    for (double psi : kPsi) {
      for (double phi : kPhi) {
        const EulerZXZ e{psi, th, phi};
        INFO(describe(e));
        const Mat3 R = matrix_from_euler_zxz(e);
        const double st = std::sin(th);  // 1.2e-16 at th = π (the double nearest π)
        for (double hint : {0.0, phi, 1.3}) {
          INFO("phi_hint = " << hint);
          const EulerZXZExtraction x = euler_zxz_from_matrix(R, hint);
          CHECK(x.singular);
          CHECK(x.angles.phi == hint);
          CHECK(w_th(std::abs(x.angles.theta - th), describe(e)) <= 1e-15);
          const double err = maxabs(Mat3(matrix_from_euler_zxz(x.angles) - R));
          if (th == 0.0 || th == pi) {
            CHECK(w_exact(err, describe(e)) <= 1e-15);
          } else if (hint == phi) {
            CHECK(w_hint(err, describe(e)) <= 1e-15);
          } else {
            // With φ pinned to a hint that is not the true spin, R is only
            // reproduced to O(sinθ): Rz(ψ)Rx(θ)Rz(φ) = Rz(ψ+φ)·(a rotation by θ about
            // an axis in the x-y plane at angle −φ), and that axis is lost.
            // At θ = 1e-12 the error is ~1e-12, not 1e-15, whatever the code does.
            CHECK(w_nohint(err, describe(e)) <= 1e-15 + 2.0 * st);
          }
        }
      }
    }
  }
}

TEST_CASE("Euler ZXZ: round trip of rotations not built from angles (generic round-off)", "[lie][charts][euler]") {
  // An integrator's attitude carries absolute round-off ε in every entry. Near
  // sinθ → 0 the angles ψ, φ separately are then only known to ε/sinθ, but
  // ψ + φ (θ → 0) and ψ − φ (θ → π) are known to ε, and R must be reproduced to
  // round-off whenever the regular branch is taken (sinθ ≥ 1e-9).
  Worst w_reg("reproduce generic R, regular branch (max entry)");
  Worst w_sing("reproduce generic R, singular branch (max entry; bound 2 sin(theta))");
  const std::vector<Vec3> as = {Vec3(0.3, -1.2, 2.0), Vec3(-2.0, 0.5, 0.1), Vec3(1.0, 1.0, -1.0)};
  for (double th : {0.5, 2.0, 1e-2, 1e-4, 1e-6, 1e-8, 2e-9, 1.1e-9, pi - 1e-4, pi - 1e-8, pi - 2e-9, 5e-10, pi - 5e-10}) {
    for (double psi : kPsi) {
      for (double phi : kPhi) {
        for (const Vec3& a : as) {
          const EulerZXZ e{psi, th, phi};
          INFO(describe(e) << ", roughened with a = (" << a.transpose() << ")");
          const Mat3 R = roughened(matrix_from_euler_zxz(e), a);
          REQUIRE(orthogonality_error(R) < 1e-14);
          const EulerZXZExtraction x = euler_zxz_from_matrix(R);
          const double err = maxabs(Mat3(matrix_from_euler_zxz(x.angles) - R));
          const double s = std::hypot(R(2, 0), R(2, 1));
          if (!x.singular) {
            CHECK(w_reg(err, describe(e)) <= 2e-15);
          } else {
            CHECK(w_sing(err, describe(e)) <= 2e-15 + 2.0 * s);
          }
        }
      }
    }
  }
  // And on rotations from exp: every sample angle about several axes.
  for (double th : {0.0, 1e-12, 1e-8, 1e-4, 1e-2, 1.0, 2.0, pi - 1e-6, pi - 1e-8, pi}) {
    for (const Vec3& n : {Vec3(Vec3::UnitX()), Vec3(Vec3::UnitZ()), Vec3(Vec3(1.0, 2.0, 3.0).normalized()),
                          Vec3(Vec3(1e-3, -1.0, 2e-3).normalized()), Vec3(Vec3(1e-9, 2e-9, 1.0).normalized())}) {
      INFO("R = exp(theta n), theta = " << th << ", n = (" << n.transpose() << ")");
      const Mat3 R = exp_so3(th * n);
      const EulerZXZExtraction x = euler_zxz_from_matrix(R);
      const double err = maxabs(Mat3(matrix_from_euler_zxz(x.angles) - R));
      const double s = std::hypot(R(2, 0), R(2, 1));
      if (!x.singular) {
        CHECK(w_reg(err, "exp path") <= 2e-15);
      } else {
        CHECK(w_sing(err, "exp path") <= 2e-15 + 2.0 * s);
      }
    }
  }
}

TEST_CASE("Euler ZXZ: Γ = Rᵀ e3 = (sinθ sinφ, sinθ cosφ, cosθ)", "[lie][charts][euler]") {
  Worst w("R^T e3 - Gamma(theta, phi)");
  for (double th : {0.0, 1e-12, 0.3, 1.0, pi / 2, 2.5, pi - 1e-8, pi}) {
    for (double psi : kPsi) {
      for (double phi : kPhi) {
        const EulerZXZ e{psi, th, phi};
        INFO(describe(e));
        const Vec3 gamma(std::sin(th) * std::sin(phi), std::sin(th) * std::cos(phi), std::cos(th));
        CHECK(w((matrix_from_euler_zxz(e).transpose() * Vec3::UnitZ() - gamma).norm(), describe(e)) <= 1e-15);
      }
    }
  }
}

TEST_CASE("Euler ZXZ: omega_from_euler_zxz_rates = (Rᵀ Ṙ)ˇ by central differences", "[lie][charts][euler]") {
  const double h = 1e-5;  // truncation ~h²/6, round-off ~ε/h: both ~1e-11
  Worst w("omega_from_euler_zxz_rates - vee(R^T dR/dt)");
  Worst w_teeth("[teeth] |body - space velocity| (must be large)");
  const std::vector<Vec3> rates = {Vec3(0.3, -1.1, 2.0), Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ(),
                                   Vec3(-0.8, 0.25, 0.6)};
  for (double th : {0.0, 1e-8, 0.3, 1.0, pi / 2, 2.5, pi - 1e-8, pi}) {
    for (double psi : {-1.2, 0.7, 2.5}) {
      for (double phi : {-2.9, 0.0, 1.1}) {
        const EulerZXZ e{psi, th, phi};
        const Mat3 R = matrix_from_euler_zxz(e);
        for (const Vec3& r : rates) {
          INFO(describe(e) << ", rates = (" << r.transpose() << ")");
          auto at = [&e, &r](double t) {
            return matrix_from_euler_zxz({e.psi + t * r.x(), e.theta + t * r.y(), e.phi + t * r.z()});
          };
          const Mat3 dR = (at(h) - at(-h)) / (2.0 * h);
          const Vec3 omega = omega_from_euler_zxz_rates(e, r);
          CHECK(w((vee(Mat3(R.transpose() * dR)) - omega).norm(), describe(e)) <= 1e-8 * r.norm());
          CHECK(maxabs(Mat3(R.transpose() * dR + dR.transpose() * R)) <= 1e-8);  // RᵀṘ is skew
          if (r == rates[0] && th == 1.0) {
            // Body and spatial velocities differ by O(1) here: the check above does see the frame.
            CHECK(w_teeth((vee(Mat3(dR * R.transpose())) - omega).norm(), describe(e)) > 0.1);
          }
        }
      }
    }
  }
}

TEST_CASE("Euler ZXZ: euler_zxz_rates_from_omega inverts omega_from_euler_zxz_rates", "[lie][charts][euler]") {
  Worst w_r("rates -> omega -> rates, * sin(theta) / |rates|");
  Worst w_o("omega -> rates -> omega, * sin(theta) / |omega|");
  const std::vector<Vec3> vs = {Vec3(0.3, -1.1, 2.0), Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ(),
                                Vec3(-0.8, 0.25, 0.6)};
  for (double th : {1e-6, 1e-3, 0.3, 1.0, pi / 2, 2.5, pi - 1e-3, pi - 1e-6}) {
    for (double psi : kPsi) {
      for (double phi : kPhi) {
        const EulerZXZ e{psi, th, phi};
        INFO(describe(e));
        const double st = std::sin(th);  // the inverse divides by sinθ: error ~ε/sinθ
        for (const Vec3& v : vs) {
          CHECK(w_r((euler_zxz_rates_from_omega(e, omega_from_euler_zxz_rates(e, v)) - v).norm() * st / v.norm(),
                    describe(e)) <= 2e-15);
          CHECK(w_o((omega_from_euler_zxz_rates(e, euler_zxz_rates_from_omega(e, v)) - v).norm() * st / v.norm(),
                    describe(e)) <= 2e-15);
        }
      }
    }
  }
}

TEST_CASE("Euler ZXZ: integrating the angle rates reproduces Ṙ = R Ω̂(t)", "[lie][charts][euler]") {
  const double T = 1.0;
  const int n = 1000;
  using V3 = Eigen::Vector3d;
  Worst w("|R(e(T)) - R(T)| (RK4 on angles vs RK4 in R^9)");
  for (const EulerZXZ& e0 : {EulerZXZ{0.3, 1.0, -0.5}, EulerZXZ{-2.0, 2.0, 1.5}, EulerZXZ{1.0, 0.6, 3.0}}) {
    INFO(describe(e0));
    const V3 a = rk4<V3>(
        [](double t, const V3& x) { return euler_zxz_rates_from_omega({x(0), x(1), x(2)}, omega_of_t(t)); },
        V3(e0.psi, e0.theta, e0.phi), T, n);
    const Mat3 r = lgi::testing::body_attitude_rk4(matrix_from_euler_zxz(e0), T, n);
    REQUIRE(std::sin(a(1)) > 0.05);  // stayed away from the singular set
    CHECK(w(maxabs(Mat3(matrix_from_euler_zxz({a(0), a(1), a(2)}) - r)),
            describe(e0)) <= 1e-10);
  }
}

// ===========================================================================
// Rotation vector

TEST_CASE("Rotation vector chart: round trip, rate = dexpinv_body, and its kinematics", "[lie][charts][rotvec]") {
  Worst w_rt("log(exp(Psi)) - Psi / max(1,|Psi|), |Psi| < pi");
  Worst w_rr("exp(log(R)) - R (max entry)");
  Worst w_cd("vee(R^T dR/dt) along rotation_vector_rate - omega");
  const double h = 1e-5;
  const std::vector<Vec3> ns = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ(), Vec3(1.0, 2.0, 3.0).normalized(),
                                Vec3(-0.7, 0.2, 0.5).normalized()};
  const std::vector<Vec3> omegas = {Vec3(0.3, -0.5, 0.8), Vec3(-1.1, 0.4, 0.25), Vec3::UnitZ()};
  for (double th : {0.0, 1e-12, 1e-8, 1e-4, 1e-2, 1.0, 2.0, pi - 1e-6, pi - 1e-8, pi}) {
    for (const Vec3& n : ns) {
      const Vec3 psi = th * n;
      INFO("theta = " << th << ", n = (" << n.transpose() << ")");
      const std::string where = "theta = " + std::to_string(th);
      const Mat3 R = matrix_from_rotation_vector(psi);
      CHECK(maxabs(Mat3(R - exp_so3(psi))) == 0.0);
      const Vec3 back = rotation_vector_from_matrix(R);
      if (th < pi) CHECK(w_rt((back - psi).norm() / std::max(1.0, th), where) <= 1e-15);
      CHECK(w_rr(maxabs(Mat3(matrix_from_rotation_vector(back) - R)), where) <= 1e-15);
      for (const Vec3& om : omegas) {
        const Vec3 rate = rotation_vector_rate(psi, om);
        CHECK(rate == dexpinv_body(psi, om));
        const Mat3 dR = (exp_so3(psi + h * rate) - exp_so3(psi - h * rate)) / (2.0 * h);
        CHECK(w_cd((vee(Mat3(R.transpose() * dR)) - om).norm(), where) <= 1e-8);
      }
    }
  }
}

TEST_CASE("Rotation vector chart: Ψ̇ = rotation_vector_rate(Ψ, Ω(t)) reproduces Ṙ = R Ω̂(t)", "[lie][charts][rotvec]") {
  const double T = 1.0;
  const int n = 1000;
  Worst w("|exp(Psi(T)) - R(T)|");
  for (const Vec3& psi0 : {Vec3(Vec3::Zero()), Vec3(0.3, -0.2, 0.1), Vec3(-1.0, 0.8, 1.5)}) {
    INFO("Psi0 = (" << psi0.transpose() << ")");
    const Vec3 psi = rk4<Vec3>([](double t, const Vec3& x) { return rotation_vector_rate(x, omega_of_t(t)); }, psi0,
                               T, n);
    const Mat3 r = lgi::testing::body_attitude_rk4(matrix_from_rotation_vector(psi0), T, n);
    CHECK(psi.norm() < 2.0 * pi - 0.5);  // stayed inside the chart
    CHECK(w(maxabs(Mat3(matrix_from_rotation_vector(psi) - r)), "") <= 1e-10);
  }
}

}  // namespace test_lie_charts
