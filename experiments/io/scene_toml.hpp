#pragma once
// Reading one TOML table of a scene file with the scene reader's one-line
// messages ("<file>:<line>: [<table>] <key>: <what>", exit status 2): the
// shared helpers of scene_reader.cpp and scene_term_tables.cpp.
#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "experiments/errors/input_error.hpp"
#include "integrators/system/inertia.hpp"
#include "lie/quaternion.hpp"

namespace lgi::experiments::scene_toml {

using lie::Mat3;
using lie::Vec3;

// experiments/scenes/README.md, "Bad input": | |q| − 1 | is rejected at or above this.
inline constexpr double unit_norm_tolerance = 1e-12;

using Line = std::optional<std::uint32_t>;

inline Line line_of(const toml::source_region& r) {
  if (r.begin.line == 0) return std::nullopt;
  return r.begin.line;
}
inline Line line_of(const toml::node& n) { return line_of(n.source()); }

/// Shortest round-trip decimal form of a double ("0.1", "nan", "-inf").
inline std::string fmt(double x) {
  std::array<char, 64> buf{};
  const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), x);
  return std::string(buf.data(), r.ptr);
}
inline std::string fmt(const Vec3& v) { return "(" + fmt(v.x()) + ", " + fmt(v.y()) + ", " + fmt(v.z()) + ")"; }

template <class Names>
std::string join(const Names& names) {
  std::string out;
  for (std::string_view n : names) {
    if (!out.empty()) out += ", ";
    out += n;
  }
  return out;
}

inline std::string type_name(const toml::node& n) {
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
  const std::string& file() const { return file_; }

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
  /// table_list: for the top level, the names of the tables a file may have.
  void check_keys(const Names& allowed, std::string_view table_list = {}) const {
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
              "unknown table (the tables are " + std::string(table_list) + ")");
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

inline Table sub_table(const Table& root, std::string_view name) {
  const toml::node* n = root.get(name);
  if (!n) return {root.rd, name, nullptr, std::nullopt};
  const auto* t = n->as_table();
  if (!t) root.rd.fail(line_of(*n), name, "", "expected a table, got " + type_name(*n));
  return {root.rd, name, t, line_of(*t)};
}

/// A unit quaternion [w, x, y, z], normalised if its norm is within the
/// tolerance of 1, rejected otherwise; returned as a rotation matrix.
inline Mat3 unit_quaternion(const Table& t, std::string_view key, const toml::node& n) {
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


}  // namespace lgi::experiments::scene_toml
