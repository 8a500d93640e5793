// Scene files (experiments/io/scene_reader.hpp): every rule a bad scene can
// break, as one table. Each row is a scene text, the prefix its one-line
// InputError message must start with,
//   <file>:<line>: [table] key: what is wrong
// and the words the message must also hold. The structure of a file (missing
// or conflicting keys, wrong types and lengths, unknown keys and tables,
// non-finite numbers, [run] values, TOML syntax) comes first, then physically
// invalid values (mass, moments and inertia tensors, gravity, spring and drive
// parameters, attitudes that are not rotations). Valid spellings near these
// limits: test_scene_reader.cpp.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "experiments/errors/input_error.hpp"
#include "experiments/io/scene_reader.hpp"

#include "support/scene_error.hpp"

namespace test_scene_reader_errors {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

namespace {

struct BadScene {
  std::string rule;
  std::string text;
  std::string prefix;                  // the message starts with this
  std::vector<std::string> contains{};  // and holds each of these
};

// Scene heads that most rows extend; the comments give the line numbers they take.
const std::string body = "name = \"t\"\n[body]\n";      // lines 1-2
const std::string unit = body + "inertia = [1, 1, 1]\n";  // lines 1-3
const std::string initial = unit + "[initial]\n";         // lines 1-4
const std::string run = "[run]\nt_end = 1\n";

std::vector<BadScene> structure_rows() {
  return {
      {"missing name", "[body]\ninertia = [1, 1, 1]\n" + run, "test.toml: name: missing"},
      {"name not a string", "name = 3\n[body]\ninertia = [1, 1, 1]\n" + run,
       "test.toml:1: name: expected a string, got an integer"},
      {"name of two lines", "name = \"\"\"two\nlines\"\"\"\n[body]\ninertia = [1, 1, 1]\n" + run,
       "test.toml:1: name: must be one line"},
      {"missing inertia key", body + "mass = 1\n" + run, "test.toml:2: [body] inertia: missing",
       {"inertia_cm", "inertia_tensor"}},
      {"missing [body]", "name = \"t\"\n" + run, "test.toml: [body] inertia: missing"},
      {"two attitude keys", initial + "quaternion = [1, 0, 0, 0]\neuler_zxz = [0, 0, 0]\n" + run,
       "test.toml:6: [initial] euler_zxz: conflicts with quaternion (line 5)"},
      {"zero gamma", initial + "gamma = [0, 0, 0]\nangular_momentum = [1, 0, 0]\n",
       "test.toml:5: [initial] gamma: must be a nonzero vector"},
      {"gamma of two numbers", initial + "gamma = [0, 1]\n", "test.toml:5: [initial] gamma: expected 3 numbers"},
      {"gamma and quaternion", initial + "quaternion = [1, 0, 0, 0]\ngamma = [0, 0, 1]\n",
       "test.toml:6: [initial] gamma: conflicts with quaternion (line 5): give at most one "
       "attitude key (quaternion, euler_zxz, rotation_vector, matrix, gamma)"},
      {"gamma with Euler rates", initial + "gamma = [0, 0, 1]\neuler_zxz_rates = [0, 0, 1]\n",
       "test.toml:6: [initial] euler_zxz_rates: needs the attitude given as euler_zxz (here: gamma)"},
      {"two motion keys", initial + "angular_momentum = [1, 0, 0]\nangular_velocity = [1, 0, 0]\n" + run,
       "test.toml:6: [initial] angular_velocity: conflicts with angular_momentum (line 5)"},
      {"two inertia keys", unit + "inertia_tensor = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]\n" + run,
       "test.toml:4: [body] inertia_tensor: conflicts with inertia (line 3)"},
      {"mass a string", body + "mass = \"five\"\ninertia = [1, 1, 1]\n" + run,
       "test.toml:3: [body] mass: expected a number, got a string"},
      {"inertia holds a boolean", body + "inertia = [1, 1, true]\n" + run,
       "test.toml:3: [body] inertia: element 3: expected a number, got a boolean"},
      {"allow_unphysical a string", unit + "allow_unphysical = \"yes\"\n" + run,
       "test.toml:4: [body] allow_unphysical: expected true or false, got a string"},
      {"gravity a number", "name = \"t\"\ngravity = 9.81\n[body]\ninertia = [1, 1, 1]\n" + run,
       "test.toml:2: [gravity]: expected a table, got a float"},
      {"inertia a number", body + "inertia = 1\n" + run,
       "test.toml:3: [body] inertia: expected 3 numbers, got an integer"},
      {"inertia of two numbers", body + "inertia = [1, 1]\n" + run,
       "test.toml:3: [body] inertia: expected 3 numbers, got 2"},
      {"quaternion of three numbers", initial + "quaternion = [1, 0, 0]\n" + run,
       "test.toml:5: [initial] quaternion: expected 4 numbers, got 3"},
      {"matrix row of two", initial + "matrix = [[1, 0, 0],\n          [0, 1],\n          [0, 0, 1]]\n" + run,
       "test.toml:6: [initial] matrix: row 2: expected 3 numbers, got 2"},
      {"matrix of two rows", initial + "matrix = [[1, 0, 0], [0, 1, 0]]\n" + run,
       "test.toml:5: [initial] matrix: expected 3 rows of 3 numbers, got 2 rows"},
      // a typo is not ignored
      {"unknown [body] key", unit + "centre_of_mass = [0, 0, 1]\n" + run,
       "test.toml:4: [body] centre_of_mass: unknown key"},
      {"unknown top-level key", "name = \"t\"\nnmae = \"typo\"\n[body]\ninertia = [1, 1, 1]\n" + run,
       "test.toml:2: nmae: unknown key"},
      {"unknown [initial] key",
       initial + "matrix = [[0, -1, 0], [1, 0, 0], [0, 0, 1]]\nrotation_vector_is_not_here = 0\n" + run,
       "test.toml:6: [initial] rotation_vector_is_not_here: unknown key"},
      {"unknown [run] key", unit + run + "dt = 0.1\nt_end2 = 2\n", "test.toml:7: [run] t_end2: unknown key"},
      {"unknown table", unit + "mass = 1\ncenter_of_mass = [0, 0, 1]\n[gravty]\ng = 9.81\n" + run,
       "test.toml:6: [gravty]: unknown table"},
      {"unknown subtable", unit + "[body.extra]\nx = 1\n" + run, "test.toml:4: [body] extra: unknown key"},
      {"NaN moment", body + "inertia = [1, nan, 1]\n" + run,
       "test.toml:3: [body] inertia: element 2: expected a finite number, got nan"},
      {"infinite t_end", unit + "[run]\nt_end = inf\n", "test.toml:5: [run] t_end: expected a finite number, got inf"},
      {"infinite angular velocity", initial + "angular_velocity = [0, -inf, 0]\n" + run,
       "test.toml:5: [initial] angular_velocity: element 2: expected a finite number, got -inf"},
      {"t_end < 0", unit + "[run]\nt_end = -1\n", "test.toml:5: [run] t_end: must be >= 0, got -1"},
      {"dt = 0", unit + run + "dt = 0\n", "test.toml:6: [run] dt: must be > 0, got 0"},
      {"dt < 0", unit + run + "dt = -1e-3\n", "test.toml:6: [run] dt: must be > 0, got -0.001"},
      {"tol = 0", unit + run + "tol = 0.0\n",
       "test.toml:6: [run] tol: must be in (0, 1) (a relative tolerance), got 0"},
      {"tol >= 1", unit + run + "tol = 1e50\n",
       "test.toml:6: [run] tol: must be in (0, 1) (a relative tolerance), got 1e+50"},
      {"TOML syntax error", unit + "[run]\nt_end = = 1\n", "test.toml:5: TOML syntax error:"},
      // a key defined twice is a TOML error too
      {"key defined twice", unit + "inertia = [2, 2, 2]\n" + run, "test.toml:4: TOML syntax error:"},
  };
}

std::vector<BadScene> value_rows() {
  return {
      {"zero mass", body + "mass = 0\ninertia = [1, 1, 1]\n" + run, "test.toml:3: [body] mass: must be > 0, got 0"},
      {"negative mass", body + "mass = -2.5\ninertia = [1, 1, 1]\n" + run,
       "test.toml:3: [body] mass: must be > 0, got -2.5"},
      {"zero moment", body + "inertia = [1, 0, 1]\n" + run,
       "test.toml:3: [body] inertia: moment 2 must be > 0, got 0"},
      {"negative moment about the centre of mass", body + "inertia_cm = [1, 1, -1]\n" + run,
       "test.toml:3: [body] inertia_cm: moment 3 must be > 0, got -1"},
      {"triangle inequality", body + "inertia = [2, 1, 0.6666666666666666]\n" + run,
       "test.toml:3: [body] inertia: principal moments", {"triangle inequality", "allow_unphysical"}},
      // a general tensor: its principal moments (eigenvalues 1, 1, 3) are checked
      {"triangle inequality of a tensor", body + "inertia_tensor = [[2, 1, 0], [1, 2, 0], [0, 0, 1]]\n" + run,
       "test.toml:3: [body] inertia_tensor: principal moments"},
      {"triangle inequality about the centre of mass", body + "inertia_cm = [2, 1, 0.6]\n" + run,
       "test.toml:3: [body] inertia_cm: principal moments"},
      {"tensor not symmetric",
       body + "inertia_tensor = [[2, 0.1, 0],\n                  [0.1000001, 3, 0],\n                  [0, 0, 4]]\n" + run,
       "test.toml:3: [body] inertia_tensor: not symmetric"},
      {"tensor not positive definite",
       body + "allow_unphysical = true\ninertia_tensor = [[1, 2, 0], [2, 1, 0], [0, 0, 1]]\n" + run,
       "test.toml:4: [body] inertia_tensor: not positive definite"},
      {"[gravity] without mass", unit + "center_of_mass = [0, 0, 1]\n[gravity]\ng = 9.81\n" + run,
       "test.toml:5: [body] mass: missing", {"[gravity]"}},
      {"[gravity] without center_of_mass", body + "mass = 1\ninertia = [1, 1, 1]\n[gravity]\ng = 9.81\n" + run,
       "test.toml:5: [body] center_of_mass: missing", {"[gravity]"}},
      {"negative gravity",
       body + "mass = 1\ninertia = [1, 1, 1]\ncenter_of_mass = [0, 0, 1]\n[gravity]\ng = -9.81\n" + run,
       "test.toml:7: [gravity] g: must be >= 0"},
      {"inertia_cm with center_of_mass but no mass", body + "inertia_cm = [1, 1, 1]\ncenter_of_mass = [0, 0, 1]\n" + run,
       "test.toml:3: [body] mass: missing", {"parallel-axis"}},
      {"negative stiffness", unit + "[spring]\nstiffness = -1\ndamping = 0\n" + run,
       "test.toml:5: [spring] stiffness: must be >= 0, got -1"},
      {"negative damping", unit + "[spring]\nstiffness = 1\ndamping = -0.5\n" + run,
       "test.toml:6: [spring] damping: must be >= 0, got -0.5"},
      {"[spring] without stiffness", unit + "[spring]\ndamping = 1\n" + run, "test.toml:4: [spring] stiffness: missing"},
      {"[spring] without damping", unit + "[spring]\nstiffness = 1\n" + run, "test.toml:4: [spring] damping: missing"},
      {"[drive] without amplitude", unit + "[drive]\nangular_frequency = 1\n" + run,
       "test.toml:4: [drive] torque_amplitude: missing"},
      {"[drive] without frequency", unit + "[drive]\ntorque_amplitude = [1, 0, 0]\nphase = 0.5\n" + run,
       "test.toml:4: [drive] angular_frequency: missing"},
      {"quaternion not of unit norm", initial + "quaternion = [1, 0, 0, 0.001]\n" + run,
       "test.toml:5: [initial] quaternion: not a unit quaternion"},
      // 2e-12 off is rejected; test_scene_reader.cpp: 5e-13 off is normalised
      {"quaternion 2e-12 off unit norm", initial + "quaternion = [1.000000000002, 0, 0, 0]\n" + run,
       "test.toml:5: [initial] quaternion: not a unit quaternion"},
      {"zero rest quaternion", unit + "[spring]\nstiffness = 1\ndamping = 1\nrest_quaternion = [0, 0, 0, 0]\n" + run,
       "test.toml:7: [spring] rest_quaternion: not a unit quaternion"},
      {"matrix not orthogonal", initial + "matrix = [[1, 0, 0], [0, 1, 0.001], [0, 0, 1]]\n" + run,
       "test.toml:5: [initial] matrix: not orthogonal"},
      {"matrix with det = -1", initial + "matrix = [[1, 0, 0], [0, 1, 0], [0, 0, -1]]\n" + run,
       "test.toml:5: [initial] matrix: det = -1"},
      {"Euler rates with a rotation vector", initial + "rotation_vector = [0, 0.3, 0]\neuler_zxz_rates = [0, 0, 1]\n" + run,
       "test.toml:6: [initial] euler_zxz_rates: needs the attitude given as euler_zxz"},
      {"Euler rates without an attitude", initial + "euler_zxz_rates = [0, 0, 1]\n" + run,
       "test.toml:5: [initial] euler_zxz_rates: needs the attitude given as euler_zxz"},
  };
}

void check_rows(const std::vector<BadScene>& rows) {
  for (const auto& row : rows) {
    DYNAMIC_SECTION(row.rule) {
      const auto m = lgi::testing::error_of(row.text);
      CHECK_THAT(m, Catch::Matchers::StartsWith(row.prefix));
      for (const auto& word : row.contains) CHECK_THAT(m, Catch::Matchers::Contains(word));
    }
  }
}

}  // namespace

TEST_CASE("bad input: the structure of a scene file", "[scene][bad]") { check_rows(structure_rows()); }

TEST_CASE("bad input: physically invalid values", "[scene][bad]") { check_rows(value_rows()); }

TEST_CASE("bad input: unreadable or missing file", "[scene][bad]") {
  using lgi::experiments::InputError;
  using lgi::experiments::read_scene;
  using Catch::Matchers::StartsWith;
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

}  // namespace test_scene_reader_errors
