// `lgi simulate --output-dt D` (experiments/cli/output_grid.hpp) as a user
// runs it: samples exactly at t0 + k D and t_end; a pair with dense output
// interpolates them and takes the steps of a run without them, to the same
// final state bit for bit; a pair without dense output lands on them; a
// fixed-step scheme is sampled on its own grid; bad values exit 2 with one
// line naming --output-dt and no file.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>

#include "support/h5_read.hpp"
#include "support/run_command.hpp"

namespace test_simulate_output_dt {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi::testing;
namespace fs = std::filesystem;

namespace {
const std::string scenes = LGI_SCENES_DIR;
const std::string top = scenes + "/heavy_top_hlw.toml";

std::vector<double> times_of(const std::string& file) {
  return read_dataset(file, "/particles/body/orientation/time").data;
}
std::vector<double> grid(double D, int n) {
  std::vector<double> t;
  for (int k = 0; k <= n; ++k) t.push_back(static_cast<double>(k) * D);
  return t;
}
/// The quaternion of sample k.
std::vector<double> orientation(const std::string& file, std::size_t k) {
  const auto q = read_dataset(file, "/particles/body/orientation/value").data;
  return {q.begin() + static_cast<std::ptrdiff_t>(4 * k), q.begin() + static_cast<std::ptrdiff_t>(4 * k + 4)};
}
double distance(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0.0, e = 0.0;  // q and −q are the same rotation
  for (std::size_t i = 0; i < 4; ++i) d = std::max(d, std::abs(a[i] - b[i])), e = std::max(e, std::abs(a[i] + b[i]));
  return std::min(d, e);
}
}  // namespace

TEST_CASE("--output-dt samples at t0 + k D and t_end", "[cli][output-dt]") {
  const std::string dir = scratch_dir("cli_output_dt");
  const std::string run = "simulate --scene " + top + " --t-end 2 ";
  SECTION("a pair with dense output interpolates, and its steps and final state are those of a plain run") {
    const auto plain = run_lgi(run + "--scheme rkmk-verner87 --tol 1e-10 --out " + dir + "/plain.h5");
    const auto dense = run_lgi(run + "--scheme rkmk-verner87 --tol 1e-10 --output-dt 0.1 --out " + dir + "/d.h5");
    REQUIRE(plain.status == 0);
    REQUIRE(dense.status == 0);
    CHECK(times_of(dir + "/d.h5") == grid(0.1, 20));
    const auto steps_plain = read_dataset(dir + "/plain.h5", "/particles/body/orientation/step").data;
    const auto steps_dense = read_dataset(dir + "/d.h5", "/particles/body/orientation/step").data;
    CHECK(steps_dense.back() == steps_plain.back());  // the same steps
    CHECK(steps_dense.size() == 21);
    CHECK(orientation(dir + "/d.h5", 20) == orientation(dir + "/plain.h5", steps_plain.size() - 1));
    // Against a pair that lands on the same times at a much tighter tolerance.
    const auto landed = run_lgi(run + "--scheme rkmk-dp54 --tol 1e-13 --output-dt 0.1 --out " + dir + "/l.h5");
    REQUIRE(landed.status == 0);
    CHECK(times_of(dir + "/l.h5") == grid(0.1, 20));
    double worst = 0.0;
    for (std::size_t k = 1; k < 20; ++k)
      worst = std::max(worst, distance(orientation(dir + "/d.h5", k), orientation(dir + "/l.h5", k)));
    INFO("largest difference of the interpolated samples: " << worst);
    CHECK(worst <= 1e-9);
  }
  SECTION("a fixed-step scheme is sampled on its grid") {
    const auto r = run_lgi(run + "--scheme rkmk4 --dt 0.01 --output-dt 0.25 --out " + dir + "/f.h5");
    REQUIRE(r.status == 0);
    CHECK(times_of(dir + "/f.h5") == grid(0.25, 8));
    std::vector<double> steps;
    for (int k = 0; k <= 8; ++k) steps.push_back(25.0 * k);
    CHECK(read_dataset(dir + "/f.h5", "/particles/body/orientation/step").data == steps);
  }
  SECTION("a last interval shorter than D ends at t_end") {
    const auto r = run_lgi("simulate --scene " + top + " --t-end 1.05 --scheme rkmk-dop853 --tol 1e-9 --output-dt 0.5 "
                           "--out " + dir + "/s.h5");
    REQUIRE(r.status == 0);
    CHECK(times_of(dir + "/s.h5") == std::vector<double>{0.0, 0.5, 1.0, 1.05});
  }
}

TEST_CASE("bad --output-dt values exit 2 with one line and no file", "[cli][output-dt][bad-input]") {
  const std::string dir = scratch_dir("cli_output_dt_bad");
  const std::string out = dir + "/a.h5";
  const std::string run = "simulate --scene " + top + " --out " + out + " ";
  auto bad = [&](const std::string& args) {
    const CommandResult r = run_lgi(run + args);
    INFO(args << "\nstderr: " << r.err);
    CHECK(r.status == 2);
    CHECK(line_count(r.err) == 1);
    CHECK(r.err.find("--output-dt") != std::string::npos);
    CHECK_FALSE(fs::exists(out));
    CHECK_FALSE(fs::exists(out + ".partial"));
  };
  bad("--scheme rkmk4 --dt 0.01 --output-dt 0");
  bad("--scheme rkmk4 --dt 0.01 --output-dt -0.1");
  bad("--scheme rkmk4 --dt 0.01 --output-dt nan");
  bad("--scheme rkmk4 --dt 0.01 --output-dt 0.015");            // not a multiple of the step
  bad("--scheme rkmk4 --dt 0.01 --output-dt 0.1 --save-every 5");  // both
  bad("--scheme rkmk-verner87 --tol 1e-8 --t-end 10 --output-dt 1e-8");  // 1e9 samples
}

}  // namespace test_simulate_output_dt
