// Scene files (experiments/io/scene_reader.hpp, experiments/scenes/README.md):
// every shipped scene parses with the values its README table gives, and every
// bad-input rule throws InputError with one line
//   <file>:<line>: [table] key: what is wrong
// naming the file, the key and (where one applies) the line.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <set>
#include <string>

#include "experiments/errors/input_error.hpp"
#include "experiments/io/scene_reader.hpp"
#include "lie/charts.hpp"
#include "lie/quaternion.hpp"
#include "lie/so3.hpp"

using lgi::experiments::InputError;
using lgi::experiments::parse_scene;
using lgi::experiments::read_scene;
using lgi::lie::Mat3;
using lgi::lie::Vec3;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

const std::string scenes_dir = LGI_SCENES_DIR;

/// The message parse_scene throws for `text` (read as "test.toml"); fails the
/// test if it accepts the text or throws anything else.
std::string error_of(const std::string& text) {
  try {
    (void)parse_scene(text, "test.toml");
  } catch (const InputError& e) {
    const std::string m = e.what();
    CHECK(m.find('\n') == std::string::npos);  // one line
    CHECK_THAT(m, StartsWith("test.toml"));     // names the file
    return m;
  }
  FAIL("parse_scene accepted bad input:\n" << text);
  return {};
}

bool near(const Mat3& a, const Mat3& b, double tol) { return (a - b).cwiseAbs().maxCoeff() <= tol; }
bool near(const Vec3& a, const Vec3& b, double tol) { return (a - b).cwiseAbs().maxCoeff() <= tol; }

// A valid scene used as the base for several bad-input tests; line numbers:
//  1 name, 2 [body], 3 mass, 4 inertia, 5 center_of_mass, 6 [gravity],
//  7 g, 8 [initial], 9 euler_zxz, 10 euler_zxz_rates, 11 [run], 12 t_end,
//  13 dt.
const std::string valid_top = R"(name = "top"
[body]
mass = 5
inertia = [5.8, 5.8, 1]
center_of_mass = [0, 0, 1]
[gravity]
g = 9.81
[initial]
euler_zxz = [0, 0.3490658503988659, 0]
euler_zxz_rates = [0, 0, 50]
[run]
t_end = 10
dt = 1e-3
)";

}  // namespace

// ---------------------------------------------------------------------------
// Shipped scenes

TEST_CASE("every shipped scene parses", "[scene]") {
  const std::set<std::string> expected = {
      "dzhanibekov_book_axis1.toml", "dzhanibekov_book_axis2.toml",     "dzhanibekov_book_axis3.toml",
      "prism_edurev.toml",           "gyroscope.toml",                  "heavy_top_trindade_1.toml",
      "heavy_top_trindade_2.toml",   "heavy_top_trindade_3.toml",       "heavy_top_trindade_4.toml",
      "heavy_top_trindade_singular.toml", "free_body_hlw.toml",         "kovalevskaya.toml", "magnetic_top.toml",
      "general_top_richter.toml",    "stiff_damped_spring.toml"};
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

// ---------------------------------------------------------------------------
// Bad input: one test per rule

TEST_CASE("bad input: missing name", "[scene][bad]") {
  const auto m = error_of(R"([body]
inertia = [1, 1, 1]
[run]
t_end = 1
)");
  CHECK_THAT(m, StartsWith("test.toml: name: missing"));
}

TEST_CASE("bad input: name must be a one-line string", "[scene][bad]") {
  CHECK_THAT(error_of("name = 3\n[body]\ninertia = [1, 1, 1]\n[run]\nt_end = 1\n"),
             StartsWith("test.toml:1: name: expected a string, got an integer"));
  CHECK_THAT(error_of("name = \"\"\"two\nlines\"\"\"\n[body]\ninertia = [1, 1, 1]\n[run]\nt_end = 1\n"),
             StartsWith("test.toml:1: name: must be one line"));
}

TEST_CASE("bad input: missing inertia key", "[scene][bad]") {
  const auto m = error_of(R"(name = "t"
[body]
mass = 1
[run]
t_end = 1
)");
  CHECK_THAT(m, StartsWith("test.toml:2: [body] inertia: missing"));
  CHECK_THAT(m, Contains("inertia_cm") && Contains("inertia_tensor"));
  CHECK_THAT(error_of("name = \"t\"\n[run]\nt_end = 1\n"), StartsWith("test.toml: [body] inertia: missing"));
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

TEST_CASE("bad input: two attitude keys", "[scene][bad]") {
  const auto m = error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
[initial]
quaternion = [1, 0, 0, 0]
euler_zxz = [0, 0, 0]
[run]
t_end = 1
)");
  CHECK_THAT(m, StartsWith("test.toml:6: [initial] euler_zxz: conflicts with quaternion (line 5)"));
}

TEST_CASE("bad input: two motion keys", "[scene][bad]") {
  const auto m = error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
[initial]
angular_momentum = [1, 0, 0]
angular_velocity = [1, 0, 0]
[run]
t_end = 1
)");
  CHECK_THAT(m, StartsWith("test.toml:6: [initial] angular_velocity: conflicts with angular_momentum (line 5)"));
}

TEST_CASE("bad input: two inertia keys", "[scene][bad]") {
  const auto m = error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
inertia_tensor = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
[run]
t_end = 1
)");
  CHECK_THAT(m, StartsWith("test.toml:4: [body] inertia_tensor: conflicts with inertia (line 3)"));
}

TEST_CASE("bad input: wrong type", "[scene][bad]") {
  CHECK_THAT(error_of(R"(name = "t"
[body]
mass = "five"
inertia = [1, 1, 1]
[run]
t_end = 1
)"),
             StartsWith("test.toml:3: [body] mass: expected a number, got a string"));
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, true]
[run]
t_end = 1
)"),
             StartsWith("test.toml:3: [body] inertia: element 3: expected a number, got a boolean"));
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
allow_unphysical = "yes"
[run]
t_end = 1
)"),
             StartsWith("test.toml:4: [body] allow_unphysical: expected true or false, got a string"));
  CHECK_THAT(error_of(R"(name = "t"
gravity = 9.81
[body]
inertia = [1, 1, 1]
[run]
t_end = 1
)"),
             StartsWith("test.toml:2: [gravity]: expected a table, got a float"));
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = 1
[run]
t_end = 1
)"),
             StartsWith("test.toml:3: [body] inertia: expected 3 numbers, got an integer"));
}

TEST_CASE("bad input: wrong length", "[scene][bad]") {
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1]
[run]
t_end = 1
)"),
             StartsWith("test.toml:3: [body] inertia: expected 3 numbers, got 2"));
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
[initial]
quaternion = [1, 0, 0]
[run]
t_end = 1
)"),
             StartsWith("test.toml:5: [initial] quaternion: expected 4 numbers, got 3"));
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
[initial]
matrix = [[1, 0, 0],
          [0, 1],
          [0, 0, 1]]
[run]
t_end = 1
)"),
             StartsWith("test.toml:6: [initial] matrix: row 2: expected 3 numbers, got 2"));
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
[initial]
matrix = [[1, 0, 0], [0, 1, 0]]
[run]
t_end = 1
)"),
             StartsWith("test.toml:5: [initial] matrix: expected 3 rows of 3 numbers, got 2 rows"));
}

TEST_CASE("bad input: unknown key (a typo is not ignored)", "[scene][bad]") {
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
centre_of_mass = [0, 0, 1]
[run]
t_end = 1
)"),
             StartsWith("test.toml:4: [body] centre_of_mass: unknown key"));
  CHECK_THAT(error_of(R"(name = "t"
nmae = "typo"
[body]
inertia = [1, 1, 1]
[run]
t_end = 1
)"),
             StartsWith("test.toml:2: nmae: unknown key"));
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
[initial]
matrix = [[0, -1, 0], [1, 0, 0], [0, 0, 1]]
rotation_vector_is_not_here = 0
[run]
t_end = 1
)"),
             StartsWith("test.toml:6: [initial] rotation_vector_is_not_here: unknown key"));
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
[run]
t_end = 1
dt = 0.1
t_end2 = 2
)"),
             StartsWith("test.toml:7: [run] t_end2: unknown key"));
}

TEST_CASE("bad input: unknown table", "[scene][bad]") {
  const auto m = error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
mass = 1
center_of_mass = [0, 0, 1]
[gravty]
g = 9.81
[run]
t_end = 1
)");
  CHECK_THAT(m, StartsWith("test.toml:6: [gravty]: unknown table"));
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
[body.extra]
x = 1
[run]
t_end = 1
)"),
             StartsWith("test.toml:4: [body] extra: unknown key"));
}

TEST_CASE("bad input: NaN or infinite numbers", "[scene][bad]") {
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, nan, 1]
[run]
t_end = 1
)"),
             StartsWith("test.toml:3: [body] inertia: element 2: expected a finite number, got nan"));
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
[run]
t_end = inf
)"),
             StartsWith("test.toml:5: [run] t_end: expected a finite number, got inf"));
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
[initial]
angular_velocity = [0, -inf, 0]
[run]
t_end = 1
)"),
             StartsWith("test.toml:5: [initial] angular_velocity: element 2: expected a finite number, got -inf"));
}

TEST_CASE("bad input: non-positive mass", "[scene][bad]") {
  CHECK_THAT(error_of(R"(name = "t"
[body]
mass = 0
inertia = [1, 1, 1]
[run]
t_end = 1
)"),
             StartsWith("test.toml:3: [body] mass: must be > 0, got 0"));
  CHECK_THAT(error_of(R"(name = "t"
[body]
mass = -2.5
inertia = [1, 1, 1]
[run]
t_end = 1
)"),
             StartsWith("test.toml:3: [body] mass: must be > 0, got -2.5"));
}

TEST_CASE("bad input: non-positive moment", "[scene][bad]") {
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 0, 1]
[run]
t_end = 1
)"),
             StartsWith("test.toml:3: [body] inertia: moment 2 must be > 0, got 0"));
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia_cm = [1, 1, -1]
[run]
t_end = 1
)"),
             StartsWith("test.toml:3: [body] inertia_cm: moment 3 must be > 0, got -1"));
}

TEST_CASE("bad input: triangle inequality, unless allow_unphysical", "[scene][bad]") {
  const std::string hlw = R"(name = "t"
[body]
inertia = [2, 1, 0.6666666666666666]
[run]
t_end = 1
)";
  const auto m = error_of(hlw);
  CHECK_THAT(m, StartsWith("test.toml:3: [body] inertia: principal moments"));
  CHECK_THAT(m, Contains("triangle inequality") && Contains("allow_unphysical"));
  // allowed when asked for
  const auto s = parse_scene(R"(name = "t"
[body]
inertia = [2, 1, 0.6666666666666666]
allow_unphysical = true
[run]
t_end = 1
)",
                             "test.toml");
  CHECK(s.allow_unphysical);
  // a general tensor: its principal moments (eigenvalues 1, 1, 3) are checked
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia_tensor = [[2, 1, 0], [1, 2, 0], [0, 0, 1]]
[run]
t_end = 1
)"),
             StartsWith("test.toml:3: [body] inertia_tensor: principal moments"));
  // equality (a plane body) is physical
  CHECK_NOTHROW(parse_scene("name = \"t\"\n[body]\ninertia = [1, 2, 3]\n[run]\nt_end = 1\n", "test.toml"));
  // the rule applies to the final J about the reference point: J_c = (2, 1, 0.6)
  // violates it, but J = J_c + m(|χ|²I − χχᵀ) = diag(2, 2, 1.6) with χ = e1 does not
  const auto pa = parse_scene(R"(name = "t"
[body]
mass = 1
inertia_cm = [2, 1, 0.6]
center_of_mass = [1, 0, 0]
[run]
t_end = 1
)",
                              "test.toml");
  CHECK(near(pa.inertia, Vec3(2, 2, 1.6).asDiagonal().toDenseMatrix(), 1e-15));
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia_cm = [2, 1, 0.6]
[run]
t_end = 1
)"),
             StartsWith("test.toml:3: [body] inertia_cm: principal moments"));
}

TEST_CASE("bad input: inertia tensor not symmetric", "[scene][bad]") {
  const auto m = error_of(R"(name = "t"
[body]
inertia_tensor = [[2, 0.1, 0],
                  [0.1000001, 3, 0],
                  [0, 0, 4]]
[run]
t_end = 1
)");
  CHECK_THAT(m, StartsWith("test.toml:3: [body] inertia_tensor: not symmetric"));
  // within 1e-12 relative: accepted and symmetrised
  const auto s = parse_scene(R"(name = "t"
[body]
inertia_tensor = [[2, 0.1, 0], [0.100000000000001, 3, 0], [0, 0, 4]]
[run]
t_end = 1
)",
                             "test.toml");
  CHECK(s.inertia(0, 1) == s.inertia(1, 0));
}

TEST_CASE("bad input: inertia tensor not positive definite", "[scene][bad]") {
  const auto m = error_of(R"(name = "t"
[body]
allow_unphysical = true
inertia_tensor = [[1, 2, 0], [2, 1, 0], [0, 0, 1]]
[run]
t_end = 1
)");
  CHECK_THAT(m, StartsWith("test.toml:4: [body] inertia_tensor: not positive definite"));
}

TEST_CASE("bad input: [gravity] without mass", "[scene][bad]") {
  const auto m = error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
center_of_mass = [0, 0, 1]
[gravity]
g = 9.81
[run]
t_end = 1
)");
  CHECK_THAT(m, StartsWith("test.toml:5: [body] mass: missing"));
  CHECK_THAT(m, Contains("[gravity]"));
}

TEST_CASE("bad input: [gravity] without center_of_mass", "[scene][bad]") {
  const auto m = error_of(R"(name = "t"
[body]
mass = 1
inertia = [1, 1, 1]
[gravity]
g = 9.81
[run]
t_end = 1
)");
  CHECK_THAT(m, StartsWith("test.toml:5: [body] center_of_mass: missing"));
  CHECK_THAT(m, Contains("[gravity]"));
}

TEST_CASE("bad input: negative gravity magnitude", "[scene][bad]") {
  CHECK_THAT(error_of(R"(name = "t"
[body]
mass = 1
inertia = [1, 1, 1]
center_of_mass = [0, 0, 1]
[gravity]
g = -9.81
[run]
t_end = 1
)"),
             StartsWith("test.toml:7: [gravity] g: must be >= 0"));
}

TEST_CASE("bad input: inertia_cm with center_of_mass but no mass", "[scene][bad]") {
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia_cm = [1, 1, 1]
center_of_mass = [0, 0, 1]
[run]
t_end = 1
)"),
             StartsWith("test.toml:3: [body] mass: missing") && Contains("parallel-axis"));
}

TEST_CASE("bad input: [spring] with negative stiffness", "[scene][bad]") {
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
[spring]
stiffness = -1
damping = 0
[run]
t_end = 1
)"),
             StartsWith("test.toml:5: [spring] stiffness: must be >= 0, got -1"));
}

TEST_CASE("bad input: [spring] with negative damping", "[scene][bad]") {
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
[spring]
stiffness = 1
damping = -0.5
[run]
t_end = 1
)"),
             StartsWith("test.toml:6: [spring] damping: must be >= 0, got -0.5"));
}

TEST_CASE("bad input: [spring] and [drive] required keys", "[scene][bad]") {
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
[spring]
damping = 1
[run]
t_end = 1
)"),
             StartsWith("test.toml:4: [spring] stiffness: missing"));
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
[spring]
stiffness = 1
[run]
t_end = 1
)"),
             StartsWith("test.toml:4: [spring] damping: missing"));
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
[drive]
angular_frequency = 1
[run]
t_end = 1
)"),
             StartsWith("test.toml:4: [drive] torque_amplitude: missing"));
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
[drive]
torque_amplitude = [1, 0, 0]
phase = 0.5
[run]
t_end = 1
)"),
             StartsWith("test.toml:4: [drive] angular_frequency: missing"));
}

TEST_CASE("bad input: quaternion not of unit norm", "[scene][bad]") {
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
[initial]
quaternion = [1, 0, 0, 0.001]
[run]
t_end = 1
)"),
             StartsWith("test.toml:5: [initial] quaternion: not a unit quaternion"));
  // 1e-12 off is rejected, below is normalised
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
[initial]
quaternion = [1.000000000002, 0, 0, 0]
[run]
t_end = 1
)"),
             StartsWith("test.toml:5: [initial] quaternion: not a unit quaternion"));
  const auto s = parse_scene(R"(name = "t"
[body]
inertia = [1, 1, 1]
[initial]
quaternion = [1.0000000000005, 0, 0, 0]
[run]
t_end = 1
)",
                             "test.toml");
  CHECK(s.initial.R == Mat3::Identity());
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
[spring]
stiffness = 1
damping = 1
rest_quaternion = [0, 0, 0, 0]
[run]
t_end = 1
)"),
             StartsWith("test.toml:7: [spring] rest_quaternion: not a unit quaternion"));
}

TEST_CASE("bad input: matrix not orthogonal", "[scene][bad]") {
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
[initial]
matrix = [[1, 0, 0], [0, 1, 0.001], [0, 0, 1]]
[run]
t_end = 1
)"),
             StartsWith("test.toml:5: [initial] matrix: not orthogonal"));
}

TEST_CASE("bad input: matrix with det = -1", "[scene][bad]") {
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
[initial]
matrix = [[1, 0, 0], [0, 1, 0], [0, 0, -1]]
[run]
t_end = 1
)"),
             StartsWith("test.toml:5: [initial] matrix: det = -1"));
  // a proper rotation is accepted as given
  const auto s = parse_scene(R"(name = "t"
[body]
inertia = [1, 1, 1]
[initial]
matrix = [[0, -1, 0], [1, 0, 0], [0, 0, 1]]
[run]
t_end = 1
)",
                             "test.toml");
  Mat3 Rz90;
  Rz90 << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  CHECK(s.initial.R == Rz90);
}

TEST_CASE("bad input: euler_zxz_rates without euler_zxz attitude", "[scene][bad]") {
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
[initial]
rotation_vector = [0, 0.3, 0]
euler_zxz_rates = [0, 0, 1]
[run]
t_end = 1
)"),
             StartsWith("test.toml:6: [initial] euler_zxz_rates: needs the attitude given as euler_zxz"));
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
[initial]
euler_zxz_rates = [0, 0, 1]
[run]
t_end = 1
)"),
             StartsWith("test.toml:5: [initial] euler_zxz_rates: needs the attitude given as euler_zxz"));
}

TEST_CASE("bad input: t_end < 0", "[scene][bad]") {
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
[run]
t_end = -1
)"),
             StartsWith("test.toml:5: [run] t_end: must be >= 0, got -1"));
}

TEST_CASE("bad input: dt <= 0", "[scene][bad]") {
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
[run]
t_end = 1
dt = 0
)"),
             StartsWith("test.toml:6: [run] dt: must be > 0, got 0"));
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
[run]
t_end = 1
dt = -1e-3
)"),
             StartsWith("test.toml:6: [run] dt: must be > 0, got -0.001"));
}

TEST_CASE("bad input: tol <= 0", "[scene][bad]") {
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
[run]
t_end = 1
tol = 0.0
)"),
             StartsWith("test.toml:6: [run] tol: must be > 0, got 0"));
}

TEST_CASE("bad input: TOML syntax error", "[scene][bad]") {
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
[run]
t_end = = 1
)"),
             StartsWith("test.toml:5: TOML syntax error:"));
  // a key defined twice is a TOML error too
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
inertia = [2, 2, 2]
[run]
t_end = 1
)"),
             StartsWith("test.toml:4: TOML syntax error:"));
}

TEST_CASE("bad input: unreadable or missing file", "[scene][bad]") {
  const std::string missing = std::string(LGI_TEST_TMPDIR) + "/no_such_scene.toml";
  std::filesystem::remove(missing);
  try {
    (void)read_scene(missing);
    FAIL("read_scene accepted a missing file");
  } catch (const InputError& e) {
    CHECK_THAT(std::string(e.what()), StartsWith(missing + ": cannot read scene file"));
  }
  try {
    (void)read_scene(LGI_TEST_TMPDIR);
    FAIL("read_scene accepted a directory");
  } catch (const InputError& e) {
    CHECK_THAT(std::string(e.what()), StartsWith(std::string(LGI_TEST_TMPDIR) + ": cannot read scene file"));
  }
  // and a readable file reports its own path in messages
  const std::string bad = std::string(LGI_TEST_TMPDIR) + "/scene_reader_bad.toml";
  {
    std::ofstream out(bad);
    out << "name = \"t\"\n[body]\ninertia = [1, 1]\n[run]\nt_end = 1\n";
  }
  try {
    (void)read_scene(bad);
    FAIL("read_scene accepted bad input");
  } catch (const InputError& e) {
    CHECK_THAT(std::string(e.what()), StartsWith(bad + ":3: [body] inertia: expected 3 numbers, got 2"));
  }
  std::filesystem::remove(bad);
}
