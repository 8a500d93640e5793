// TrajectoryWriter (experiments/io/h5md_writer.hpp): the H5MD layout of
// experiments/OUTPUT.md, read back with the HDF5 C API.
#include <catch2/catch.hpp>
#include <hdf5.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "experiments/io/h5md_writer.hpp"
#include "lgi/build_info.hpp"

namespace fs = std::filesystem;
using namespace lgi::experiments;

namespace {

// ---- scratch files --------------------------------------------------------------

std::string scratch(const std::string& name) {
  const fs::path dir = fs::path(LGI_TEST_TMPDIR) / "h5md_writer";
  fs::create_directories(dir);
  const fs::path p = dir / name;
  fs::remove(p);
  fs::remove(fs::path(p.string() + ".partial"));
  return p.string();
}

bool exists(const std::string& p) { return fs::exists(fs::symlink_status(p)); }

std::string slurp(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// ---- deterministic samples -----------------------------------------------------------

TrajectoryLayout full_layout() {
  TrajectoryLayout l;
  l.scalar_invariants = {{"casimir_vertical_momentum", "kg m+2 s-1"}, {"kovalevskaya_k", "s-4"}};
  l.space_momentum = true;
  l.euler_zxz = true;
  return l;
}

TrajectorySample sample(std::int64_t i, std::size_t invariant_count) {
  const double x = static_cast<double>(i);
  TrajectorySample s;
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

Provenance provenance() {
  Provenance p;
  p.text_attributes["scheme"] = "rkmk4";
  p.text_attributes["scene_toml"] = "[body]\ninertia = [1.0, 2.0, 3.0]\n# ünïcödé\n";
  p.text_attributes["command_line"] = "lgi simulate --scene x.toml --scheme rkmk4 --dt 0.001";
  p.number_attributes["dt"] = 1e-3;
  p.number_attributes["t_end"] = 10.0;
  p.integer_attributes["save_every"] = 10;
  return p;
}

Diagnostics diagnostics(const std::string& status) {
  Diagnostics d;
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

H open_file(const std::string& path) { return {H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose}; }
H open_dataset(hid_t f, const std::string& p) { return {H5Dopen2(f, p.c_str(), H5P_DEFAULT), H5Dclose}; }

bool has_link(hid_t f, const std::string& p) { return H5Lexists(f, p.c_str(), H5P_DEFAULT) > 0; }
bool has_attribute(hid_t f, const std::string& obj, const std::string& name) {
  return H5Aexists_by_name(f, obj.c_str(), name.c_str(), H5P_DEFAULT) > 0;
}

std::vector<hsize_t> dims(hid_t f, const std::string& p, std::vector<hsize_t>* maxdims = nullptr) {
  H d = open_dataset(f, p);
  H s(H5Dget_space(d), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(s);
  REQUIRE(rank >= 1);
  std::vector<hsize_t> out(static_cast<std::size_t>(rank)), mx(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(s, out.data(), mx.data());
  if (maxdims != nullptr) *maxdims = mx;
  return out;
}

bool chunked(hid_t f, const std::string& p) {
  H d = open_dataset(f, p);
  H dcpl(H5Dget_create_plist(d), H5Pclose);
  return H5Pget_layout(dcpl) == H5D_CHUNKED;
}

/// Class and size of a dataset's file type.
std::pair<H5T_class_t, std::size_t> type_of(hid_t f, const std::string& p) {
  H d = open_dataset(f, p);
  H t(H5Dget_type(d), H5Tclose);
  return {H5Tget_class(t), H5Tget_size(t)};
}

template <class T>
std::vector<T> read_all(hid_t f, const std::string& p, hid_t memory_type) {
  H d = open_dataset(f, p);
  H s(H5Dget_space(d), H5Sclose);
  const auto n = static_cast<std::size_t>(H5Sget_simple_extent_npoints(s));
  std::vector<T> out(n);
  REQUIRE(H5Dread(d, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) >= 0);
  return out;
}
std::vector<double> doubles(hid_t f, const std::string& p) { return read_all<double>(f, p, H5T_NATIVE_DOUBLE); }
std::vector<std::int64_t> int64s(hid_t f, const std::string& p) {
  return read_all<std::int64_t>(f, p, H5T_NATIVE_INT64);
}

struct StringAttribute {
  std::vector<std::string> values;
  bool variable = false;
  bool utf8 = false;
  bool scalar = false;
};

StringAttribute string_attribute(hid_t f, const std::string& obj, const std::string& name) {
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

std::string text(hid_t f, const std::string& obj, const std::string& name) {
  const auto a = string_attribute(f, obj, name);
  REQUIRE(a.values.size() == 1);
  return a.values[0];
}

std::int64_t integer(hid_t f, const std::string& obj, const std::string& name) {
  H a(H5Aopen_by_name(f, obj.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  H t(H5Aget_type(a), H5Tclose);
  REQUIRE(H5Tget_class(t) == H5T_INTEGER);
  std::int64_t v = 0;
  REQUIRE(H5Aread(a, H5T_NATIVE_INT64, &v) >= 0);
  return v;
}

double number(hid_t f, const std::string& obj, const std::string& name) {
  H a(H5Aopen_by_name(f, obj.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  H t(H5Aget_type(a), H5Tclose);
  REQUIRE(H5Tget_class(t) == H5T_FLOAT);
  double v = 0;
  REQUIRE(H5Aread(a, H5T_NATIVE_DOUBLE, &v) >= 0);
  return v;
}

H5O_info_t object_info(hid_t f, const std::string& p) {
  H5O_info_t info{};
  REQUIRE(H5Oget_info_by_name2(f, p.c_str(), &info, H5O_INFO_BASIC, H5P_DEFAULT) >= 0);
  return info;
}

/// Number of samples in a trajectory file (rows of orientation/value).
std::size_t sample_count(hid_t f) { return static_cast<std::size_t>(dims(f, "/particles/body/orientation/value")[0]); }

/// Checks that rows [0, n) hold sample(i) for every series of the full layout.
void check_values(hid_t f, std::size_t n) {
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
    const TrajectorySample s = sample(static_cast<std::int64_t>(i), 2);
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

}  // namespace

TEST_CASE("trajectory file: H5MD layout, shapes, units, links, values", "[h5md]") {
  const std::string path = scratch("layout.h5");
  const std::size_t n = 10000;
  {
    TrajectoryWriter w(path, false, full_layout(), provenance());
    CHECK(w.partial_path() == path + ".partial");
    CHECK(exists(path + ".partial"));
    CHECK_FALSE(exists(path));
    for (std::size_t i = 0; i < n; ++i) w.append(sample(static_cast<std::int64_t>(i), 2));
    CHECK(w.samples() == static_cast<std::int64_t>(n));
    CHECK(exists(path + ".partial"));
    CHECK_FALSE(exists(path));
    w.finish(diagnostics("ok"));
  }
  CHECK(exists(path));
  CHECK_FALSE(exists(path + ".partial"));

  H f = open_file(path);

  SECTION("/h5md metadata") {
    H a(H5Aopen_by_name(f, "/h5md", "version", H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
    H t(H5Aget_type(a), H5Tclose);
    H s(H5Aget_space(a), H5Sclose);
    CHECK(H5Tget_class(t) == H5T_INTEGER);
    CHECK(H5Tget_size(t) == 4);
    CHECK(H5Sget_simple_extent_npoints(s) == 2);
    std::int32_t v[2] = {0, 0};
    REQUIRE(H5Aread(a, H5T_NATIVE_INT32, v) >= 0);
    CHECK(v[0] == 1);
    CHECK(v[1] == 1);

    const auto author = string_attribute(f, "/h5md/author", "name");
    CHECK_FALSE(author.variable);  // H5MD 1.1: fixed-length strings
    CHECK(author.scalar);
    REQUIRE(author.values.size() == 1);
    const char* user = std::getenv("USER");
    CHECK(author.values[0] == (user != nullptr && *user != '\0' ? std::string(user) : author.values[0]));
    CHECK_FALSE(author.values[0].empty());
    const auto creator = string_attribute(f, "/h5md/creator", "name");
    CHECK_FALSE(creator.variable);
    CHECK(creator.values == std::vector<std::string>{"lgi"});
    CHECK(text(f, "/h5md/creator", "version") == lgi::build_info::version);

    // The units module that the `unit` attributes follow.
    H u(H5Aopen_by_name(f, "/h5md/modules/units", "version", H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
    std::int32_t uv[2] = {0, 0};
    REQUIRE(H5Aread(u, H5T_NATIVE_INT32, uv) >= 0);
    CHECK(uv[0] == 1);
    CHECK(uv[1] == 0);
    CHECK(text(f, "/h5md/modules/units", "system") == "SI");
  }

  SECTION("box") {
    CHECK(integer(f, "/particles/body/box", "dimension") == 3);
    const auto b = string_attribute(f, "/particles/body/box", "boundary");
    CHECK_FALSE(b.variable);
    CHECK_FALSE(b.scalar);
    CHECK(b.values == std::vector<std::string>{"none", "none", "none"});
  }

  SECTION("datasets: shapes, types, chunked and extendible") {
    const std::vector<std::pair<std::string, std::vector<hsize_t>>> values = {
        {"/particles/body/orientation/value", {n, 1, 4}},
        {"/particles/body/angular_momentum_body/value", {n, 1, 3}},
        {"/particles/body/angular_velocity_body/value", {n, 1, 3}},
        {"/particles/body/euler_zxz/value", {n, 1, 3}},
        {"/observables/energy/value", {n}},
        {"/observables/angular_momentum_space/value", {n, 3}},
        {"/observables/casimir_vertical_momentum/value", {n}},
        {"/observables/kovalevskaya_k/value", {n}},
        {"/observables/orthogonality_error/value", {n}},
        {"/particles/body/orientation/time", {n}},
        {"/particles/body/orientation/step", {n}},
    };
    for (const auto& [p, shape] : values) {
      INFO(p);
      std::vector<hsize_t> mx;
      CHECK(dims(f, p, &mx) == shape);
      REQUIRE(mx.size() == shape.size());
      CHECK(mx[0] == H5S_UNLIMITED);
      for (std::size_t k = 1; k < mx.size(); ++k) CHECK(mx[k] == shape[k]);
      CHECK(chunked(f, p));
      const auto [cls, size] = type_of(f, p);
      CHECK(cls == (p.ends_with("/step") ? H5T_INTEGER : H5T_FLOAT));
      CHECK(size == 8);
    }
  }

  SECTION("step and time are hard links to orientation's") {
    const std::vector<std::string> groups = {
        "/particles/body/angular_momentum_body", "/particles/body/angular_velocity_body",
        "/particles/body/euler_zxz",             "/observables/energy",
        "/observables/angular_momentum_space",   "/observables/casimir_vertical_momentum",
        "/observables/kovalevskaya_k",           "/observables/orthogonality_error"};
    for (const char* leaf : {"step", "time"}) {
      const H5O_info_t ref = object_info(f, std::string("/particles/body/orientation/") + leaf);
      CHECK(ref.rc == groups.size() + 1);  // one object, nine names
      for (const auto& g : groups) {
        const std::string p = g + "/" + leaf;
        INFO(p);
        H5L_info_t li{};
        REQUIRE(H5Lget_info(f, p.c_str(), &li, H5P_DEFAULT) >= 0);
        CHECK(li.type == H5L_TYPE_HARD);
        CHECK(object_info(f, p).addr == ref.addr);
      }
    }
  }

  SECTION("units") {
    const std::vector<std::pair<std::string, std::string>> units = {
        {"/particles/body/orientation/time", "s"},
        {"/particles/body/angular_momentum_body/value", "kg m+2 s-1"},
        {"/particles/body/angular_velocity_body/value", "s-1"},
        {"/particles/body/euler_zxz/value", "rad"},
        {"/observables/energy/value", "kg m+2 s-2"},
        {"/observables/angular_momentum_space/value", "kg m+2 s-1"},
        {"/observables/casimir_vertical_momentum/value", "kg m+2 s-1"},
        {"/observables/kovalevskaya_k/value", "s-4"},
    };
    for (const auto& [p, u] : units) {
      INFO(p);
      const auto a = string_attribute(f, p, "unit");
      CHECK(a.variable);
      CHECK(a.scalar);
      CHECK(a.values == std::vector<std::string>{u});
    }
    // Dimensionless series carry no unit attribute.
    CHECK_FALSE(has_attribute(f, "/particles/body/orientation/value", "unit"));
    CHECK_FALSE(has_attribute(f, "/observables/orthogonality_error/value", "unit"));
    CHECK_FALSE(has_attribute(f, "/particles/body/orientation/step", "unit"));
  }

  SECTION("values round-trip exactly") { check_values(f, n); }

  SECTION("/parameters") {
    const auto scene = string_attribute(f, "/parameters", "scene_toml");
    CHECK(scene.variable);
    CHECK(scene.utf8);
    CHECK(scene.values[0] == provenance().text_attributes["scene_toml"]);
    CHECK(text(f, "/parameters", "scheme") == "rkmk4");
    CHECK(text(f, "/parameters", "command_line") == provenance().text_attributes["command_line"]);
    CHECK(number(f, "/parameters", "dt") == 1e-3);
    CHECK(number(f, "/parameters", "t_end") == 10.0);
    CHECK(integer(f, "/parameters", "save_every") == 10);
    // Filled in by the writer.
    CHECK(text(f, "/parameters", "compiler") == lgi::build_info::compiler);
    CHECK(text(f, "/parameters", "cxx_flags") == lgi::build_info::cxx_flags);
    CHECK(text(f, "/parameters", "build_type") == lgi::build_info::build_type);
    CHECK(text(f, "/parameters", "hdf5_version") == hdf5_library_version());
    CHECK(hdf5_library_version().starts_with("1.10."));
    const std::string utc = text(f, "/parameters", "utc_start");
    CHECK(utc.size() == 20);
    CHECK(utc.ends_with("Z"));
  }

  SECTION("/diagnostics") {
    CHECK(integer(f, "/diagnostics", "steps") == 99990);
    CHECK(integer(f, "/diagnostics", "rejected_steps") == 3);
    CHECK(integer(f, "/diagnostics", "rhs_evaluations") == 399960);
    CHECK(integer(f, "/diagnostics", "newton_iterations_max") == 7);
    CHECK(integer(f, "/diagnostics", "newton_failures") == 1);
    CHECK(number(f, "/diagnostics", "cpu_seconds") == 1.25);
    const auto status = string_attribute(f, "/diagnostics", "status");
    CHECK(status.variable);
    CHECK(status.values == std::vector<std::string>{"ok"});
  }
}

TEST_CASE("trajectory file: minimal layout has only the mandatory series", "[h5md]") {
  const std::string path = scratch("minimal.h5");
  {
    TrajectoryWriter w(path, false, TrajectoryLayout{}, Provenance{});
    for (std::int64_t i = 0; i < 3; ++i) w.append(sample(i, 0));
    w.finish(diagnostics("ok"));
  }
  H f = open_file(path);
  CHECK(sample_count(f) == 3);
  CHECK(has_link(f, "/observables/energy/value"));
  CHECK(has_link(f, "/observables/orthogonality_error/value"));
  CHECK_FALSE(has_link(f, "/observables/angular_momentum_space"));
  CHECK_FALSE(has_link(f, "/particles/body/euler_zxz"));
  CHECK(object_info(f, "/particles/body/orientation/step").rc == 5);
  CHECK(int64s(f, "/observables/energy/step") == std::vector<std::int64_t>{0, 10, 20});
}

TEST_CASE("trajectory file: refuses to overwrite without force", "[h5md]") {
  const std::string path = scratch("existing.h5");
  { std::ofstream(path) << "precious"; }
  try {
    TrajectoryWriter w(path, false, full_layout(), provenance());
    FAIL("no exception");
  } catch (const OutputFileError& e) {
    const std::string msg = e.what();
    CHECK(msg.find(path) != std::string::npos);
    CHECK(msg.find('\n') == std::string::npos);
    CHECK(msg.find("exists") != std::string::npos);
  }
  CHECK(slurp(path) == "precious");
  CHECK_FALSE(exists(path + ".partial"));
}

TEST_CASE("trajectory file: force replaces the old file only on success", "[h5md]") {
  const std::string path = scratch("forced.h5");
  { std::ofstream(path) << "old"; }
  SECTION("finish replaces") {
    TrajectoryWriter w(path, true, full_layout(), provenance());
    for (std::int64_t i = 0; i < 100; ++i) w.append(sample(i, 2));
    w.flush();
    CHECK(slurp(path) == "old");  // untouched during the run
    w.finish(diagnostics("ok"));
    CHECK_FALSE(exists(path + ".partial"));
    H f = open_file(path);
    CHECK(sample_count(f) == 100);
    check_values(f, 100);
  }
  SECTION("abandon keeps the old file") {
    {
      TrajectoryWriter w(path, true, full_layout(), provenance());
      for (std::int64_t i = 0; i < 100; ++i) w.append(sample(i, 2));
      w.abandon(diagnostics("non-finite state at t = 0.099"));
    }
    CHECK(slurp(path) == "old");
    CHECK(exists(path + ".partial"));
  }
}

TEST_CASE("trajectory file: abandon leaves a readable .partial with every sample and the reason", "[h5md]") {
  const std::string path = scratch("abandoned.h5");
  const std::size_t n = 5000;  // one full block of 4096 flushed, 904 still buffered at abandon
  {
    TrajectoryWriter w(path, false, full_layout(), provenance());
    for (std::size_t i = 0; i < n; ++i) w.append(sample(static_cast<std::int64_t>(i), 2));
    w.abandon(diagnostics("implicit solve did not converge at t = 4.999"));
    w.abandon(diagnostics("again"));  // no-op once closed
    CHECK_THROWS_AS(w.append(sample(static_cast<std::int64_t>(n), 2)), std::logic_error);
    CHECK_THROWS_AS(w.finish(diagnostics("ok")), std::logic_error);
  }
  CHECK_FALSE(exists(path));
  REQUIRE(exists(path + ".partial"));
  H f = open_file(path + ".partial");
  CHECK(sample_count(f) == n);
  check_values(f, n);
  CHECK(text(f, "/diagnostics", "status") == "implicit solve did not converge at t = 4.999");
  CHECK(integer(f, "/diagnostics", "steps") == 99990);
  CHECK(number(f, "/diagnostics", "cpu_seconds") == 1.25);
}

TEST_CASE("trajectory file: a writer destroyed by an exception records \"interrupted\"", "[h5md]") {
  const std::string path = scratch("interrupted.h5");
  try {
    TrajectoryWriter w(path, false, full_layout(), provenance());
    for (std::int64_t i = 0; i < 300; ++i) w.append(sample(i, 2));
    throw std::runtime_error("scheme blew up");
  } catch (const std::runtime_error&) {
  }
  CHECK_FALSE(exists(path));
  REQUIRE(exists(path + ".partial"));
  H f = open_file(path + ".partial");
  CHECK(sample_count(f) == 300);
  check_values(f, 300);
  CHECK(text(f, "/diagnostics", "status") == "interrupted");
  CHECK(integer(f, "/diagnostics", "steps") == -1);  // not known
  CHECK(std::isnan(number(f, "/diagnostics", "cpu_seconds")));
}

TEST_CASE("trajectory file: missing or unwritable directory gives a one-line error naming the path", "[h5md]") {
  SECTION("missing directory") {
    const std::string path = std::string(LGI_TEST_TMPDIR) + "/h5md_writer/no/such/dir/out.h5";
    try {
      TrajectoryWriter w(path, false, full_layout(), provenance());
      FAIL("no exception");
    } catch (const OutputFileError& e) {
      const std::string msg = e.what();
      INFO(msg);
      CHECK(msg.find(path) != std::string::npos);
      CHECK(msg.find('\n') == std::string::npos);
      CHECK(msg.find("No such file or directory") != std::string::npos);
    }
  }
  SECTION("read-only directory") {
    const fs::path dir = fs::path(LGI_TEST_TMPDIR) / "h5md_writer" / "readonly";
    fs::create_directories(dir);
    fs::permissions(dir, fs::perms::owner_read | fs::perms::owner_exec);
    // root ignores directory permissions; /proc refuses new files even to root.
    const std::string path = geteuid() == 0 ? "/proc/lgi_h5md_writer_test.h5" : (dir / "out.h5").string();
    try {
      TrajectoryWriter w(path, false, full_layout(), provenance());
      FAIL("no exception");
    } catch (const OutputFileError& e) {
      const std::string msg = e.what();
      INFO(msg);
      CHECK(msg.find(path) != std::string::npos);
      CHECK(msg.find('\n') == std::string::npos);
    }
    CHECK_FALSE(exists(path + ".partial"));
    fs::permissions(dir, fs::perms::owner_all);
  }
}

TEST_CASE("trajectory file: invalid layouts and samples are rejected", "[h5md]") {
  const std::string path = scratch("invalid.h5");
  TrajectoryLayout too_many;
  for (int k = 0; k < 9; ++k) too_many.scalar_invariants.push_back({"inv" + std::to_string(k), ""});
  CHECK_THROWS_AS(TrajectoryWriter(path, false, too_many, Provenance{}), std::invalid_argument);
  TrajectoryLayout dup;
  dup.scalar_invariants = {{"a", ""}, {"a", ""}};
  CHECK_THROWS_AS(TrajectoryWriter(path, false, dup, Provenance{}), std::invalid_argument);
  TrajectoryLayout reserved;
  reserved.scalar_invariants = {{"energy", ""}};
  CHECK_THROWS_AS(TrajectoryWriter(path, false, reserved, Provenance{}), std::invalid_argument);
  TrajectoryLayout slash;
  slash.scalar_invariants = {{"a/b", ""}};
  CHECK_THROWS_AS(TrajectoryWriter(path, false, slash, Provenance{}), std::invalid_argument);
  CHECK_FALSE(exists(path + ".partial"));

  TrajectoryWriter w(path, false, full_layout(), provenance());
  CHECK_THROWS_AS(w.append(sample(0, 1)), std::invalid_argument);  // wrong invariant count
  w.append(sample(1, 2));
  CHECK_THROWS_AS(w.append(sample(1, 2)), std::invalid_argument);  // step does not increase
  CHECK_THROWS_AS(w.append(sample(0, 2)), std::invalid_argument);
  w.append(sample(2, 2));
  w.finish(diagnostics("ok"));
  H f = open_file(path);
  CHECK(int64s(f, "/particles/body/orientation/step") == std::vector<std::int64_t>{10, 20});
}

namespace {

/// Runs a writer in a child process that kills itself (SIGKILL, no cleanup)
/// after `before` appends, a pause, and `after` more; returns the child's status.
int killed_child(const std::string& path, const WriterOptions& options, std::int64_t before,
                 std::chrono::milliseconds pause, std::int64_t after) {
  std::cout.flush();
  std::cerr.flush();
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    try {
      TrajectoryWriter w(path, false, full_layout(), provenance(), options);
      std::int64_t i = 0;
      for (; i < before; ++i) w.append(sample(i, 2));
      std::this_thread::sleep_for(pause);
      for (; i < before + after; ++i) w.append(sample(i, 2));
      ::kill(::getpid(), SIGKILL);
    } catch (...) {
    }
    ::_exit(3);
  }
  int status = 0;
  REQUIRE(::waitpid(pid, &status, 0) == pid);
  return status;
}

}  // namespace

TEST_CASE("trajectory file: a killed run leaves a readable .partial with every flushed block", "[h5md]") {
  const std::string path = scratch("killed.h5");
  SECTION("blocks flushed when full") {
    WriterOptions o;
    o.block_size = 512;
    o.flush_interval_seconds = 1e9;
    const int status = killed_child(path, o, 1100, std::chrono::milliseconds(0), 0);
    REQUIRE(WIFSIGNALED(status));
    CHECK(WTERMSIG(status) == SIGKILL);
  }
  SECTION("buffer flushed by the wall clock") {
    WriterOptions o;
    o.block_size = 1u << 20;
    o.flush_interval_seconds = 0.05;
    // The clock is read every 256 appends: at 1024, 0.1 s after the last flush.
    const int status = killed_child(path, o, 1000, std::chrono::milliseconds(100), 280);
    REQUIRE(WIFSIGNALED(status));
  }
  CHECK_FALSE(exists(path));
  REQUIRE(exists(path + ".partial"));
  H f = open_file(path + ".partial");  // no h5clear needed
  CHECK(sample_count(f) == 1024);
  check_values(f, 1024);
  CHECK(text(f, "/diagnostics", "status") == "running");
  CHECK(text(f, "/parameters", "scheme") == "rkmk4");
}

TEST_CASE("trajectory file: cost per append, 1e6 samples", "[h5md][slow]") {
  const std::string path = scratch("large.h5");
  const std::int64_t n = 1000000;
  std::vector<TrajectorySample> samples;
  samples.reserve(1000);
  for (std::int64_t i = 0; i < 1000; ++i) samples.push_back(sample(i, 2));
  const auto t0 = std::chrono::steady_clock::now();
  TrajectoryWriter w(path, false, full_layout(), provenance());
  for (std::int64_t i = 0; i < n; ++i) {
    TrajectorySample s = samples[static_cast<std::size_t>(i % 1000)];
    s.step = i;
    s.time = static_cast<double>(i);
    w.append(s);
  }
  w.finish(diagnostics("ok"));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double bytes = static_cast<double>(fs::file_size(path));
  std::cout << "h5md writer: " << n << " samples in " << seconds << " s, " << 1e9 * seconds / static_cast<double>(n)
            << " ns per append (file " << bytes / 1e6 << " MB)\n";
  H f = open_file(path);
  CHECK(sample_count(f) == static_cast<std::size_t>(n));
  const auto step = int64s(f, "/observables/energy/step");
  CHECK(step.back() == n - 1);
  fs::remove(path);
}
