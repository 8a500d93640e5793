// TrajectoryWriter (experiments/io/h5md_writer.hpp): the life cycle of a
// trajectory file: no overwrite without force, force replacing the old file
// only on success, the .partial left by an abandoned, interrupted or killed
// run, one-line errors for bad paths, layouts and samples, and the cost per
// append.
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
#include "support/h5md_trajectory.hpp"

namespace test_h5md_writer_lifecycle {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

namespace fs = std::filesystem;
using namespace lgi::experiments;
using namespace lgi::testing;

namespace {

/// The OutputFileError message of creating a trajectory file at `path`; the test fails if none is thrown.
std::string creation_error(const std::string& path) {
  try {
    TrajectoryWriter w(path, false, full_layout(), provenance());
  } catch (const OutputFileError& e) {
    return e.what();
  }
  FAIL("no exception");
  return {};
}

}  // namespace

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
    const std::string msg = creation_error(path);
    INFO(msg);
    CHECK(msg.find(path) != std::string::npos);
    CHECK(msg.find('\n') == std::string::npos);
    CHECK(msg.find("No such file or directory") != std::string::npos);
  }
  SECTION("read-only directory") {
    const fs::path dir = fs::path(LGI_TEST_TMPDIR) / "h5md_writer" / "readonly";
    fs::create_directories(dir);
    fs::permissions(dir, fs::perms::owner_read | fs::perms::owner_exec);
    // root ignores directory permissions; /proc refuses new files even to root.
    const std::string path = geteuid() == 0 ? "/proc/lgi_h5md_writer_test.h5" : (dir / "out.h5").string();
    const std::string msg = creation_error(path);
    INFO(msg);
    CHECK(msg.find(path) != std::string::npos);
    CHECK(msg.find('\n') == std::string::npos);
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
  CHECK_THROWS_AS(w.append(sample(1, 2)), std::invalid_argument);  // neither step nor time increases
  CHECK_THROWS_AS(w.append(sample(0, 2)), std::invalid_argument);
  w.append(sample(2, 2));
  auto inside = sample(2, 2);  // an output time interpolated inside the same step (lgi simulate --output-dt)
  inside.time += 1e-4;
  w.append(inside);
  CHECK_THROWS_AS(w.append(inside), std::invalid_argument);  // the same step needs a later time
  w.finish(diagnostics("ok"));
  H f = open_file(path);
  CHECK(int64s(f, "/particles/body/orientation/step") == std::vector<std::int64_t>{10, 20, 20});
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

}  // namespace test_h5md_writer_lifecycle
