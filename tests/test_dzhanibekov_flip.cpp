// The acceptance run, through lgi: the book spun about its
// intermediate axis flips. Ω2 changes sign first near t = 1.6 s and then
// about every 3.4 s, and rkmk4 at h = 1e-3 agrees with the exact flow to
// the order-4 error expected at that step.
#include <catch2/catch.hpp>
#include <cmath>

#include "support/h5_read.hpp"
#include "support/run_command.hpp"

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

  // Order-4 error at h = 1e-3 with |Ω| = 10: (h|Ω|)^4 = 1e-8 per unit time,
  // amplified near the separatrix; measured 3e-8 relative (see the issue note).
  double worst = 0.0;
  for (std::size_t i = 0; i < w_rk.data.size(); i += 3) {
    double d = 0.0;
    for (int k = 0; k < 3; ++k) d += std::pow(w_rk.data[i + k] - w_ex.data[i + k], 2);
    worst = std::max(worst, std::sqrt(d) / 10.0);
  }
  INFO("max |Ω_rkmk4 − Ω_exact| / |Ω| = " << worst);
  CHECK(worst < 1e-6);
  CHECK(worst > 1e-12);  // not trivially identical: the two runs are independent
}
