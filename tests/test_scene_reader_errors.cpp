// Scene files (experiments/io/scene_reader.hpp): bad input in the structure
// of a file (missing or conflicting keys, wrong types and lengths, unknown keys
// and tables, non-finite numbers, [run] values, TOML syntax, unreadable files)
// throws InputError with one line
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

TEST_CASE("bad input: [initial] gamma", "[scene][bad]") {
  const std::string head = "name = \"t\"\n[body]\ninertia = [1, 1, 1]\n[initial]\n";
  CHECK_THAT(error_of(head + "gamma = [0, 0, 0]\nangular_momentum = [1, 0, 0]\n"),
             StartsWith("test.toml:5: [initial] gamma: must be a nonzero vector"));
  CHECK_THAT(error_of(head + "gamma = [0, 1]\n"), StartsWith("test.toml:5: [initial] gamma: expected 3 numbers"));
  CHECK_THAT(error_of(head + "quaternion = [1, 0, 0, 0]\ngamma = [0, 0, 1]\n"),
             StartsWith("test.toml:6: [initial] gamma: conflicts with quaternion (line 5): give at most one "
                        "attitude key (quaternion, euler_zxz, rotation_vector, matrix, gamma)"));
  CHECK_THAT(error_of(head + "gamma = [0, 0, 1]\neuler_zxz_rates = [0, 0, 1]\n"),
             StartsWith("test.toml:6: [initial] euler_zxz_rates: needs the attitude given as euler_zxz (here: gamma)"));
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

TEST_CASE("bad input: tol <= 0 or >= 1", "[scene][bad]") {
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
[run]
t_end = 1
tol = 0.0
)"),
             StartsWith("test.toml:6: [run] tol: must be in (0, 1) (a relative tolerance), got 0"));
  CHECK_THAT(error_of(R"(name = "t"
[body]
inertia = [1, 1, 1]
[run]
t_end = 1
tol = 1e50
)"),
             StartsWith("test.toml:6: [run] tol: must be in (0, 1) (a relative tolerance), got 1e+50"));
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
