// The demo's run (scripts/demo.sh), through lgi: the book spun about its
// intermediate axis flips. Ω2 changes sign first near t = 1.6 s and then
// about every 3.4 s, and rkmk4 at h = 1e-3 agrees with the exact flow to
// the order-4 error expected at that step.
#include <catch2/catch.hpp>
#include <cmath>

#include "support/h5_read.hpp"
#include "support/run_command.hpp"

namespace test_dzhanibekov_flip {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi::testing;

namespace {
std::vector<double> sign_changes(const std::vector<double>& t, const H5Array& omega, int component) {
  std::vector<double> times;
  const std::size_t n = t.size();
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double a = omega.data[3 * i + static_cast<std::size_t>(component)];
    const double b = omega.data[3 * (i + 1) + static_cast<std::size_t>(component)];
    if (std::signbit(a) != std::signbit(b)) times.push_back(t[i] - a * (t[i + 1] - t[i]) / (b - a));
  }
  return times;
}
}  // namespace

TEST_CASE("dzhanibekov_book_axis2 flips, and rkmk4 at dt = 1e-3 matches exact to order-4 accuracy", "[acceptance]") {
  const std::string dir = scratch_dir("flip");
  const std::string scene = std::string(LGI_SCENES_DIR) + "/dzhanibekov_book_axis2.toml";
  for (const char* scheme : {"rkmk4", "exact"}) {
    const auto r = run_lgi(std::string("simulate --scene ") + scene + " --scheme " + scheme + " --dt 1e-3 --out " +
                           dir + "/" + scheme + ".h5");
    INFO(r.err);
    REQUIRE(r.status == 0);
  }
  const auto t = read_dataset(dir + "/rkmk4.h5", "/particles/body/angular_velocity_body/time").data;
  const auto w_rk = read_dataset(dir + "/rkmk4.h5", "/particles/body/angular_velocity_body/value");
  const auto w_ex = read_dataset(dir + "/exact.h5", "/particles/body/angular_velocity_body/value");
  REQUIRE(t.size() == 14001);
  REQUIRE(w_rk.shape == std::vector<hsize_t>{14001, 1, 3});

  const auto flips = sign_changes(t, w_rk, 1);
  REQUIRE(flips.size() >= 3);
  CHECK(flips[0] == Approx(1.6).margin(0.15));
  for (std::size_t i = 1; i < flips.size(); ++i) CHECK(flips[i] - flips[i - 1] == Approx(3.4).margin(0.2));
  const auto flips_exact = sign_changes(t, w_ex, 1);
  REQUIRE(flips_exact.size() == flips.size());
  for (std::size_t i = 0; i < flips.size(); ++i) CHECK(std::abs(flips[i] - flips_exact[i]) < 1e-6);

  // "Agrees to the order-4 error expected at that step". Near the separatrix
  // the flow amplifies perturbations ~1e3-fold per flip, so below h ≈ 2e-3
  // the deviation sits on a round-off floor of ~1e-9 (measured, relative:
  // 7.6e-7, 4.6e-8, 3.8e-9, 9.3e-10, 4.9e-9 at h = 8e-3 … 5e-4). So: at
  // h = 1e-3 the deviation is at that floor, and at coarser steps it is
  // rkmk4's truncation error, falling 16-fold per halving.
  // Deviation at the sample times common to all runs (multiples of 8e-3).
  auto worst_deviation = [&](const H5Array& w, std::size_t stride) {
    double worst = 0.0;
    for (std::size_t j = 0; 3 * j * stride < w.data.size(); ++j) {
      const std::size_t i = 3 * j * stride;
      double d = 0.0, n = 0.0;
      for (std::size_t k = 0; k < 3; ++k) {
        d += std::pow(w.data[i + k] - w_ex.data[3 * j * 8 + k], 2);
        n += std::pow(w_ex.data[3 * j * 8 + k], 2);
      }
      worst = std::max(worst, std::sqrt(d / n));
    }
    return worst;
  };
  auto run_rkmk4 = [&](const char* dt) {
    const std::string file = dir + "/rkmk4_" + dt + ".h5";
    REQUIRE(run_lgi("simulate --scene " + scene + " --scheme rkmk4 --dt " + dt + " --out " + file).status == 0);
    return read_dataset(file, "/particles/body/angular_velocity_body/value");
  };
  const double e1 = worst_deviation(w_rk, 8);
  const double e4 = worst_deviation(run_rkmk4("4e-3"), 2);
  const double e8 = worst_deviation(run_rkmk4("8e-3"), 1);
  INFO("max |Ω_rkmk4 − Ω_exact| / |Ω|: " << e8 << " at h = 8e-3, " << e4 << " at 4e-3, " << e1 << " at 1e-3");
  CHECK(e1 < 3e-9);
  CHECK(e8 / e4 == Approx(16.0).margin(3.0));
}

}  // namespace test_dzhanibekov_flip
