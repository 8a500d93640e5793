// The model's analytic Jacobians (system/terms/, rigid_body.hpp) against
// central differences, for every torque term alone and for combined models:
//   ∂τ/∂η for R → R exp(η̂) (body side), dτ/dΠ with Ω = J⁻¹Π following,
//   and the momentum field K = Π × Ω + τ.
// Central differences with step δ have error O(δ²) + O(ε/δ); δ = 1e-5 puts
// both near 1e-10 relative, so agreement to 1e-8 relative is a clean pass
// and any wrong sign or missing term fails by orders of magnitude.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "experiments/io/scene_reader.hpp"
#include "integrators/system/model.hpp"
#include "integrators/system/terms/callable_torque.hpp"

namespace test_model_jacobian {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
using lie::Mat3;
using lie::Vec3;

namespace {

constexpr double fd_step = 1e-5;

/// Central difference of f(R exp(η̂)) in η at 0, column by column.
template <class F>
Mat3 fd_attitude(const Mat3& R, F&& f) {
  Mat3 out;
  for (int j = 0; j < 3; ++j) {
    const Vec3 e = fd_step * Vec3::Unit(j);
    out.col(j) = (f(Mat3(R * lie::exp_so3(e))) - f(Mat3(R * lie::exp_so3(-e)))) / (2.0 * fd_step);
  }
  return out;
}

/// Central difference of f(Π) in Π (the caller recomputes Ω = J⁻¹Π).
template <class F>
Mat3 fd_momentum(const Vec3& Pi, F&& f) {
  const double d = fd_step * std::max(1.0, Pi.norm());
  Mat3 out;
  for (int j = 0; j < 3; ++j) {
    const Vec3 e = d * Vec3::Unit(j);
    out.col(j) = (f(Vec3(Pi + e)) - f(Vec3(Pi - e))) / (2.0 * d);
  }
  return out;
}

/// |A − B| ≤ tol · max(1, |B|) (Frobenius), with a readable failure.
void check_close(const Mat3& analytic, const Mat3& numeric, const std::string& what, double tol = 1e-8) {
  const double err = (analytic - numeric).norm();
  const double scale = std::max(1.0, numeric.norm());
  INFO(what << ": |analytic − central difference| = " << err << ", scale " << scale << "\nanalytic\n"
            << analytic << "\ncentral difference\n"
            << numeric);
  CHECK(err <= tol * scale);
}

/// A general SPD inertia (not diagonal), so J⁻¹ couples the axes.
system::Inertia general_inertia() {
  Mat3 J;
  J << 2.0, 0.3, -0.1,  //
      0.3, 1.5, 0.2,    //
      -0.1, 0.2, 1.1;
  return system::make_inertia(J);
}

/// Attitudes and momenta that exercise every branch: generic, tiny
/// rotations (series branches), and near-π deflections for the spring.
struct Sample {
  Mat3 R;
  Vec3 Pi;
  double t;
};
std::vector<Sample> samples() {
  return {
      {lie::exp_so3(Vec3(0.3, -0.7, 0.5)), Vec3(0.4, -1.2, 2.0), 0.3},
      {lie::exp_so3(Vec3(1e-3, 2e-3, -1e-3)), Vec3(-3.0, 0.1, 0.7), 1.7},
      {lie::exp_so3(Vec3(1.0, 0.5, 0.0)), Vec3(0.0, 0.0, 15.0), 0.0},
      {lie::exp_so3(Vec3(-1.5, 2.0, 1.2)), Vec3(5.0, -4.0, 3.0), 12.5},  // |ξ| = 2.77
      {Mat3::Identity(), Vec3(1.0, 2.0, 3.0), 4.0},
  };
}

}  // namespace

TEST_CASE("gravity torque Jacobians match central differences", "[jacobian]") {
  const system::GravityTerm g(5.0, 9.81, Vec3(0.2, -0.3, 1.0));
  const system::Inertia in = general_inertia();
  for (const auto& x : samples()) {
    const Vec3 W = in.omega(x.Pi);
    check_close(g.torque_jacobian_attitude(x.R, x.Pi, W, x.t),
                fd_attitude(x.R, [&](const Mat3& R) { return g.torque(R, x.Pi, W, x.t); }), "gravity d/deta");
    check_close(g.torque_jacobian_momentum(x.R, x.Pi, W, x.t, in.J_inv),
                fd_momentum(x.Pi, [&](const Vec3& P) { return g.torque(x.R, P, in.omega(P), x.t); }),
                "gravity d/dPi");
  }
}

TEST_CASE("spring-damper torque Jacobians match central differences, exact dlog included", "[jacobian]") {
  const system::Inertia in = general_inertia();
  for (const Mat3& rest : {Mat3(Mat3::Identity()), Mat3(lie::exp_so3(Vec3(0.2, 0.1, -0.4)))}) {
    const system::SpringTerm sp(100.0, 7.0, rest);
    for (const auto& x : samples()) {
      const Vec3 W = in.omega(x.Pi);
      INFO("deflection |xi| = " << sp.deflection(x.R).norm());
      check_close(sp.torque_jacobian_attitude(x.R, x.Pi, W, x.t),
                  fd_attitude(x.R, [&](const Mat3& R) { return sp.torque(R, x.Pi, W, x.t); }), "spring d/deta");
      check_close(sp.torque_jacobian_momentum(x.R, x.Pi, W, x.t, in.J_inv),
                  fd_momentum(x.Pi, [&](const Vec3& P) { return sp.torque(x.R, P, in.omega(P), x.t); }),
                  "damper d/dPi");
    }
  }
  SECTION("the trivialisation matters: the space-side dlog fails the same check") {
    const system::SpringTerm sp(100.0, 0.0, Mat3::Identity());
    const Mat3 R = lie::exp_so3(Vec3(0.3, -0.7, 0.5));
    const Mat3 wrong = -100.0 * lie::dexpinv_space_matrix(sp.deflection(R));
    const Mat3 fd = fd_attitude(R, [&](const Mat3& Rp) { return sp.torque(Rp, Vec3::Zero(), Vec3::Zero(), 0.0); });
    CHECK((wrong - fd).norm() > 1.0);
  }
}

TEST_CASE("drive and generic time-dependent torque Jacobians match central differences", "[jacobian]") {
  const system::Inertia in = general_inertia();
  system::HarmonicDriveTerm drive;
  drive.amplitude = Vec3(0.3, -0.2, 0.1);
  drive.angular_frequency = 2.0;
  drive.phase = 0.3;
  // A callable that depends on R, Π and Ω at once, so the fallback is exercised in full.
  const system::CallableTorque custom{[](double t, const Mat3& R, const Vec3& Pi, const Vec3& W) -> Vec3 {
    return std::cos(t) * R.row(2).transpose().cross(Vec3(0.1, 0.2, 0.3)) - 0.5 * W + 0.01 * Pi.squaredNorm() * Pi;
  }};
  for (const auto& x : samples()) {
    const Vec3 W = in.omega(x.Pi);
    check_close(drive.torque_jacobian_attitude(x.R, x.Pi, W, x.t),
                fd_attitude(x.R, [&](const Mat3& R) { return drive.torque(R, x.Pi, W, x.t); }), "drive d/deta");
    check_close(drive.torque_jacobian_momentum(x.R, x.Pi, W, x.t, in.J_inv),
                fd_momentum(x.Pi, [&](const Vec3& P) { return drive.torque(x.R, P, in.omega(P), x.t); }),
                "drive d/dPi");
    check_close(custom.torque_jacobian_attitude(x.R, x.Pi, W, x.t),
                fd_attitude(x.R, [&](const Mat3& R) { return custom.torque(R, x.Pi, W, x.t); }), "custom d/deta",
                1e-6);
    check_close(custom.torque_jacobian_momentum(x.R, x.Pi, W, x.t, in.J_inv),
                fd_momentum(x.Pi, [&](const Vec3& P) { return custom.torque(x.R, P, in.omega(P), x.t); }),
                "custom d/dPi", 1e-6);
  }
}

namespace {

template <class Model>
void check_model(const Model& model, const std::string& name) {
  for (const auto& x : samples()) {
    const Vec3 W = model.omega(x.Pi);
    const auto jac = model.momentum_rate_jacobian(x.R, x.Pi, W, x.t);
    check_close(jac.attitude,
                fd_attitude(x.R, [&](const Mat3& R) { return model.momentum_rate(R, x.Pi, W, x.t); }),
                name + ": dK/deta");
    check_close(jac.momentum,
                fd_momentum(x.Pi, [&](const Vec3& P) { return model.momentum_rate(x.R, P, model.omega(P), x.t); }),
                name + ": dK/dPi");
    check_close(model.torque_jacobian_attitude(x.R, x.Pi, W, x.t),
                fd_attitude(x.R, [&](const Mat3& R) { return model.torque(R, x.Pi, W, x.t); }), name + ": dtau/deta");
    check_close(model.torque_jacobian_momentum(x.R, x.Pi, W, x.t),
                fd_momentum(x.Pi, [&](const Vec3& P) { return model.torque(x.R, P, model.omega(P), x.t); }),
                name + ": dtau/dPi");
    check_close(model.omega_jacobian(), fd_momentum(x.Pi, [&](const Vec3& P) { return model.omega(P); }),
                name + ": dOmega/dPi");
  }
}

}  // namespace

TEST_CASE("momentum-field Jacobians of combined models match central differences", "[jacobian]") {
  const system::Inertia in = general_inertia();
  const system::GravityTerm g(2.0, 9.81, Vec3(0.1, 0.4, -0.8));
  const system::SpringTerm sp(40.0, 3.0, lie::exp_so3(Vec3(-0.1, 0.3, 0.2)));
  system::HarmonicDriveTerm drive;
  drive.amplitude = Vec3(1.0, -2.0, 0.5);
  drive.angular_frequency = 3.0;
  check_model(system::FreeBody{in, {}}, "free body");
  check_model(system::HeavyTop{in, {g}}, "heavy top");
  check_model(system::RigidBody<system::SpringTerm>{in, {sp}}, "spring body");
  check_model(system::RigidBody<system::GravityTerm, system::SpringTerm>{in, {g, sp}}, "heavy top + spring");
  check_model(system::RigidBody<system::GravityTerm, system::SpringTerm, system::HarmonicDriveTerm>{in, {g, sp, drive}}, "driven heavy top + spring");
}

TEST_CASE("momentum-field Jacobians of every shipped scene match central differences", "[jacobian]") {
  for (const char* name : {"free_body_hlw", "heavy_top_trindade_1", "kovalevskaya", "general_top_richter",
                           "stiff_damped_spring", "gyroscope"}) {
    const system::Scene scene = experiments::read_scene(std::string(LGI_SCENES_DIR) + "/" + name + ".toml");
    std::visit([&](const auto& model) { check_model(model, name); }, system::make_model(scene));
  }
}

}  // namespace test_model_jacobian
