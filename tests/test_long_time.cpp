// lgi long-time, run as a user would: log-spaced samples, window maxima that
// keep the spikes between samples, bounded energy error of a symplectic
// scheme against the drift of an explicit one, and Ctrl-C mid-run.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <fstream>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <thread>

#include "integrators/registry/registry.hpp"
#include "support/h5_read.hpp"
#include "support/run_command.hpp"

extern char** environ;  // POSIX's, at global scope (not in this file's namespace)

namespace test_long_time {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

namespace fs = std::filesystem;
using namespace lgi::testing;

namespace {

const std::string scenes = LGI_SCENES_DIR;

/// Largest value of `v` over the rows whose step lies in (lo, hi].
double max_over(const std::vector<double>& v, const std::vector<double>& step, double lo, double hi) {
  double m = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i)
    if (step[i] > lo && step[i] <= hi) m = std::max(m, v[i]);
  return m;
}

}  // namespace

TEST_CASE("long-time: log-spaced samples and window maxima", "[long-time]") {
  const std::string dir = scratch_dir("lt_samples");
  const std::string out = dir + "/lt.h5";
  const auto r = run_lgi("long-time --scene " + scenes +
                         "/free_body_hlw.toml --scheme rkmk4 --dt 0.1 --t-end 10000 --samples 10 --out " + out);
  INFO(r.out << r.err);
  REQUIRE(r.status == 0);
  REQUIRE(fs::exists(out));
  REQUIRE(fs::exists(dir + "/lt.csv"));
  CHECK(read_string_attribute(out, "/diagnostics", "status") == "ok");
  CHECK(read_string_attribute(out, "/parameters", "scheme") == "rkmk4");
  CHECK(read_double_attribute(out, "/diagnostics", "steps") == 100000);

  const auto step = read_dataset(out, "/series/step").data;
  const auto time = read_dataset(out, "/series/time").data;
  REQUIRE(step.size() >= 45);
  CHECK(step.size() <= 60);  // about 10 per decade over 5 decades, plus step 0
  CHECK(step.front() == 0);
  CHECK(step[1] == 1);
  CHECK(step.back() == 100000);
  CHECK(time.back() == Approx(10000.0));
  for (std::size_t i = 1; i < step.size(); ++i) {
    CHECK(step[i] > step[i - 1]);
    if (step[i - 1] >= 100) CHECK(step[i] / step[i - 1] < 1.35);  // log-spaced: 10^(1/10) = 1.26
  }
  // Samples per decade.
  for (double lo : {1e2, 1e3, 1e4}) {
    int n = 0;
    for (double s : step) n += s > lo && s <= 10 * lo;
    CHECK(n >= 9);
    CHECK(n <= 11);
  }
  // Every window maximum is at least the sample it ends on, and the free
  // body's invariants are all there.
  for (const std::string c : {"energy_error", "angular_momentum_norm_error", "angular_momentum_space_error",
                              "orthogonality_error"}) {
    const auto v = read_dataset(out, "/series/" + c).data;
    const auto w = read_dataset(out, "/series/" + c + "_window_max").data;
    REQUIRE(v.size() == step.size());
    REQUIRE(w.size() == step.size());
    for (std::size_t i = 0; i < v.size(); ++i) CHECK(w[i] >= v[i]);
  }
  // rkmk4 is not symplectic: its energy error drifts (grows from decade to decade).
  const auto energy = read_dataset(out, "/series/energy_error_window_max").data;
  const double early = max_over(energy, step, 1e2, 1e3);
  const double late = max_over(energy, step, 1e4, 1e5);
  CHECK(early > 0.0);
  CHECK(late > 5.0 * early);
  CHECK(r.out.find("steps=100000") != std::string::npos);
}

TEST_CASE("long-time: lgvi's energy error stays bounded where rkmk4 drifts", "[long-time]") {
  const auto* lgvi = lgi::integrators::find_scheme("lgvi");
  const std::string dir = scratch_dir("lt_energy");
  const std::string scene = " --scene " + scenes + "/heavy_top_trindade_1.toml --dt 2e-3 --t-end 200 --samples 10 ";
  const auto rk = run_lgi("long-time" + scene + "--scheme rkmk4 --quiet --out " + dir + "/rk.h5");
  REQUIRE(rk.status == 0);
  const auto step_rk = read_dataset(dir + "/rk.h5", "/series/step").data;
  const auto e_rk = read_dataset(dir + "/rk.h5", "/series/energy_error_window_max").data;
  const double rk_early = max_over(e_rk, step_rk, 1e3, 1e4);
  const double rk_late = max_over(e_rk, step_rk, 1e4, 1e5);
  CHECK(rk_late > 3.0 * rk_early);  // drift
  if (lgvi == nullptr) {
    WARN("lgvi is not registered: only rkmk4's drift is checked");
    return;
  }
  const auto vi = run_lgi("long-time" + scene + "--scheme lgvi --quiet --out " + dir + "/vi.h5");
  INFO(vi.err);
  REQUIRE(vi.status == 0);
  const auto step = read_dataset(dir + "/vi.h5", "/series/step").data;
  const auto e = read_dataset(dir + "/vi.h5", "/series/energy_error_window_max").data;
  const auto casimir = read_dataset(dir + "/vi.h5", "/series/casimir_vertical_momentum_error_window_max").data;
  const double early = max_over(e, step, 1e3, 1e4);
  const double late = max_over(e, step, 1e4, 1e5);
  CHECK(early > 0.0);
  CHECK(late < 2.0 * early);  // bounded: no growth from one decade to the next
  CHECK(max_over(casimir, step, 0, 1e5) < 1e-10);
}

TEST_CASE("long-time: Ctrl-C keeps a readable .partial and exits 130", "[long-time]") {
  const std::string dir = scratch_dir("lt_sigint");
  const std::string out = dir + "/int.h5";
  const std::string err_file = dir + "/stderr.txt";
  // 1e9 steps: far longer than the test waits.
  std::vector<std::string> args = {LGI_EXECUTABLE, "long-time", "--scene", scenes + "/free_body_hlw.toml",
                                   "--scheme", "rkmk4", "--dt", "1e-3", "--t-end", "1e6", "--out", out};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = -1;
  REQUIRE(posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ) == 0);
  posix_spawn_file_actions_destroy(&actions);

  // Wait until the run has started (its .partial exists), then a little more.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (!fs::exists(out + ".partial") && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  std::this_thread::sleep_for(std::chrono::milliseconds(800));
  REQUIRE(::kill(pid, SIGINT) == 0);
  int raw = 0;
  REQUIRE(::waitpid(pid, &raw, 0) == pid);
  const std::string err = read_text(err_file);
  INFO(err);
  REQUIRE(WIFEXITED(raw));
  CHECK(WEXITSTATUS(raw) == 130);  // 128 + SIGINT (exit_status.hpp)
  CHECK_FALSE(fs::exists(out));
  REQUIRE(fs::exists(out + ".partial"));
  CHECK(fs::exists(dir + "/int.csv.partial"));
  CHECK(err.find("interrupted by signal") != std::string::npos);
  CHECK(err.find(out + ".partial") != std::string::npos);
  CHECK(line_count(err) == 1);

  const std::string partial = out + ".partial";
  CHECK(read_string_attribute(partial, "/diagnostics", "status") == "interrupted by signal");
  const auto step = read_dataset(partial, "/series/step").data;
  REQUIRE(step.size() >= 3);
  CHECK(step.front() == 0);
  for (std::size_t i = 1; i < step.size(); ++i) CHECK(step[i] > step[i - 1]);
  CHECK(step.back() < 1e9);
  CHECK(read_double_attribute(partial, "/diagnostics", "steps") == step.back());
  const auto v = read_dataset(partial, "/series/energy_error").data;
  const auto w = read_dataset(partial, "/series/energy_error_window_max").data;
  REQUIRE(v.size() == step.size());
  for (std::size_t i = 0; i < v.size(); ++i) CHECK(w[i] >= v[i]);
}

TEST_CASE("long-time refuses bad input with exit 2 and no file", "[long-time]") {
  const std::string dir = scratch_dir("lt_bad");
  // A scene without [run], so every setting must come from the command line.
  const std::string scene = scratch_dir("lt_bad_scene") + "/no_run.toml";
  std::ofstream(scene) << "name = \"no run\"\n[body]\ninertia = [1.0, 2.0, 3.0]\n"
                          "[initial]\nangular_velocity = [0.3, 0.8, -0.4]\n";
  const std::string base = "long-time --scene " + scene + " --out " + dir + "/bad.h5 ";
  for (const auto& [flags, named] : std::vector<std::pair<std::string, std::string>>{
           {"--scheme nonesuch --dt 0.1 --t-end 1", "--scheme"},
           {"--scheme rkmk4 --dt 0 --t-end 1", "--dt"},
           {"--scheme rkmk4 --t-end 1", "--dt"},
           {"--scheme rkmk4 --dt 0.1", "--t-end"},
           {"--scheme rkmk4 --dt 0.1 --t-end 1 --samples 0", "--samples"},
           {"--scheme rkmk-dp54 --t-end 1", "--tol"}}) {
    const auto r = run_lgi(base + flags);
    INFO(flags << " -> " << r.err);
    CHECK(r.status == 2);
    CHECK(r.err.find(named) != std::string::npos);
    CHECK(fs::is_empty(dir));
  }
}

}  // namespace test_long_time
