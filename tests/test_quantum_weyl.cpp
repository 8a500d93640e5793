// Weyl's law of lgi quantum (docs/quantum.md §8) against exact counts: the
// spherical top's closed form, the free asymmetric rotor per j and summed over
// j at fixed m, and the staircase of a heavy (Lagrange) top; and the
// statistics built on it (quantum_statistics.hpp), including the anomalous
// statistics of the asymmetric rotor at fixed j (Manfredi & Salasnich,
// Int. J. Mod. Phys. E (2002), nucl-th/0106048).
#include <catch2/catch.hpp>
#include <cmath>

#include "experiments/analysis/quantum/quantum_statistics.hpp"
#include "experiments/analysis/quantum/weyl_law.hpp"

namespace test_quantum_weyl {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi::experiments;
using namespace lgi::experiments::quantum;

TEST_CASE("Weyl's law: the spherical top in closed form", "[quantum][weyl]") {
  // T = |Π|²/2: Vol = 4π·π(2E − ℓ²), N̄ = (2E − ℓ²)/ħ², against the exact
  // (J + 1)² − m² states with j(j+1)ħ² ≤ 2E.
  const QuantumTop top = quantum_top(Eigen::Vector3d::Ones(), Eigen::Vector3d::Zero());
  const double hbar = 0.1;
  const WeylCounting weyl(top, hbar, 3, 100);
  for (const double e : {0.5, 2.0, 7.0}) CHECK(weyl(e) == Approx((2.0 * e - 0.09) / 0.01).epsilon(1e-10));
  CHECK(weyl(0.04) == 0.0);  // below ℓ²/2
}

TEST_CASE("Weyl's law: the free asymmetric rotor per j and at fixed m", "[quantum][weyl]") {
  const Eigen::Vector3d J(1.0, 2.0, 3.0);
  const QuantumTop top = quantum_top(J, Eigen::Vector3d::Zero());
  const double hbar = 1.0;
  QuantumSettings s;
  s.hbar = hbar, s.m = 0, s.jmax = 40;
  const QuantumSpectrum q = quantum_spectrum(top, s);
  // Per j: N̄_j counts 2j + 1 levels in all and follows the staircase to a
  // few levels (its fluctuations are O(1): a 1-D system).
  for (const int j : {10, 40}) {
    CHECK(free_rotor_weyl_count(top.moments, hbar, j, 1e9) == Approx(2.0 * j + 1.0).epsilon(1e-12));
    for (std::size_t i = 0; i < q.levels.size(); ++i) {
      if (q.levels[i].j != j) continue;
      double count = 0.0;  // levels of j strictly below, plus one half of this one
      for (const QuantumLevel& l : q.levels) count += (l.j == j && l.energy < q.levels[i].energy) ? 1.0 : 0.0;
      CHECK(std::abs(free_rotor_weyl_count(top.moments, hbar, j, q.levels[i].energy) - count - 0.5) < 2.5);
    }
  }
  // At fixed m the 4-D law follows the count summed over j, below the energy
  // where j = jmax + 1 would start (ħ²j(j+1)/(2J_max)).
  const WeylCounting weyl(top, hbar, 0);
  const double top_energy = 40.0 * 41.0 / (2.0 * J.maxCoeff());
  for (const double e : {0.25 * top_energy, 0.5 * top_energy, top_energy}) {
    double count = 0.0;
    for (const QuantumLevel& l : q.levels) count += l.energy <= e ? 1.0 : 0.0;
    INFO("E = " << e << ": count " << count << ", Weyl " << weyl(e));
    CHECK(std::abs(weyl(e) / count - 1.0) < 0.05);
  }
}

TEST_CASE("Weyl's law follows the Lagrange top's staircase", "[quantum][weyl]") {
  const QuantumTop top = quantum_top(Eigen::Vector3d(1.0, 1.0, 0.5), Eigen::Vector3d(0.0, 0.0, 1.0));
  QuantumSettings s;
  s.hbar = 0.1, s.m = 1, s.jmax = 40, s.levels = 150;
  const QuantumSpectrum q = quantum_spectrum(top, s);
  const WeylCounting weyl(top, s.hbar, s.m);
  double worst = 0.0;
  for (std::size_t i = 0; i < q.levels.size(); ++i) {
    REQUIRE(q.levels[i].converged);
    worst = std::max(worst, std::abs(weyl(q.levels[i].energy) - (static_cast<double>(i) + 0.5)));
  }
  INFO("largest |N_weyl(E_i) - (i + 1/2)| over 150 levels: " << worst);
  CHECK(worst < 6.0);
}

TEST_CASE("The asymmetric rotor at fixed j: neither Poisson nor GOE (Manfredi & Salasnich)", "[quantum][weyl]") {
  // j = 100 alone (m = jmax = 100): per D₂ class about 50 levels of one
  // degree of freedom, nearly a picket fence (spacings peaked at s = 1, as
  // the paper's P(s)): the Brody fit lands at its upper bound β = 1, and Δ₃(L)
  // stays far below both Poisson (L/15) and GOE at L = 10.
  const QuantumTop top = quantum_top(Eigen::Vector3d(1.0, 2.0, 3.0), Eigen::Vector3d::Zero());
  QuantumSettings s;
  s.hbar = 1.0, s.m = 100, s.jmax = 100;
  const QuantumSpectrum q = quantum_spectrum(top, s);
  const auto classes = quantum_statistics(q, s.hbar, s.m);
  REQUIRE(classes.size() == 4);
  for (const auto& c : classes) {
    const spectral::SpectralStatistics& st = c.statistics.statistics;
    CHECK(c.j == 100);
    CHECK(st.levels >= 50);
    CHECK(st.brody.bound == 1);
    const auto& d3 = st.rigidity;
    for (std::size_t i = 0; i < d3.size(); ++i)
      if (d3[i].length == 10.0) CHECK(d3[i].value < 0.1);
  }
}

TEST_CASE("Weyl's law: the quadrature converges with its nodes", "[quantum][weyl]") {
  // Richter's general top (c with three components) at m = 2: the default
  // 400 nodes against 1600, relative to the count, where it exceeds 10 levels.
  const QuantumTop top = quantum_top(Eigen::Vector3d(1.0, 1.5, 2.0), Eigen::Vector3d(0.8, 0.4, 0.3));
  const WeylCounting coarse(top, 0.05, 2), fine(top, 0.05, 2, 1600);
  for (const double e : {-0.5, 0.0, 0.5, 2.0}) {
    REQUIRE(fine(e) > 10.0);
    INFO("E = " << e << ": " << coarse(e) << " against " << fine(e));
    CHECK(std::abs(coarse(e) / fine(e) - 1.0) < 1e-5);
  }
}

}  // namespace test_quantum_weyl
