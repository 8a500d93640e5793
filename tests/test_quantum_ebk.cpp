// EBK levels of the Lagrange top against lgi quantum's exact levels
// (docs/quantum.md §7): I_θ = ħ(n + 1/2) at ℓ = mħ, L3 = kħ (Maslov index 2)
// gives the levels to O(ħ²) at fixed quantum numbers, so the largest
// difference over the lowest ten levels drops by about 4 when ħ halves; in
// the free limit (w → 0) the error is exactly ħ²/(8A).
#include <catch2/catch.hpp>
#include <cmath>

#include "experiments/analysis/quantum/ebk_lagrange.hpp"

namespace test_quantum_ebk {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi::experiments;
using namespace lgi::experiments::quantum;

namespace {

/// max |E_ebk − E_exact| over the lowest `levels` levels at m.
double largest_difference(const QuantumTop& top, double hbar, int m, int jmax, int levels) {
  QuantumSettings s;
  s.hbar = hbar, s.m = m, s.jmax = jmax, s.levels = levels, s.tol = 1e-9;
  const QuantumSpectrum q = quantum_spectrum(top, s);
  REQUIRE(static_cast<int>(q.levels.size()) == levels);
  double worst = 0.0;
  for (const EbkRow& r : ebk_lagrange_table(q, hbar, m)) {
    CHECK(r.converged);
    REQUIRE(std::isfinite(r.energy_ebk));
    worst = std::max(worst, std::abs(r.energy_ebk - r.energy_exact));
  }
  return worst;
}

}  // namespace

TEST_CASE("EBK levels of the Lagrange top are exact to O(hbar^2)", "[quantum][ebk]") {
  const QuantumTop top = quantum_top(Eigen::Vector3d(1.0, 1.0, 0.5), Eigen::Vector3d(0.0, 0.0, 1.0));
  REQUIRE(top.symmetry == TopSymmetry::symmetric_heavy);
  for (const int m : {0, 1, 3}) {
    const double coarse = largest_difference(top, 0.1, m, 30, 10);
    const double fine = largest_difference(top, 0.05, m, 40, 10);
    INFO("m = " << m << ": max|E_ebk - E_exact| = " << coarse << " at hbar 0.1, " << fine << " at 0.05");
    CHECK(coarse < 0.1 * 0.1);  // well below a spacing ~ hbar
    CHECK(coarse / fine > 3.4);
    CHECK(coarse / fine < 4.6);
  }
}

TEST_CASE("EBK of the Lagrange top: the ground level sits above the bottom by the zero-point energy",
          "[quantum][ebk]") {
  // Near the hanging position at ℓ = L3 = 0 the top is a 2-D oscillator of
  // frequency √(w/A); EBK gives E₀ = −w + ħ√(w/A) + O(ħ²).
  const LagrangeBody body{1.0, 0.5, 1.0};
  for (const double hbar : {0.02, 0.01}) {
    const auto e = ebk_lagrange_level(body, hbar, 0, 0, 0);
    REQUIRE(e);
    CHECK(std::abs((*e + 1.0) / hbar - 1.0) < 0.5 * hbar);
  }
  const QuantumTop heavy_asymmetric = quantum_top(Eigen::Vector3d(1.0, 2.0, 0.5), Eigen::Vector3d(0.0, 0.0, 1.0));
  QuantumSettings s;
  s.hbar = 0.1, s.jmax = 10, s.levels = 2;
  CHECK_THROWS_AS(ebk_lagrange_table(quantum_spectrum(heavy_asymmetric, s), 0.1, 0), std::invalid_argument);
}

TEST_CASE("EBK of the Lagrange top in the free limit: the exact level plus hbar^2/(8A)", "[quantum][ebk]") {
  // docs/quantum.md §7: as w → 0, I_θ = L − max(|ℓ|, |L3|), so the rule gives
  // ħ²(j + 1/2)²/(2A) + ħ²k²(1/(2C) − 1/(2A)), j = n + max(|m|, |k|).
  const double A = 1.0, C = 0.5, hbar = 0.1, w = 1e-7;
  const LagrangeBody body{A, C, w};
  for (const int m : {0, 2, -3})
    for (const int k : {0, 1, -2, 4})
      for (const int n : {0, 3}) {
        const int j = n + std::max(std::abs(m), std::abs(k));
        const double exact = hbar * hbar * (j * (j + 1.0) / (2.0 * A) + k * k * (1.0 / (2.0 * C) - 1.0 / (2.0 * A)));
        const auto e = ebk_lagrange_level(body, hbar, n, m, k);
        REQUIRE(e);
        INFO("n " << n << " m " << m << " k " << k);
        CHECK(*e - exact == Approx(hbar * hbar / (8.0 * A)).margin(1e-5));
      }
}

}  // namespace test_quantum_ebk
