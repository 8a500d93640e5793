// Scene files: TOML (toml++) → lgi::system::Scene, with every bad-input rule
// of experiments/scenes/README.md. See scene_reader.hpp for the message format and
// experiments/scenes/README.md for the format itself.
#include "experiments/scene_reader.hpp"

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
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "integrators/system/inertia.hpp"
#include "lie/charts.hpp"
#include "lie/quaternion.hpp"
#include "lie/so3.hpp"

namespace lgi::experiments {
namespace {

using lie::Mat3;
using lie::Vec3;
using lgi::system::Scene;

// Tolerances of experiments/scenes/README.md, "Bad input".
constexpr double unit_norm_tolerance = 1e-12;      // | |q| − 1 |, rejected at or above
constexpr double orthogonality_tolerance = 1e-12;  // |RᵀR − I| (Frobenius) and |det R − 1|
constexpr double symmetry_tolerance = 1e-12;       // |J_ij − J_ji| relative to max |J_kl|
// The triangle inequality J_i ≤ J_j + J_k holds with equality for plane
// bodies (a thin disk: J3 = J1 + J2); this relative slack keeps rounding in
// the parallel-axis sum or the eigen-decomposition from rejecting them.
constexpr double triangle_slack = 1e-12;

constexpr std::array<std::string_view, 4> attitude_keys = {"quaternion", "euler_zxz", "rotation_vector", "matrix"};
constexpr std::array<std::string_view, 3> motion_keys = {"angular_velocity", "angular_momentum", "euler_zxz_rates"};
constexpr std::array<std::string_view, 3> inertia_keys = {"inertia", "inertia_cm", "inertia_tensor"};
constexpr std::array<std::string_view, 6> table_names = {"body", "gravity", "spring", "drive", "initial", "run"};

using Line = std::optional<std::uint32_t>;

Line line_of(const toml::source_region& r) {
  if (r.begin.line == 0) return std::nullopt;
  return r.begin.line;
}
Line line_of(const toml::node& n) { return line_of(n.source()); }

/// Shortest round-trip decimal form of a double ("0.1", "nan", "-inf").
std::string fmt(double x) {
  std::array<char, 64> buf{};
  const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), x);
  return std::string(buf.data(), r.ptr);
}
std::string fmt(const Vec3& v) { return "(" + fmt(v.x()) + ", " + fmt(v.y()) + ", " + fmt(v.z()) + ")"; }

template <class Names>
std::string join(const Names& names) {
  std::string out;
  for (std::string_view n : names) {
    if (!out.empty()) out += ", ";
    out += n;
  }
  return out;
}

std::string type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a float";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::date: return "a date";
    case toml::node_type::time: return "a time";
    case toml::node_type::date_time: return "a date-time";
    default: return "nothing";
  }
}

/// The file being read; builds and throws the one-line messages.
class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  /// "<file>[:<line>]: [<table>] <key>: <what>", on one line.
  [[noreturn]] void fail(Line line, std::string_view table, std::string_view key, std::string_view what) const {
    std::string m = file_;
    if (line) m += ":" + std::to_string(*line);
    m += ": ";
    if (!table.empty()) {
      m += "[";
      m += table;
      m += "]";
      if (!key.empty()) m += " ";
    }
    m += key;
    m += ": ";
    m += what;
    std::replace_if(m.begin(), m.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
    throw InputError(m);
  }

 private:
  std::string file_;
};

/// One table of the file (the top level has an empty name); `tbl` is null
/// for a table the file does not have.
struct Table {
  const Reader& rd;
  std::string_view name;
  const toml::table* tbl = nullptr;
  Line line;  // the header's line; none for the top level or an absent table

  bool present() const { return tbl != nullptr; }
  const toml::node* get(std::string_view key) const { return tbl ? tbl->get(key) : nullptr; }

  [[noreturn]] void fail(const toml::node& at, std::string_view key, std::string_view what) const {
    rd.fail(line_of(at), name, key, what);
  }
  [[noreturn]] void fail_here(std::string_view key, std::string_view what) const { rd.fail(line, name, key, what); }

  /// Rejects every key not in `allowed` (the first in the file, by line).
  template <class Names>
  void check_keys(const Names& allowed) const {
    if (!tbl) return;
    const toml::key* first = nullptr;
    const toml::node* first_value = nullptr;
    for (auto&& [k, v] : *tbl) {
      if (std::find(std::begin(allowed), std::end(allowed), k.str()) != std::end(allowed)) continue;
      const std::uint32_t l = k.source().begin.line;
      if (!first || l < first->source().begin.line) {
        first = &k;
        first_value = &v;
      }
    }
    if (!first) return;
    if (name.empty() && first_value->is_table()) {
      rd.fail(line_of(first->source()), first->str(), "",
              "unknown table (the tables are " + join(table_names) + ")");
    }
    rd.fail(line_of(first->source()), name, first->str(), "unknown key (allowed here: " + join(allowed) + ")");
  }

  // ---- values ---------------------------------------------------------

  static std::optional<double> as_double(const toml::node& n) {
    if (const auto* i = n.as_integer()) return static_cast<double>(i->get());
    if (const auto* f = n.as_floating_point()) return f->get();
    return std::nullopt;
  }

  /// A finite number (integers accepted). `what` prefixes element messages.
  double number(std::string_view key, const toml::node& n, const std::string& element = {}) const {
    const auto v = as_double(n);
    if (!v) fail(n, key, element + "expected a number, got " + type_name(n));
    if (!std::isfinite(*v)) fail(n, key, element + "expected a finite number, got " + fmt(*v));
    return *v;
  }

  std::vector<double> numbers(std::string_view key, const toml::node& n, std::size_t count,
                              const std::string& row = {}) const {
    const auto* a = n.as_array();
    if (!a) fail(n, key, row + "expected " + std::to_string(count) + " numbers, got " + type_name(n));
    if (a->size() != count) {
      fail(n, key, row + "expected " + std::to_string(count) + " numbers, got " + std::to_string(a->size()));
    }
    std::vector<double> out;
    out.reserve(count);
    for (std::size_t i = 0; i < count; ++i) {
      out.push_back(number(key, (*a)[i], row + "element " + std::to_string(i + 1) + ": "));
    }
    return out;
  }

  Vec3 vec3(std::string_view key, const toml::node& n) const {
    const auto v = numbers(key, n, 3);
    return {v[0], v[1], v[2]};
  }

  /// A 3×3 matrix, row by row: [[a, b, c], [d, e, f], [g, h, i]].
  Mat3 matrix(std::string_view key, const toml::node& n) const {
    const auto* a = n.as_array();
    if (!a) fail(n, key, "expected 3 rows of 3 numbers, got " + type_name(n));
    if (a->size() != 3) fail(n, key, "expected 3 rows of 3 numbers, got " + std::to_string(a->size()) + " rows");
    Mat3 m;
    for (std::size_t i = 0; i < 3; ++i) {
      const auto row = numbers(key, (*a)[i], 3, "row " + std::to_string(i + 1) + ": ");
      for (std::size_t j = 0; j < 3; ++j) m(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = row[j];
    }
    return m;
  }

  bool boolean(std::string_view key, const toml::node& n) const {
    const auto* b = n.as_boolean();
    if (!b) fail(n, key, "expected true or false, got " + type_name(n));
    return b->get();
  }

  std::string string(std::string_view key, const toml::node& n) const {
    const auto* s = n.as_string();
    if (!s) fail(n, key, "expected a string, got " + type_name(n));
    return s->get();
  }

  /// A required number: missing → error naming the key at the table's line.
  double required_number(std::string_view key, std::string_view meaning) const {
    const toml::node* n = get(key);
    if (!n) {
      fail_here(key, std::string("missing (required: ") + std::string(meaning) + ")");
    }
    return number(key, *n);
  }

  std::optional<double> optional_number(std::string_view key) const {
    const toml::node* n = get(key);
    if (!n) return std::nullopt;
    return number(key, *n);
  }

  /// At most one key of `group`; returns it, or nothing if none is given.
  template <std::size_t N>
  std::optional<std::string_view> one_of(const std::array<std::string_view, N>& group,
                                         std::string_view what) const {
    std::vector<std::pair<std::uint32_t, std::string_view>> found;
    for (std::string_view k : group) {
      if (const toml::node* n = get(k)) found.emplace_back(n->source().begin.line, k);
    }
    if (found.empty()) return std::nullopt;
    if (found.size() > 1) {
      std::stable_sort(found.begin(), found.end(),
                       [](const auto& a, const auto& b) { return a.first < b.first; });
      const auto& [l0, k0] = found[0];
      const auto& [l1, k1] = found[1];
      rd.fail(l1 == 0 ? Line{} : Line{l1}, name, k1,
              "conflicts with " + std::string(k0) + (l0 == 0 ? std::string() : " (line " + std::to_string(l0) + ")") +
                  ": give at most one " + std::string(what) + " key (" + join(group) + ")");
    }
    return found[0].second;
  }
};

Table sub_table(const Table& root, std::string_view name) {
  const toml::node* n = root.get(name);
  if (!n) return {root.rd, name, nullptr, std::nullopt};
  const auto* t = n->as_table();
  if (!t) root.rd.fail(line_of(*n), name, "", "expected a table, got " + type_name(*n));
  return {root.rd, name, t, line_of(*t)};
}

/// A unit quaternion [w, x, y, z], normalised if its norm is within the
/// tolerance of 1, rejected otherwise; returned as a rotation matrix.
Mat3 unit_quaternion(const Table& t, std::string_view key, const toml::node& n) {
  const auto v = t.numbers(key, n, 4);
  const double norm = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3]);
  const double dev = std::abs(norm - 1.0);
  if (!(dev < unit_norm_tolerance)) {
    t.fail(n, key,
           "not a unit quaternion: norm " + fmt(norm) + " differs from 1 by " + fmt(dev) +
               " (tolerance 1e-12; give [w, x, y, z] with w^2 + x^2 + y^2 + z^2 = 1)");
  }
  return lie::matrix_from_quat(Eigen::Quaterniond(v[0] / norm, v[1] / norm, v[2] / norm, v[3] / norm));
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

void read_gravity(const Table& gravity, Scene& s) {
  constexpr std::array<std::string_view, 1> keys = {"g"};
  gravity.check_keys(keys);
  lgi::system::GravitySpec spec;
  if (const auto g = gravity.optional_number("g")) {
    if (!(*g >= 0.0)) {
      gravity.fail(*gravity.get("g"), "g", "must be >= 0 (a magnitude; gravity points along -e3), got " + fmt(*g));
    }
    spec.g = *g;
  }
  if (!s.mass) gravity.rd.fail(gravity.line, "body", "mass", "missing: [gravity] needs the body's mass");
  if (!s.center_of_mass) {
    gravity.rd.fail(gravity.line, "body", "center_of_mass", "missing: [gravity] needs the body's centre of mass");
  }
  s.gravity = spec;
}

void read_spring(const Table& spring, Scene& s) {
  constexpr std::array<std::string_view, 3> keys = {"stiffness", "damping", "rest_quaternion"};
  spring.check_keys(keys);
  lgi::system::SpringSpec spec;
  spec.stiffness = spring.required_number("stiffness", "k in N m/rad");
  if (!(spec.stiffness >= 0.0)) spring.fail(*spring.get("stiffness"), "stiffness", "must be >= 0, got " + fmt(spec.stiffness));
  spec.damping = spring.required_number("damping", "c in N m s/rad");
  if (!(spec.damping >= 0.0)) spring.fail(*spring.get("damping"), "damping", "must be >= 0, got " + fmt(spec.damping));
  if (const toml::node* n = spring.get("rest_quaternion")) spec.rest = unit_quaternion(spring, "rest_quaternion", *n);
  s.spring = spec;
}

void read_drive(const Table& drive, Scene& s) {
  constexpr std::array<std::string_view, 3> keys = {"torque_amplitude", "angular_frequency", "phase"};
  drive.check_keys(keys);
  lgi::system::DriveSpec spec;
  const toml::node* a = drive.get("torque_amplitude");
  if (!a) drive.fail_here("torque_amplitude", "missing (required: the body torque amplitude A in N m)");
  spec.torque_amplitude = drive.vec3("torque_amplitude", *a);
  spec.angular_frequency = drive.required_number("angular_frequency", "omega in rad/s");
  spec.phase = drive.optional_number("phase").value_or(0.0);
  s.drive = spec;
}

void read_initial(const Table& initial, Scene& s) {
  std::vector<std::string_view> keys(attitude_keys.begin(), attitude_keys.end());
  keys.insert(keys.end(), motion_keys.begin(), motion_keys.end());
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
  if (s.tol && !(*s.tol > 0.0)) run.fail(*run.get("tol"), "tol", "must be > 0, got " + fmt(*s.tol));
}

}  // namespace

Scene parse_scene(std::string_view toml_text, const std::string& path_for_messages) {
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
  top.insert(top.end(), table_names.begin(), table_names.end());
  root.check_keys(top);

  const toml::node* name = root.get("name");
  if (!name) rd.fail(std::nullopt, "", "name", "missing (required: a one-line name for the scene)");
  s.name = root.string("name", *name);
  if (s.name.find_first_of("\n\r") != std::string::npos) root.fail(*name, "name", "must be one line");
  if (s.name.find_first_not_of(" \t") == std::string::npos) root.fail(*name, "name", "must not be empty");
  if (const toml::node* d = root.get("description")) s.description = root.string("description", *d);

  // The tables' own types first, so that "gravity = 9.81" is reported as such.
  const Table body = sub_table(root, "body");
  const Table gravity = sub_table(root, "gravity");
  const Table spring = sub_table(root, "spring");
  const Table drive = sub_table(root, "drive");
  const Table initial = sub_table(root, "initial");
  const Table run = sub_table(root, "run");

  read_body(body, s);
  if (gravity.present()) read_gravity(gravity, s);
  if (spring.present()) read_spring(spring, s);
  if (drive.present()) read_drive(drive, s);
  read_initial(initial, s);
  read_run(run, s);
  return s;
}

Scene read_scene(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(path + ": cannot read scene file: is a directory");
  errno = 0;
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!f) {
    throw InputError(path + ": cannot read scene file: " + (errno ? std::strerror(errno) : "cannot open"));
  }
  std::string text;
  std::array<char, 1 << 16> buf{};
  std::size_t got = 0;
  while ((got = std::fread(buf.data(), 1, buf.size(), f.get())) > 0) text.append(buf.data(), got);
  if (std::ferror(f.get())) {
    throw InputError(path + ": cannot read scene file: " + (errno ? std::strerror(errno) : "read error"));
  }
  return parse_scene(text, path);
}

}  // namespace lgi::experiments
