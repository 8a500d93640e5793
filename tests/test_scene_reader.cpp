// Scene files (experiments/io/scene_reader.hpp, experiments/scenes/README.md)
// that are valid: every shipped scene parses with the values its README table
// gives, and the accepted spellings (integers for floats, quaternion, matrix,
// rotation vector, inertia tensor, optional [run] keys) read as intended.
// Bad input: test_scene_reader_errors.cpp (one table of bad scenes).
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <set>
#include <string>

#include "experiments/io/gamma_attitude.hpp"
#include "experiments/io/scene_reader.hpp"
#include "lie/charts.hpp"
#include "lie/quaternion.hpp"
#include "lie/so3.hpp"

#include "support/near.hpp"
#include "support/scene_error.hpp"
#include "support/valid_scene.hpp"

namespace test_scene_reader {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using lgi::experiments::parse_scene;
using lgi::experiments::read_scene;
using lgi::lie::Mat3;
using lgi::lie::Vec3;
using Catch::Matchers::StartsWith;
using lgi::testing::error_of;
using lgi::testing::near;
using lgi::testing::valid_top;

namespace {

const std::string scenes_dir = LGI_SCENES_DIR;

}  // namespace

// ---------------------------------------------------------------------------
// Shipped scenes

TEST_CASE("every shipped scene parses", "[scene]") {
  const std::set<std::string> expected = {
      "dzhanibekov_book_axis1.toml", "dzhanibekov_book_axis2.toml",     "dzhanibekov_book_axis3.toml",
      "prism_edurev.toml",           "gyroscope.toml",                  "heavy_top_trindade_1.toml",
      "heavy_top_trindade_2.toml",   "heavy_top_trindade_3.toml",       "heavy_top_trindade_4.toml",
      "heavy_top_trindade_singular.toml", "free_body_hlw.toml",         "kovalevskaya.toml", "magnetic_top.toml",
      "general_top_richter.toml",    "lagrange_top_cigar.toml",         "lagrange_top_oblate.toml",
      "lagrange_top_disk.toml",    "stiff_damped_spring.toml",
      "heavy_top_hlw.toml",          "cardan_trindade_1_massless.toml", "cardan_lagrange_upright.toml",
      "cardan_lagrange_horizontal.toml", "cardan_euler_symmetric_up.toml", "cardan_euler_tilted.toml",
      "cardan_general_asymmetric_up.toml", "cardan_general_horizontal.toml"};
  std::set<std::string> found;
  for (const auto& entry : std::filesystem::directory_iterator(scenes_dir)) {
    if (entry.path().extension() != ".toml") continue;
    found.insert(entry.path().filename().string());
    INFO(entry.path().string());
    const auto s = read_scene(entry.path().string());
    CHECK(!s.name.empty());
    CHECK(s.file == entry.path().string());
    CHECK(!s.toml_text.empty());
    CHECK(s.t_end > 0.0);
    REQUIRE(s.dt);
    CHECK(*s.dt > 0.0);
    REQUIRE(s.tol);
    CHECK(*s.tol == 1e-8);
    CHECK(lgi::lie::orthogonality_error(s.initial.R) < 1e-15);
    CHECK(s.initial.R.determinant() == Approx(1.0));
    CHECK((s.inertia - s.inertia.transpose()).norm() == 0.0);
  }
  CHECK(found == expected);
}

TEST_CASE("shipped scene: heavy_top_trindade_1 (parallel axis, Euler rates)", "[scene]") {
  const auto s = read_scene(scenes_dir + "/heavy_top_trindade_1.toml");
  CHECK(s.name == "Heavy top, Trindade & Sampaio (2001) case 1");
  CHECK(near(s.inertia, Vec3(5.8, 5.8, 1.0).asDiagonal().toDenseMatrix(), 1e-15));
  REQUIRE(s.mass);
  CHECK(*s.mass == 5.0);
  REQUIRE(s.center_of_mass);
  CHECK(*s.center_of_mass == Vec3(0, 0, 1));
  REQUIRE(s.declared<lgi::system::GravityTerm>());
  CHECK(s.declared<lgi::system::GravityTerm>()->g == 9.81);
  CHECK(!s.declared<lgi::system::SpringTerm>());
  CHECK(!s.declared<lgi::system::HarmonicDriveTerm>());
  CHECK(!s.is_free_body());
  CHECK(near(s.initial.R, lgi::lie::rot_x(0.3490658503988659), 0.0));
  CHECK(near(s.initial.Pi, Vec3(0, 0, 50), 1e-14));  // Ω = (0, 0, φ̇), J3 = 1
  CHECK(s.t_end == 10.0);
  CHECK(*s.dt == 1e-3);
}

TEST_CASE("shipped scene: heavy_top_trindade_2 (Π0 from Euler rates)", "[scene]") {
  const auto s = read_scene(scenes_dir + "/heavy_top_trindade_2.toml");
  const double th = 0.3490658503988659;
  // Ω = (ψ̇ sinθ sinφ + θ̇ cosφ, ψ̇ sinθ cosφ − θ̇ sinφ, ψ̇ cosθ + φ̇) with ψ̇ = −10, θ̇ = 0, φ̇ = 50, φ = 0.
  const Vec3 Omega(0.0, -10.0 * std::sin(th), -10.0 * std::cos(th) + 50.0);
  CHECK(near(s.initial.Pi, Vec3(5.8 * Omega.x(), 5.8 * Omega.y(), Omega.z()), 1e-13));
  const auto s3 = read_scene(scenes_dir + "/heavy_top_trindade_3.toml");
  CHECK(near(s3.initial.Pi, Vec3(0.0, 5.8 * std::sin(th), std::cos(th) + 50.0), 1e-13));
  const auto s4 = read_scene(scenes_dir + "/heavy_top_trindade_4.toml");
  CHECK(near(s4.initial.Pi, Vec3(0, 0, 0.01), 1e-16));
  const auto sing = read_scene(scenes_dir + "/heavy_top_trindade_singular.toml");
  // θ̇ = 0.5 at φ = 0 gives Ω1 = 0.5; φ̇ = 0.01 gives Ω3 = 0.01.
  CHECK(near(sing.initial.Pi, Vec3(5.8 * 0.5, 0.0, 0.01), 1e-14));
  CHECK(sing.t_end == 50.0);
  CHECK(near(sing.initial.R, lgi::lie::rot_x(3.14), 0.0));
}

TEST_CASE("shipped scene: gyroscope in steady precession", "[scene]") {
  const auto s = read_scene(scenes_dir + "/gyroscope.toml");
  // J about the pivot: 0.0025 + 1 · 0.15² = 0.025 transverse, 0.005 axial.
  CHECK(near(s.inertia, Vec3(0.025, 0.025, 0.005).asDiagonal().toDenseMatrix(), 1e-15));
  const double Omega_p = 1.0 * 9.81 * 0.15 / (0.005 * 200.0);
  CHECK(Omega_p == 1.4715);
  CHECK(near(s.initial.Pi, Vec3(0.0, 0.025 * Omega_p, 0.005 * 200.0), 1e-14));
  // The axle (body e3) starts horizontal.
  CHECK(std::abs(s.initial.R(2, 2)) < 1e-15);
  CHECK(s.t_end == 20.0);
}

TEST_CASE("shipped scene: free bodies, Kovalevskaya, Richter, spring", "[scene]") {
  const auto book = read_scene(scenes_dir + "/dzhanibekov_book_axis2.toml");
  CHECK(book.is_free_body());
  CHECK(book.inertia == Vec3(0.01203, 0.0074, 0.0048).asDiagonal().toDenseMatrix());
  CHECK(near(book.initial.Pi, Vec3(0.01203 * 0.01, 0.0074 * 10.0, 0.0048 * 0.01), 1e-17));
  CHECK(book.initial.R == Mat3::Identity());
  CHECK(book.t_end == 14.0);

  const auto prism = read_scene(scenes_dir + "/prism_edurev.toml");
  CHECK(prism.inertia == Vec3(5, 20, 17).asDiagonal().toDenseMatrix());
  CHECK(near(prism.initial.Pi, Vec3(0.0, 0.2, 17.0), 1e-15));
  CHECK(prism.t_end == 20.0);

  const auto hlw = read_scene(scenes_dir + "/free_body_hlw.toml");
  CHECK(hlw.allow_unphysical);
  CHECK(hlw.is_free_body());
  CHECK(hlw.inertia(2, 2) == 0.6666666666666666);
  CHECK(near(hlw.initial.Pi, Vec3(std::cos(1.1), 0.0, std::sin(1.1)), 1e-16));
  CHECK(hlw.t_end == 100.0);

  const auto kov = read_scene(scenes_dir + "/kovalevskaya.toml");
  CHECK(kov.inertia == Vec3(2, 2, 1).asDiagonal().toDenseMatrix());
  CHECK(*kov.center_of_mass == Vec3(1, 0, 0));
  CHECK(kov.declared<lgi::system::GravityTerm>()->g == 1.0);
  CHECK(near(kov.initial.R, lgi::lie::exp_so3(Vec3(0.3, 0.2, 0.0)), 0.0));
  CHECK(kov.initial.Pi == Vec3(1.0, 0.6, 1.2));

  const auto richter = read_scene(scenes_dir + "/general_top_richter.toml");
  CHECK(richter.inertia == Vec3(1, 1.5, 2).asDiagonal().toDenseMatrix());
  CHECK(*richter.center_of_mass == Vec3(0.8, 0.4, 0.3));
  CHECK(richter.initial.Pi == Vec3(1.0, 0.75, 1.0));

  const auto spring = read_scene(scenes_dir + "/stiff_damped_spring.toml");
  REQUIRE(spring.declared<lgi::system::SpringTerm>());
  CHECK(spring.declared<lgi::system::SpringTerm>()->stiffness == 100.0);
  CHECK(spring.declared<lgi::system::SpringTerm>()->damping == 1000.0);
  CHECK(spring.declared<lgi::system::SpringTerm>()->rest == Mat3::Identity());
  CHECK(!spring.declared<lgi::system::GravityTerm>());
  CHECK(spring.initial.Pi == Vec3(0.0, 0.0, 15.0));
  CHECK(spring.t_end == 50.0);
}

// ---------------------------------------------------------------------------
// Valid inline scenes: the other keys

TEST_CASE("scene: integers are accepted where floats are expected", "[scene]") {
  const auto s = parse_scene(valid_top, "test.toml");
  CHECK(s.name == "top");
  CHECK(s.file == "test.toml");
  CHECK(s.toml_text == valid_top);
  CHECK(*s.mass == 5.0);
  CHECK(s.t_end == 10.0);
  CHECK(!s.tol);
}

TEST_CASE("scene: quaternion, matrix, rotation vector, inertia tensor, drive, spring", "[scene]") {
  const auto s = parse_scene(R"(name = "all keys"
description = "every optional table"
[body]
inertia_tensor = [[2, 0.1, 0], [0.1, 3, 0], [0, 0, 4]]
[spring]
stiffness = 2
damping = 0
rest_quaternion = [0.7071067811865476, 0, 0, 0.7071067811865476]
[drive]
torque_amplitude = [0, 0, 1.5]
angular_frequency = 3
[initial]
quaternion = [0.5, 0.5, 0.5, 0.5000000000001]
angular_momentum = [1, 2, 3]
[run]
t_end = 0
tol = 1e-6
)",
                            "test.toml");
  CHECK(s.description == "every optional table");
  Mat3 J;
  J << 2, 0.1, 0, 0.1, 3, 0, 0, 0, 4;
  CHECK(s.inertia == J);
  REQUIRE(s.declared<lgi::system::HarmonicDriveTerm>());
  CHECK(s.declared<lgi::system::HarmonicDriveTerm>()->torque_amplitude == Vec3(0, 0, 1.5));
  CHECK(s.declared<lgi::system::HarmonicDriveTerm>()->angular_frequency == 3.0);
  CHECK(s.declared<lgi::system::HarmonicDriveTerm>()->phase == 0.0);
  REQUIRE(s.declared<lgi::system::SpringTerm>());
  CHECK(near(s.declared<lgi::system::SpringTerm>()->rest, lgi::lie::rot_z(std::numbers::pi / 2), 1e-15));
  // The quaternion within 1e-12 of unit norm is normalised: R is orthogonal.
  CHECK(lgi::lie::orthogonality_error(s.initial.R) < 1e-15);
  Mat3 cyclic;  // (0.5, 0.5, 0.5, 0.5): rotation by 2π/3 about (1,1,1), e1 → e2 → e3
  cyclic << 0, 0, 1, 1, 0, 0, 0, 1, 0;
  CHECK(near(s.initial.R, cyclic, 1e-12));
  CHECK(s.initial.Pi == Vec3(1, 2, 3));
  CHECK(s.t_end == 0.0);
  CHECK(!s.dt);
  CHECK(*s.tol == 1e-6);
  CHECK(!s.declared<lgi::system::GravityTerm>());

}

TEST_CASE("scene: [initial] gamma sets the attitude as the sweep specs' initial.gamma", "[scene]") {
  const auto text = [](const std::string& gamma) {
    return "name = \"g\"\n[body]\ninertia = [1, 1.5, 2]\n[initial]\ngamma = " + gamma +
           "\nangular_momentum = [0.3, -0.2, 1.1]\n";
  };
  const Vec3 g = Vec3(0.48, -0.6, 0.64);  // a unit vector
  const auto s = parse_scene(text("[0.48, -0.6, 0.64]"), "test.toml");
  CHECK(near(Vec3(s.initial.R.transpose() * Vec3::UnitZ()), g, 1e-15));
  // ψ = 0: R = Rx(θ) Rz(φ) with γ = (sinθ sinφ, sinθ cosφ, cosθ), the rule of experiments/SWEEPS.md.
  CHECK(near(s.initial.R, lgi::experiments::attitude_from_gamma(g), 0.0));
  CHECK(near(s.initial.R, Mat3(lgi::lie::rot_x(std::acos(0.64)) * lgi::lie::rot_z(std::atan2(0.48, -0.6))), 1e-15));
  CHECK(lgi::lie::orthogonality_error(s.initial.R) < 1e-15);
  CHECK(s.initial.Pi == Vec3(0.3, -0.2, 1.1));
  // Not a unit vector: normalised (a note goes to stderr), the same attitude.
  const auto twice = parse_scene(text("[0.96, -1.2, 1.28]"), "test.toml");
  CHECK(near(twice.initial.R, s.initial.R, 1e-15));
  // The vertical itself and its opposite.
  CHECK(near(parse_scene(text("[0, 0, 1]"), "test.toml").initial.R, Mat3::Identity(), 1e-15));
  CHECK(near(Vec3(parse_scene(text("[0, 0, -2]"), "test.toml").initial.R.transpose() * Vec3::UnitZ()),
             Vec3(0, 0, -1), 1e-15));
}

TEST_CASE("every [run] key is optional: the command line gives what a scene lacks", "[scene]") {
  const auto only_dt = lgi::experiments::parse_scene("name = \"t\"\n[body]\ninertia = [1, 1, 1]\n[run]\ndt = 0.1\n", "test.toml");
  CHECK_FALSE(only_dt.t_end.has_value());
  CHECK(only_dt.dt == 0.1);
  const auto no_run = lgi::experiments::parse_scene("name = \"t\"\n[body]\ninertia = [1, 1, 1]\n", "test.toml");
  CHECK_FALSE(no_run.t_end.has_value());
  CHECK_FALSE(no_run.dt.has_value());
  CHECK_THAT(error_of("name = \"t\"\n[body]\ninertia = [1, 1, 1]\n[run]\nt_end = -1\n"),
             StartsWith("test.toml:5: [run] t_end: must be >= 0"));
}

// Valid scenes just inside the rules of test_scene_reader_errors.cpp.
TEST_CASE("scene: accepted at the limits of the bad-input rules", "[scene]") {
  const auto read = [](const std::string& body) {
    return parse_scene("name = \"t\"\n[body]\n" + body + "[run]\nt_end = 1\n", "test.toml");
  };
  // the triangle inequality broken when asked for; equality (a plane body) is physical
  CHECK(read("inertia = [2, 1, 0.6666666666666666]\nallow_unphysical = true\n").allow_unphysical);
  CHECK_NOTHROW(read("inertia = [1, 2, 3]\n"));
  // the rule applies to the final J about the reference point: J_c = (2, 1, 0.6)
  // violates it, but J = J_c + m(|χ|²I − χχᵀ) = diag(2, 2, 1.6) with χ = e1 does not
  const auto pa = read("mass = 1\ninertia_cm = [2, 1, 0.6]\ncenter_of_mass = [1, 0, 0]\n");
  CHECK(near(pa.inertia, Vec3(2, 2, 1.6).asDiagonal().toDenseMatrix(), 1e-15));
  // a tensor symmetric within 1e-12 relative: accepted and symmetrised
  const auto sym = read("inertia_tensor = [[2, 0.1, 0], [0.100000000000001, 3, 0], [0, 0, 4]]\n");
  CHECK(sym.inertia(0, 1) == sym.inertia(1, 0));
  // a quaternion 5e-13 off unit norm is normalised
  const auto q = read("inertia = [1, 1, 1]\n[initial]\nquaternion = [1.0000000000005, 0, 0, 0]\n");
  CHECK(q.initial.R == Mat3::Identity());
  // a proper rotation is accepted as given
  const auto r = read("inertia = [1, 1, 1]\n[initial]\nmatrix = [[0, -1, 0], [1, 0, 0], [0, 0, 1]]\n");
  Mat3 Rz90;
  Rz90 << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  CHECK(r.initial.R == Rz90);
}

}  // namespace test_scene_reader
