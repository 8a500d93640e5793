// Scene files (experiments/io/scene_reader.hpp): physically invalid values
// (mass, moments and inertia tensors, gravity, spring and drive parameters,
// attitudes that are not rotations) throw InputError with one line naming the
// file, the key and (where one applies) the line.
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

#include "support/near.hpp"
#include "support/scene_error.hpp"
#include "support/valid_scene.hpp"

using lgi::experiments::InputError;
using lgi::experiments::parse_scene;
using lgi::experiments::read_scene;
using lgi::lie::Mat3;
using lgi::lie::Vec3;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using lgi::testing::error_of;
using lgi::testing::near;
using lgi::testing::valid_top;

// ---------------------------------------------------------------------------
// Bad input: physical values

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
