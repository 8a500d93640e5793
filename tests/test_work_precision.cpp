// lgi work-precision, run as a user would: orders seen in the error, the
// reference (exact for a free body, converged with an estimated error
// otherwise), the floor below which no error is reported, the CSV twin, and
// bad input refused with exit 2 and no file.
#include <catch2/catch.hpp>
#include <fstream>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "support/h5_read.hpp"
#include "support/run_command.hpp"

namespace test_work_precision {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

namespace fs = std::filesystem;
using namespace lgi::testing;

namespace {

const std::string scenes = LGI_SCENES_DIR;

/// Observed order between consecutive steps halved.
double slope(double e_coarse, double e_fine, double ratio) { return std::log(e_coarse / e_fine) / std::log(ratio); }

}  // namespace

TEST_CASE("work-precision on the free body: exact reference, orders 4 and 2", "[work-precision]") {
  const std::string dir = scratch_dir("wp_free");
  const std::string out = dir + "/wp.h5";
  const auto r = run_lgi("work-precision --scene " + scenes +
                         "/free_body_hlw.toml --schemes rkmk4,rkmk2 --dt 0.1,0.05,0.025 --t-end 10 --repeat 2 --out " +
                         out);
  INFO(r.out << r.err);
  REQUIRE(r.status == 0);
  REQUIRE(fs::exists(out));
  REQUIRE_FALSE(fs::exists(out + ".partial"));
  CHECK(read_string_attribute(out, "/reference", "kind") == "exact");
  // The conditioning floor of the exact flow (perturbed at round-off) on this well-conditioned body.
  CHECK(read_double_attribute(out, "/reference", "estimated_error") < 1e-12);
  CHECK(read_string_attribute(out, "/diagnostics", "status") == "ok");
  CHECK(read_string_attribute(out, "/parameters", "subcommand") == "work-precision");
  CHECK_FALSE(read_string_attribute(out, "/parameters", "scene_toml").empty());
  CHECK_FALSE(read_string_attribute(out, "/h5md/creator", "version").empty());

  const auto scheme = read_string_dataset(out, "/results/scheme");
  const auto status = read_string_dataset(out, "/results/status");
  const auto dt = read_dataset(out, "/results/dt").data;
  const auto tol = read_dataset(out, "/results/tol").data;
  const auto error = read_dataset(out, "/results/error").data;
  const auto att = read_dataset(out, "/results/error_attitude").data;
  const auto mom = read_dataset(out, "/results/error_momentum").data;
  const auto steps = read_dataset(out, "/results/steps").data;
  const auto rhs = read_dataset(out, "/results/rhs_evaluations").data;
  const auto cpu_min = read_dataset(out, "/results/cpu_seconds_min").data;
  const auto cpu_median = read_dataset(out, "/results/cpu_seconds_median").data;
  const auto repeats = read_dataset(out, "/results/repeats").data;
  const auto runs = read_dataset(out, "/results/runs_per_repeat").data;
  const auto floor = read_dataset(out, "/results/below_reference_floor").data;
  const auto energy = read_dataset(out, "/results/error_energy").data;
  const auto space = read_dataset(out, "/results/error_angular_momentum_space").data;
  REQUIRE(scheme.size() == 6);
  REQUIRE(error.size() == 6);
  for (std::size_t i = 0; i < 6; ++i) {
    CHECK(scheme[i] == (i < 3 ? "rkmk4" : "rkmk2"));
    CHECK(status[i] == "ok");
    CHECK(std::isnan(tol[i]));
    CHECK(error[i] == std::max(att[i], mom[i]));
    CHECK(floor[i] == 0);
    CHECK(repeats[i] == 2);
    CHECK(runs[i] >= 1);
    CHECK(cpu_min[i] > 0.0);
    CHECK(cpu_min[i] <= cpu_median[i]);
    CHECK(steps[i] == std::round(10.0 / dt[i]));
    CHECK(rhs[i] == (i < 3 ? 4 : 2) * steps[i]);
    CHECK(std::isfinite(energy[i]));
    CHECK(std::isfinite(space[i]));
  }
  // A repeat of these runs of 100 steps (microseconds each) is a batch of
  // several back-to-back runs, timed once: the clock's system call is not
  // counted into each short run.
  CHECK(runs[0] > 1);
  CHECK(slope(error[0], error[1], 2.0) == Approx(4.0).margin(0.4));
  CHECK(slope(error[1], error[2], 2.0) == Approx(4.0).margin(0.4));
  CHECK(slope(error[3], error[4], 2.0) == Approx(2.0).margin(0.3));
  CHECK(slope(error[4], error[5], 2.0) == Approx(2.0).margin(0.3));

  // The CSV twin: header and one line per row, same table.
  const std::string csv = dir + "/wp.csv";
  REQUIRE(fs::exists(csv));
  const auto lines = split_lines(read_text(csv));
  REQUIRE(lines.size() == 7);
  CHECK(lines[0].rfind("scheme,dt,tol,steps,rejected_steps,rhs_evaluations,error_attitude,error_momentum,error,", 0) ==
        0);
  CHECK(lines[0].find("cpu_seconds_min,cpu_seconds_median,repeats,status,below_reference_floor") !=
        std::string::npos);
  CHECK(lines[1].rfind("rkmk4,0.1,nan,100,", 0) == 0);
  CHECK(lines[6].rfind("rkmk2,0.025,nan,400,", 0) == 0);

  // stdout: the reference line and a table row per run.
  CHECK(r.out.find("reference: kind=exact") != std::string::npos);
  CHECK(r.out.find("rkmk2") != std::string::npos);

  // An existing file is not replaced without --force, and is with it.
  const auto again = run_lgi("work-precision --scene " + scenes +
                             "/free_body_hlw.toml --schemes rkmk4 --dt 0.1 --t-end 1 --repeat 1 --quiet --out " + out);
  CHECK(again.status == 2);
  CHECK(again.err.find(out) != std::string::npos);
  CHECK(read_dataset(out, "/results/error").data.size() == 6);
  const auto forced = run_lgi("work-precision --scene " + scenes +
                              "/free_body_hlw.toml --schemes rkmk4 --dt 0.1 --t-end 1 --repeat 1 --quiet --force --out " +
                              out);
  CHECK(forced.status == 0);
  CHECK(forced.out.empty());
  CHECK(read_dataset(out, "/results/error").data.size() == 1);
  CHECK(split_lines(read_text(csv)).size() == 2);
}

TEST_CASE("work-precision on a heavy top: converged reference and its floor", "[work-precision]") {
  const std::string dir = scratch_dir("wp_top");
  const std::string out = dir + "/top.h5";
  // cf4 at 2e-5 is far more accurate than the reference's own error estimate;
  // `exact` refuses the scene (free bodies only), which is that row's status.
  const auto r = run_lgi("work-precision --scene " + scenes +
                         "/heavy_top_trindade_1.toml --schemes rkmk4,cf4,exact,rkmk-dp54 --dt 4e-3,2e-3,2e-5 "
                         "--tol 1e-6 --t-end 1 --repeat 1 --out " + out);
  INFO(r.out << r.err);
  REQUIRE(r.status == 0);
  CHECK(read_string_attribute(out, "/reference", "kind") == "converged");
  CHECK(read_string_attribute(out, "/reference", "scheme") == "rkmk-dop853");
  const double estimated = read_double_attribute(out, "/reference", "estimated_error");
  CHECK(std::isfinite(estimated));
  CHECK(estimated > 0.0);
  CHECK(estimated < 1e-8);
  CHECK(read_double_attribute(out, "/reference", "tol") > 0.0);

  const auto scheme = read_string_dataset(out, "/results/scheme");
  const auto status = read_string_dataset(out, "/results/status");
  const auto error = read_dataset(out, "/results/error").data;
  const auto floor = read_dataset(out, "/results/below_reference_floor").data;
  const auto casimir = read_dataset(out, "/results/error_casimir_vertical_momentum").data;
  const auto tol = read_dataset(out, "/results/tol").data;
  REQUIRE(scheme.size() == 10);
  // rkmk4: two measured errors, order 4.
  CHECK(status[0] == "ok");
  CHECK(floor[0] == 0);
  CHECK(floor[1] == 0);
  CHECK(error[1] > estimated);
  CHECK(slope(error[0], error[1], 2.0) == Approx(4.0).margin(0.5));
  CHECK(std::isfinite(casimir[0]));
  // cf4 at 2e-5: below the floor, not reported.
  CHECK(scheme[5] == "cf4");
  CHECK(status[5] == "ok");
  CHECK(floor[5] == 1);
  CHECK(std::isnan(error[5]));
  CHECK(std::isnan(read_dataset(out, "/results/error_attitude").data[5]));
  CHECK(std::isfinite(casimir[5]));  // invariant errors do not depend on the reference
  // exact refuses the heavy top: each of its rows says why.
  for (std::size_t i = 6; i < 9; ++i) {
    CHECK(scheme[i] == "exact");
    CHECK(status[i].rfind("refused: ", 0) == 0);
    CHECK(status[i].find("free body") != std::string::npos);
    CHECK(std::isnan(error[i]));
    CHECK(read_dataset(out, "/results/runs_per_repeat").data[i] == 0);  // nothing timed
  }
  // The adaptive scheme takes the tolerance.
  CHECK(scheme[9] == "rkmk-dp54");
  CHECK(tol[9] == 1e-6);
  CHECK(std::isnan(read_dataset(out, "/results/dt").data[9]));
  CHECK(status[9] == "ok");
  CHECK(error[9] > estimated);
  CHECK(r.out.find("reference: kind=converged scheme=rkmk-dop853") != std::string::npos);
}

TEST_CASE("work-precision refuses bad input with exit 2 and no file", "[work-precision]") {
  const std::string dir = scratch_dir("wp_bad");
  const std::string out = dir + "/bad.h5";
  // A scene without [run]: the steps and tolerances must come from the command line.
  const std::string no_run = scratch_dir("wp_bad_scene") + "/no_run.toml";
  std::ofstream(no_run) << "name = \"no run\"\n[body]\ninertia = [1.0, 2.0, 3.0]\n"
                           "[initial]\nangular_velocity = [0.3, 0.8, -0.4]\n";
  const std::string scene = " --scene " + no_run + " --t-end 1 --repeat 1 --out " + out;
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--schemes rkmk4,nonesuch --dt 0.1", "--schemes"},
      {"--schemes rkmk4 --dt 0.1,0", "--dt"},
      {"--schemes rkmk4 --dt=-0.1", "--dt"},
      {"--schemes rkmk4 --dt 0.1,abc", "--dt"},
      {"--schemes '' --dt 0.1", "--schemes"},
      {"--schemes rkmk4", "--dt"},
      {"--schemes rkmk-dp54 --dt 0.1", "--tol"},
      {"--schemes rkmk-dp54 --tol 0", "--tol"},
      {"--schemes rkmk4,rkmk4 --dt 0.1", "--schemes"},
      {"--schemes rkmk4 --dt 0.1 --repeat 0", "--repeat"},
  };
  for (const auto& [flags, named] : cases) {
    const auto r = run_lgi("work-precision " + flags + scene);
    INFO(flags << " -> " << r.err);
    CHECK(r.status == 2);
    CHECK(r.err.find(named) != std::string::npos);
    CHECK(line_count(r.err) == 1);
    CHECK(fs::is_empty(dir));
  }
  const auto missing = run_lgi("work-precision --scene " + dir + "/nope.toml --schemes rkmk4 --dt 0.1 --out " + out);
  CHECK(missing.status == 2);
  CHECK(fs::is_empty(dir));
}

}  // namespace test_work_precision
