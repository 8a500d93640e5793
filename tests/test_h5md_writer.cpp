// TrajectoryWriter (experiments/io/h5md_writer.hpp): the H5MD layout of
// experiments/OUTPUT.md, read back with the HDF5 C API: the full layout
// (shapes, units, links, attributes, values) and the minimal one.
// The file's life cycle and failures: test_h5md_writer_lifecycle.cpp.
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
#include "experiments/io/output_timing.hpp"
#include "lgi/build_info.hpp"
#include "support/h5md_trajectory.hpp"

namespace test_h5md_writer {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

namespace fs = std::filesystem;
using namespace lgi::experiments;
using namespace lgi::testing;


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

namespace {
/// An observer whose samples take wall time but no CPU time, as a sample does
/// while the thread waits for a core on a loaded machine.
class WaitingObserver final : public lgi::integrators::Observer {
 public:
  void observe(std::int64_t, double, const lgi::system::State&) override {
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
  }
};

void burn_cpu(double seconds) {
  const double start = lgi::integrators::detail::cpu_now();
  volatile double x = 1.0;
  while (lgi::integrators::detail::cpu_now() - start < seconds) x = x * 1.0000001 + 1e-9;
}
}  // namespace

TEST_CASE("output time is charged in CPU seconds, so waiting for a core leaves the stepping time", "[h5md][cpu]") {
  WaitingObserver waiting;
  OutputTimingObserver timed(waiting);
  const double cpu0 = lgi::integrators::detail::cpu_now();
  const lgi::system::State s{};
  for (int k = 0; k < 3; ++k) {
    burn_cpu(0.01);  // the stepping: CPU time
    timed.observe(k, 0.0, s);
  }
  lgi::integrators::RunStats stats;
  stats.steps = 3;
  stats.cpu_seconds = lgi::integrators::detail::cpu_now() - cpu0;
  const double output = timed.output_cpu_seconds(stats.cpu_seconds);
  INFO("cpu " << stats.cpu_seconds << " output wall " << timed.output_wall_seconds() << " output cpu " << output);
  // 90 ms of waiting against about 30 ms of CPU: subtracting the wall time would leave no stepping time.
  CHECK(timed.output_wall_seconds() >= 0.09);
  CHECK(output >= 0.0);
  CHECK(output < timed.output_wall_seconds());
  const Diagnostics diag = diagnostics_of_run(stats, output);
  CHECK(diag.output_seconds == output);
  CHECK(diag.cpu_seconds > 0.0);
  CHECK(diag.cpu_seconds + output == Approx(stats.cpu_seconds).epsilon(1e-12));
}

}  // namespace test_h5md_writer
