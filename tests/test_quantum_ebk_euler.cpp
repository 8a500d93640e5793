// EBK levels of the free asymmetric rotor (the Euler top) against lgi
// quantum's exact levels at fixed j (docs/quantum.md §9): |L| = ħ(j + ½) and
// the cap action I_cap = ħ(n + ½) (Maslov index 2) give each level away from
// the separatrix to O(ħ²) relative. At fixed |L| = 1, ħ = 1/(j + ½): doubling
// j about halves ħ and the largest relative error over a fixed classical
// energy window falls by (ħ₁/ħ₂)² ≈ 4.
#include <catch2/catch.hpp>
#include <cmath>

#include "experiments/analysis/quantum/ebk_free_rotor.hpp"

namespace test_quantum_ebk_euler {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi::experiments::quantum;

namespace {

/// The largest |E_ebk − E_exact|/E_exact over the levels of one j whose exact
/// energy lies in the window E/G² ∈ [e_low, e_high] (G = 1 here).
double largest_relative_error(const Eigen::Vector3d& J, int j, double e_low, double e_high, int& counted) {
  const double hbar = 1.0 / (j + 0.5);
  QuantumSettings s;
  s.hbar = hbar, s.m = j, s.jmax = j;  // m = jmax: the one block of this j
  const QuantumSpectrum q = quantum_spectrum(quantum_top(J, Eigen::Vector3d::Zero()), s);
  REQUIRE(static_cast<int>(q.levels.size()) == 2 * j + 1);
  double worst = 0.0;
  counted = 0;
  for (const EbkRow& r : ebk_table(q, hbar, j)) {
    if (r.energy_exact < e_low || r.energy_exact > e_high) continue;
    REQUIRE(std::isfinite(r.energy_ebk));
    worst = std::max(worst, std::abs(r.energy_ebk / r.energy_exact - 1.0));
    ++counted;
  }
  return worst;
}

}  // namespace

TEST_CASE("EBK levels of the Euler top are exact to O(hbar^2) relative away from the separatrix", "[quantum][ebk]") {
  // HLW body J = (2, 1, 2/3): E/G² runs from 1/4 (largest axis) to 3/4 (smallest), separatrix at 1/2.
  const Eigen::Vector3d J(2.0, 1.0, 2.0 / 3.0);
  for (const auto& [lo, hi] : {std::pair{0.25, 0.42}, std::pair{0.58, 0.75}}) {
    int n10 = 0, n20 = 0, n40 = 0;
    const double e10 = largest_relative_error(J, 10, lo, hi, n10);
    const double e20 = largest_relative_error(J, 20, lo, hi, n20);
    const double e40 = largest_relative_error(J, 40, lo, hi, n40);
    INFO("window [" << lo << ", " << hi << "]: " << e10 << " (" << n10 << " levels), " << e20 << " (" << n20
                    << "), " << e40 << " (" << n40 << ")");
    CHECK(n10 >= 4);
    CHECK(n40 >= 4 * n10 - 8);
    const double r1 = e10 / e20, r2 = e20 / e40;
    const double h1 = std::pow(20.5 / 10.5, 2), h2 = std::pow(40.5 / 20.5, 2);  // (ħ₁/ħ₂)²
    CHECK(r1 / h1 > 0.8);
    CHECK(r1 / h1 < 1.25);
    CHECK(r2 / h2 > 0.8);
    CHECK(r2 / h2 < 1.25);
  }
}

TEST_CASE("EBK of the Euler top: doublets, the separatrix, the symmetric limit", "[quantum][ebk]") {
  const Eigen::Vector3d J(1.0, 2.0, 3.0);
  // The lowest torus about the largest axis sits just above the steady rotation G²/(2 J_max).
  const double hbar = 0.01, G = hbar * 100.5;
  const auto low = ebk_euler_level(J, hbar, 100, 0, true), high = ebk_euler_level(J, hbar, 100, 0, false);
  REQUIRE(low);
  REQUIRE(high);
  CHECK(*low > G * G / 6.0);
  CHECK(*low < G * G / 4.0);
  CHECK(*high < G * G / 2.0);
  CHECK(*high > G * G / 4.0);
  // The cap area up to the separatrix holds fewer than 2j + 1 states: a large n has no torus.
  CHECK_FALSE(ebk_euler_level(J, hbar, 100, 100, true));
  // The free symmetric rotor: the exact level + ħ²/(8A).
  QuantumSettings s;
  s.hbar = 0.5, s.jmax = 6;
  const QuantumSpectrum q = quantum_spectrum(quantum_top(Eigen::Vector3d(2.0, 2.0, 1.0), Eigen::Vector3d::Zero()), s);
  for (const EbkRow& r : ebk_table(q, 0.5, 0)) CHECK(r.energy_ebk - r.energy_exact == Approx(0.25 / 16.0).epsilon(1e-10));
  // A heavy top that is not Lagrange's has no EBK table.
  s.levels = 2, s.jmax = 8;
  CHECK_THROWS_AS(ebk_table(quantum_spectrum(quantum_top(J, Eigen::Vector3d(0.0, 0.0, 1.0)), s), 0.5, 0),
                  std::invalid_argument);
}

}  // namespace test_quantum_ebk_euler
