#pragma once
// TrajectoryWriter (experiments/io/h5md_writer.hpp) test support: scratch
// paths under the build tree, a deterministic layout, samples, provenance and
// diagnostics, and reading the written file back with the HDF5 C API
// (shapes, chunking, types, attributes, and the sample values themselves).
#include <catch2/catch.hpp>
#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "experiments/io/h5md_writer.hpp"

namespace lgi::testing {

// ---- scratch files --------------------------------------------------------------

inline std::string scratch(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(LGI_TEST_TMPDIR) / "h5md_writer";
  std::filesystem::create_directories(dir);
  const std::filesystem::path p = dir / name;
  std::filesystem::remove(p);
  std::filesystem::remove(std::filesystem::path(p.string() + ".partial"));
  return p.string();
}

inline bool exists(const std::string& p) { return std::filesystem::exists(std::filesystem::symlink_status(p)); }

inline std::string slurp(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// ---- deterministic samples -----------------------------------------------------------

inline experiments::TrajectoryLayout full_layout() {
  experiments::TrajectoryLayout l;
  l.scalar_invariants = {{"casimir_vertical_momentum", "kg m+2 s-1"}, {"kovalevskaya_k", "s-4"}};
  l.space_momentum = true;
  l.euler_zxz = true;
  return l;
}

inline experiments::TrajectorySample sample(std::int64_t i, std::size_t invariant_count) {
  const double x = static_cast<double>(i);
  experiments::TrajectorySample s;
  s.step = 10 * i;
  s.time = 0.001 * x;
  const double a = 0.5 * std::sin(1e-3 * x), b = 0.5 * std::cos(2e-3 * x), c = 0.25 * std::sin(3e-3 * x);
  const double w = std::sqrt(std::max(0.0, 1.0 - a * a - b * b - c * c));
  s.quaternion_wxyz = {w, a, b, c};
  s.angular_momentum_body = {1.0 + x, -2.0 * x, 0.5 * x + 0.25};
  s.angular_velocity_body = {std::sin(x), std::cos(x), 1.0 / (1.0 + x)};
  s.energy = 3.0 + 1e-12 * x;
  s.angular_momentum_space = {-x, 2.0 + x, 1e3 * x};
  s.invariant_count = invariant_count;
  for (std::size_t k = 0; k < invariant_count; ++k) s.invariants[k] = x + 0.125 * static_cast<double>(k + 1);
  s.orthogonality_error = 1e-16 * x;
  s.euler_zxz = {0.1 * x, 0.3 + 1e-5 * x, -0.2 * x};
  return s;
}

inline experiments::Provenance provenance() {
  experiments::Provenance p;
  p.text_attributes["scheme"] = "rkmk4";
  p.text_attributes["scene_toml"] = "[body]\ninertia = [1.0, 2.0, 3.0]\n# ünïcödé\n";
  p.text_attributes["command_line"] = "lgi simulate --scene x.toml --scheme rkmk4 --dt 0.001";
  p.number_attributes["dt"] = 1e-3;
  p.number_attributes["t_end"] = 10.0;
  p.integer_attributes["save_every"] = 10;
  return p;
}

inline experiments::Diagnostics diagnostics(const std::string& status) {
  experiments::Diagnostics d;
  d.steps = 99990;
  d.rejected_steps = 3;
  d.rhs_evaluations = 399960;
  d.newton_iterations_max = 7;
  d.newton_failures = 1;
  d.cpu_seconds = 1.25;
  d.status = status;
  return d;
}

// ---- reading back with the C API ------------------------------------------------------

struct H {
  hid_t id;
  herr_t (*close)(hid_t);
  H(hid_t i, herr_t (*c)(hid_t)) : id(i), close(c) { REQUIRE(id >= 0); }
  H(const H&) = delete;
  H& operator=(const H&) = delete;
  ~H() { close(id); }
  operator hid_t() const { return id; }
};

inline H open_file(const std::string& path) { return {H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose}; }
inline H open_dataset(hid_t f, const std::string& p) { return {H5Dopen2(f, p.c_str(), H5P_DEFAULT), H5Dclose}; }

inline bool has_link(hid_t f, const std::string& p) { return H5Lexists(f, p.c_str(), H5P_DEFAULT) > 0; }
inline bool has_attribute(hid_t f, const std::string& obj, const std::string& name) {
  return H5Aexists_by_name(f, obj.c_str(), name.c_str(), H5P_DEFAULT) > 0;
}

inline std::vector<hsize_t> dims(hid_t f, const std::string& p, std::vector<hsize_t>* maxdims = nullptr) {
  H d = open_dataset(f, p);
  H s(H5Dget_space(d), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(s);
  REQUIRE(rank >= 1);
  std::vector<hsize_t> out(static_cast<std::size_t>(rank)), mx(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(s, out.data(), mx.data());
  if (maxdims != nullptr) *maxdims = mx;
  return out;
}

inline bool chunked(hid_t f, const std::string& p) {
  H d = open_dataset(f, p);
  H dcpl(H5Dget_create_plist(d), H5Pclose);
  return H5Pget_layout(dcpl) == H5D_CHUNKED;
}

/// Class and size of a dataset's file type.
inline std::pair<H5T_class_t, std::size_t> type_of(hid_t f, const std::string& p) {
  H d = open_dataset(f, p);
  H t(H5Dget_type(d), H5Tclose);
  return {H5Tget_class(t), H5Tget_size(t)};
}

template <class T>
inline std::vector<T> read_all(hid_t f, const std::string& p, hid_t memory_type) {
  H d = open_dataset(f, p);
  H s(H5Dget_space(d), H5Sclose);
  const auto n = static_cast<std::size_t>(H5Sget_simple_extent_npoints(s));
  std::vector<T> out(n);
  REQUIRE(H5Dread(d, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) >= 0);
  return out;
}
inline std::vector<double> doubles(hid_t f, const std::string& p) { return read_all<double>(f, p, H5T_NATIVE_DOUBLE); }
inline std::vector<std::int64_t> int64s(hid_t f, const std::string& p) {
  return read_all<std::int64_t>(f, p, H5T_NATIVE_INT64);
}

struct StringAttribute {
  std::vector<std::string> values;
  bool variable = false;
  bool utf8 = false;
  bool scalar = false;
};

inline StringAttribute string_attribute(hid_t f, const std::string& obj, const std::string& name) {
  H a(H5Aopen_by_name(f, obj.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  H t(H5Aget_type(a), H5Tclose);
  H s(H5Aget_space(a), H5Sclose);
  REQUIRE(H5Tget_class(t) == H5T_STRING);
  StringAttribute out;
  out.variable = H5Tis_variable_str(t) > 0;
  out.utf8 = H5Tget_cset(t) == H5T_CSET_UTF8;
  out.scalar = H5Sget_simple_extent_type(s) == H5S_SCALAR;
  const auto n = static_cast<std::size_t>(H5Sget_simple_extent_npoints(s));
  if (out.variable) {
    std::vector<char*> p(n, nullptr);
    REQUIRE(H5Aread(a, t, p.data()) >= 0);
    for (char* c : p) out.values.emplace_back(c != nullptr ? c : "");
    H5Dvlen_reclaim(t, s, H5P_DEFAULT, p.data());
  } else {
    const std::size_t width = H5Tget_size(t);
    std::vector<char> buf(width * n + 1, '\0');
    REQUIRE(H5Aread(a, t, buf.data()) >= 0);
    for (std::size_t i = 0; i < n; ++i) out.values.emplace_back(std::string(&buf[i * width], width).c_str());
  }
  return out;
}

inline std::string text(hid_t f, const std::string& obj, const std::string& name) {
  const auto a = string_attribute(f, obj, name);
  REQUIRE(a.values.size() == 1);
  return a.values[0];
}

inline std::int64_t integer(hid_t f, const std::string& obj, const std::string& name) {
  H a(H5Aopen_by_name(f, obj.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  H t(H5Aget_type(a), H5Tclose);
  REQUIRE(H5Tget_class(t) == H5T_INTEGER);
  std::int64_t v = 0;
  REQUIRE(H5Aread(a, H5T_NATIVE_INT64, &v) >= 0);
  return v;
}

inline double number(hid_t f, const std::string& obj, const std::string& name) {
  H a(H5Aopen_by_name(f, obj.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  H t(H5Aget_type(a), H5Tclose);
  REQUIRE(H5Tget_class(t) == H5T_FLOAT);
  double v = 0;
  REQUIRE(H5Aread(a, H5T_NATIVE_DOUBLE, &v) >= 0);
  return v;
}

inline H5O_info_t object_info(hid_t f, const std::string& p) {
  H5O_info_t info{};
  REQUIRE(H5Oget_info_by_name2(f, p.c_str(), &info, H5O_INFO_BASIC, H5P_DEFAULT) >= 0);
  return info;
}

/// Number of samples in a trajectory file (rows of orientation/value).
inline std::size_t sample_count(hid_t f) { return static_cast<std::size_t>(dims(f, "/particles/body/orientation/value")[0]); }

/// Checks that rows [0, n) hold sample(i) for every series of the full layout.
inline void check_values(hid_t f, std::size_t n) {
  const auto step = int64s(f, "/particles/body/orientation/step");
  const auto time = doubles(f, "/particles/body/orientation/time");
  const auto q = doubles(f, "/particles/body/orientation/value");
  const auto pi = doubles(f, "/particles/body/angular_momentum_body/value");
  const auto om = doubles(f, "/particles/body/angular_velocity_body/value");
  const auto eu = doubles(f, "/particles/body/euler_zxz/value");
  const auto en = doubles(f, "/observables/energy/value");
  const auto ms = doubles(f, "/observables/angular_momentum_space/value");
  const auto c0 = doubles(f, "/observables/casimir_vertical_momentum/value");
  const auto c1 = doubles(f, "/observables/kovalevskaya_k/value");
  const auto oe = doubles(f, "/observables/orthogonality_error/value");
  REQUIRE(step.size() == n);
  REQUIRE(q.size() == 4 * n);
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const experiments::TrajectorySample s = sample(static_cast<std::int64_t>(i), 2);
    bool ok = step[i] == s.step && time[i] == s.time && en[i] == s.energy && oe[i] == s.orthogonality_error &&
              c0[i] == s.invariants[0] && c1[i] == s.invariants[1];
    for (std::size_t c = 0; c < 4; ++c) ok = ok && q[4 * i + c] == s.quaternion_wxyz[c];  // (w, x, y, z)
    for (std::size_t c = 0; c < 3; ++c) {
      const auto e = static_cast<Eigen::Index>(c);
      ok = ok && pi[3 * i + c] == s.angular_momentum_body[e] && om[3 * i + c] == s.angular_velocity_body[e] &&
           ms[3 * i + c] == s.angular_momentum_space[e] && eu[3 * i + c] == s.euler_zxz[c];
    }
    if (!ok) ++mismatches;
  }
  CHECK(mismatches == 0);
}

}  // namespace lgi::testing
