// Scene files: TOML (toml++) → lgi::system::Scene, with every bad-input rule
// of experiments/scenes/README.md. See scene_reader.hpp for the message format and
// experiments/scenes/README.md for the format itself.
#include "experiments/io/scene_reader.hpp"

#include <toml++/toml.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "experiments/io/gamma_attitude.hpp"
#include "experiments/io/input_file.hpp"
#include "experiments/io/scene_suspension.hpp"
#include "experiments/io/scene_term_tables.hpp"
#include "experiments/io/scene_toml.hpp"
#include "integrators/system/inertia.hpp"
#include "lie/charts.hpp"
#include "lie/quaternion.hpp"
#include "lie/so3.hpp"

namespace lgi::experiments {
namespace {
// This file's own namespace: its `using namespace` below does not reach the next
// file of a unity batch (experiments/CMakeLists.txt).
namespace scene_reader_toml {

using namespace scene_toml;

using lie::Mat3;
using lie::Vec3;
using lgi::system::Scene;

// Tolerances of experiments/scenes/README.md, "Bad input".
constexpr double orthogonality_tolerance = 1e-12;  // |RᵀR − I| (Frobenius) and |det R − 1|
constexpr double symmetry_tolerance = 1e-12;       // |J_ij − J_ji| relative to max |J_kl|
// The triangle inequality J_i ≤ J_j + J_k holds with equality for plane
// bodies (a thin disk: J3 = J1 + J2); this relative slack keeps rounding in
// the parallel-axis sum or the eigen-decomposition from rejecting them.
constexpr double triangle_slack = 1e-12;

constexpr std::array<std::string_view, 5> attitude_keys = {"quaternion", "euler_zxz", "rotation_vector", "matrix",
                                                           "gamma"};
constexpr std::array<std::string_view, 3> motion_keys = {"angular_velocity", "angular_momentum", "euler_zxz_rates"};
constexpr std::array<std::string_view, 3> inertia_keys = {"inertia", "inertia_cm", "inertia_tensor"};
/// The tables a scene file may have: [body], the torque terms', [suspension], [initial], [run].
std::vector<std::string_view> table_names() {
  std::vector<std::string_view> names = {"body"};
  names.insert(names.end(), SceneTermTables::names.begin(), SceneTermTables::names.end());
  names.insert(names.end(), {"suspension", "initial", "run"});
  return names;
}

/// All moments > 0.
Vec3 positive_moments(const Table& t, std::string_view key, const toml::node& n) {
  const Vec3 m = t.vec3(key, n);
  for (int i = 0; i < 3; ++i) {
    if (!(m[i] > 0.0)) {
      t.fail(n, key, "moment " + std::to_string(i + 1) + " must be > 0, got " + fmt(m[i]));
    }
  }
  return m;
}

// ---- tables -----------------------------------------------------------

struct BodyInfo {
  std::string_view inertia_key;  // which inertia key the file uses
  Line inertia_line;
};

BodyInfo read_body(const Table& body, Scene& s) {
  constexpr std::array<std::string_view, 6> keys = {"mass",       "inertia",        "inertia_cm",
                                                    "inertia_tensor", "center_of_mass", "allow_unphysical"};
  body.check_keys(keys);

  if (const toml::node* n = body.get("allow_unphysical")) s.allow_unphysical = body.boolean("allow_unphysical", *n);
  if (const toml::node* n = body.get("mass")) {
    const double m = body.number("mass", *n);
    if (!(m > 0.0)) body.fail(*n, "mass", "must be > 0, got " + fmt(m));
    s.mass = m;
  }
  if (const toml::node* n = body.get("center_of_mass")) s.center_of_mass = body.vec3("center_of_mass", *n);

  const auto which = body.one_of(inertia_keys, "inertia");
  if (!which) {
    body.rd.fail(body.line, "body", "inertia",
                 body.present() ? "missing: give exactly one of inertia, inertia_cm, inertia_tensor"
                                : "missing (no [body] table): give exactly one of inertia, inertia_cm, "
                                  "inertia_tensor in [body]");
  }
  const std::string_view key = *which;
  const toml::node& n = *body.get(key);

  Mat3 J;
  if (key == "inertia") {
    J = positive_moments(body, key, n).asDiagonal();
  } else if (key == "inertia_cm") {
    const Mat3 J_cm = positive_moments(body, key, n).asDiagonal();
    if (s.center_of_mass) {
      if (!s.mass) {
        body.fail(n, "mass",
                  "missing: inertia_cm with center_of_mass needs the mass for the parallel-axis theorem");
      }
      J = lgi::system::parallel_axis(J_cm, *s.mass, *s.center_of_mass);
    } else {
      J = J_cm;  // a free body: the reference point is the centre of mass
    }
  } else {
    const Mat3 T = body.matrix(key, n);
    const double scale = T.cwiseAbs().maxCoeff();
    for (int i = 0; i < 3; ++i) {
      for (int j = i + 1; j < 3; ++j) {
        const double d = std::abs(T(i, j) - T(j, i));
        if (d > symmetry_tolerance * scale) {
          body.fail(n, key,
                    "not symmetric: element (" + std::to_string(i + 1) + "," + std::to_string(j + 1) + ") = " +
                        fmt(T(i, j)) + " but (" + std::to_string(j + 1) + "," + std::to_string(i + 1) +
                        ") = " + fmt(T(j, i)) + " (tolerance 1e-12 relative)");
        }
      }
    }
    J = 0.5 * (T + T.transpose());
    const Vec3 eig = Eigen::SelfAdjointEigenSolver<Mat3>(J, Eigen::EigenvaluesOnly).eigenvalues();
    if (!(eig.minCoeff() > 0.0)) {
      body.fail(n, key, "not positive definite: eigenvalues " + fmt(eig));
    }
  }

  if (!s.allow_unphysical) {
    const Vec3 p = lgi::system::make_inertia(J).principal;
    for (int i = 0; i < 3; ++i) {
      const double a = p[(i + 1) % 3], b = p[(i + 2) % 3];
      if (p[i] > (a + b) * (1.0 + triangle_slack)) {
        body.fail(n, key,
                  "principal moments " + fmt(p) + " about the reference point violate the triangle inequality (" +
                      fmt(p[i]) + " > " + fmt(a) + " + " + fmt(b) +
                      "); no rigid body has them (set allow_unphysical = true for a mathematical test problem)");
      }
    }
  }
  s.inertia = J;
  return {key, line_of(n)};
}

/// [initial] gamma: the vertical in the body frame; a zero vector is refused, any
/// other is normalised, with a note on stderr where |γ| differs from 1 by more
/// than 1e-12 (experiments/scenes/README.md).
Vec3 unit_gamma(const Table& initial, const toml::node& n) {
  const Vec3 g = initial.vec3("gamma", n);
  const double norm = g.norm();
  if (!(norm > 0.0) || !std::isfinite(norm))
    initial.fail(n, "gamma", "must be a nonzero vector (the vertical direction in the body frame), got " + fmt(g));
  if (!(std::abs(norm - 1.0) <= unit_norm_tolerance)) {
    const Line line = line_of(n);
    std::cerr << "lgi: note: " << initial.rd.file() << (line ? ":" + std::to_string(*line) : std::string()) << ": ["
              << initial.name << "] gamma: |gamma| = " << fmt(norm) << ", normalised to a unit vector\n";
  }
  return g / norm;
}

void read_initial(const Table& initial, Scene& s) {
  std::vector<std::string_view> keys(attitude_keys.begin(), attitude_keys.end());
  keys.insert(keys.end(), motion_keys.begin(), motion_keys.end());
  keys.insert(keys.end(), cardan_initial_keys.begin(), cardan_initial_keys.end());
  initial.check_keys(keys);

  const auto attitude = initial.one_of(attitude_keys, "attitude");
  const auto motion = initial.one_of(motion_keys, "motion");

  Mat3 R = Mat3::Identity();
  lie::EulerZXZ euler;
  if (attitude) {
    const std::string_view key = *attitude;
    const toml::node& n = *initial.get(key);
    if (key == "quaternion") {
      R = unit_quaternion(initial, key, n);
    } else if (key == "euler_zxz") {
      const Vec3 e = initial.vec3(key, n);
      euler = {e.x(), e.y(), e.z()};
      R = lie::matrix_from_euler_zxz(euler);
    } else if (key == "rotation_vector") {
      R = lie::matrix_from_rotation_vector(initial.vec3(key, n));
    } else if (key == "gamma") {
      R = attitude_from_gamma(unit_gamma(initial, n));
    } else {
      R = initial.matrix(key, n);
      const double orth = lie::orthogonality_error(R);
      if (!(orth <= orthogonality_tolerance)) {
        initial.fail(n, key, "not orthogonal: |R^T R - I| = " + fmt(orth) + " (tolerance 1e-12)");
      }
      const double det = R.determinant();
      if (!(std::abs(det - 1.0) <= orthogonality_tolerance)) {
        initial.fail(n, key, "det = " + fmt(det) + ", not +1: a reflection is not an attitude");
      }
    }
  }

  Vec3 Pi = Vec3::Zero();
  if (motion) {
    const std::string_view key = *motion;
    const toml::node& n = *initial.get(key);
    const Vec3 v = initial.vec3(key, n);
    if (key == "angular_velocity") {
      Pi = s.inertia * v;
    } else if (key == "angular_momentum") {
      Pi = v;
    } else {
      if (attitude != std::optional<std::string_view>("euler_zxz")) {
        initial.fail(n, key,
                     "needs the attitude given as euler_zxz (here: " +
                         (attitude ? std::string(*attitude) : std::string("none, the identity")) + ")");
      }
      Pi = s.inertia * lie::omega_from_euler_zxz_rates(euler, v);
    }
  }
  s.initial = {R, Pi};
}

void read_run(const Table& run, Scene& s) {
  constexpr std::array<std::string_view, 3> keys = {"t_end", "dt", "tol"};
  run.check_keys(keys);
  // Every [run] key is optional: a command that needs a value the scene lacks asks for its flag.
  s.t_end = run.optional_number("t_end");
  if (s.t_end && !(*s.t_end >= 0.0)) run.fail(*run.get("t_end"), "t_end", "must be >= 0, got " + fmt(*s.t_end));
  s.dt = run.optional_number("dt");
  if (s.dt && !(*s.dt > 0.0)) run.fail(*run.get("dt"), "dt", "must be > 0, got " + fmt(*s.dt));
  s.tol = run.optional_number("tol");
  if (s.tol && !(*s.tol > 0.0 && *s.tol < 1.0))
    run.fail(*run.get("tol"), "tol", "must be in (0, 1) (a relative tolerance), got " + fmt(*s.tol));
}

}  // namespace scene_reader_toml
}  // namespace

system::Scene parse_scene(std::string_view toml_text, const std::string& path_for_messages) {
  using namespace scene_reader_toml;
  const Reader rd(path_for_messages);
  toml::table doc;
  try {
    doc = toml::parse(toml_text, std::string_view(path_for_messages));
  } catch (const toml::parse_error& e) {
    std::string m = path_for_messages;
    if (const Line l = line_of(e.source())) m += ":" + std::to_string(*l);
    m += ": TOML syntax error: ";
    m += e.description();
    std::replace_if(m.begin(), m.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
    throw InputError(m);
  }

  Scene s;
  s.file = path_for_messages;
  s.toml_text = std::string(toml_text);

  const Table root{rd, "", &doc, std::nullopt};
  std::vector<std::string_view> top = {"name", "description"};
  const std::vector<std::string_view> tables = table_names();
  top.insert(top.end(), tables.begin(), tables.end());
  root.check_keys(top, join(tables));

  const toml::node* name = root.get("name");
  if (!name) rd.fail(std::nullopt, "", "name", "missing (required: a one-line name for the scene)");
  s.name = root.string("name", *name);
  if (s.name.find_first_of("\n\r") != std::string::npos) root.fail(*name, "name", "must be one line");
  if (s.name.find_first_not_of(" \t") == std::string::npos) root.fail(*name, "name", "must not be empty");
  if (const toml::node* d = root.get("description")) s.description = root.string("description", *d);

  // The tables' own types first, so that "gravity = 9.81" is reported as such.
  const Table body = sub_table(root, "body");
  const auto term_tables = SceneTermTables::find(root);
  const Table suspension = sub_table(root, "suspension");
  const Table initial = sub_table(root, "initial");
  const Table run = sub_table(root, "run");

  read_body(body, s);
  SceneTermTables::read(term_tables, s);
  read_suspension(suspension, s);  // docs/cardan.md §6
  read_initial(initial, s);
  read_cardan_initial(initial, s);
  read_run(run, s);
  return s;
}

void refuse_cardan_scene(const system::Scene& scene, const std::string& command) {
  using namespace scene_reader_toml;
  if (scene.suspension)
    throw InputError(scene.file + ": [suspension]: lgi " + command +
                     " works on SO(3) and does not take a Cardan top (simulate, equilibria, bifurcation, poincare "
                     "and indicators do; docs/cardan.md)");
}

system::Scene read_scene(const std::string& path) {
  using namespace scene_reader_toml;
  return parse_scene(read_text_input(path, "scene file"), path);
}

}  // namespace lgi::experiments
