// The harmonic limit of lgi quantum (experiments/QUANTUM.md): at m = 0 the
// ground level of a general heavy top tends to the bottom of the potential
// plus the zero-point energy of its hanging equilibrium,
//   (E₀(ħ) − min U)/ħ → (ω_a + ω_b)/2  as ħ → 0,
// with ω_a, ω_b from lgi's own linearisation there (analysis/
// relative_equilibria.hpp: λ⁴ + g1 λ² + g2 = 0, so ω_a + ω_b = √(g1 + 2√g2)).
// The deviation is first order in ħ: at most 5% at ħ = 0.01 and about half
// of that at ħ = 0.02. Richter's general top (complex Ĥ: c has no zero
// component) and a second top with a real Ĥ (c₂ = 0). The [slow] case adds
// ħ = 0.005.
#include <catch2/catch.hpp>
#include <cmath>

#include "experiments/analysis/quantum/quantum_spectrum.hpp"
#include "experiments/analysis/relative_equilibria.hpp"
#include "support/shipped_scene.hpp"

namespace test_quantum_harmonic {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi::experiments;
using namespace lgi::experiments::quantum;

namespace {

/// (ω_a + ω_b)/2 at the hanging equilibrium (ℓ = 0, lowest h).
double half_frequency_sum(const Eigen::Matrix3d& J, const Eigen::Vector3d& weight) {
  const EquilibriumSet set = equilibria_at({J, weight}, 0.0);
  REQUIRE(!set.rows.empty());
  const RelativeEquilibrium& e = set.rows.front();  // sorted by h
  REQUIRE(e.stability == EquilibriumStability::stable);
  REQUIRE(e.h == Approx(-weight.norm()).epsilon(1e-12));
  return 0.5 * std::sqrt(e.g1 + 2.0 * std::sqrt(e.g2));
}

/// (E₀ − min U)/ħ at m = 0.
double scaled_ground(const QuantumTop& top, double hbar, int jmax) {
  QuantumSettings s;
  s.hbar = hbar, s.m = 0, s.jmax = jmax, s.levels = 1, s.tol = 1e-9;
  const QuantumSpectrum q = quantum_spectrum(top, s);
  REQUIRE(q.levels.size() == 1);
  CHECK(q.levels[0].converged);
  return (q.levels[0].energy + top.weight.norm()) / hbar;
}

void check_limit(const Eigen::Matrix3d& J, const Eigen::Vector3d& weight, bool slow) {
  const double target = half_frequency_sum(J, weight);
  const QuantumTop top = quantum_top(J.diagonal(), weight);
  const double d02 = scaled_ground(top, 0.02, 40) / target - 1.0;
  const double d01 = scaled_ground(top, 0.01, 60) / target - 1.0;
  INFO("(w_a + w_b)/2 = " << target << ", deviation at hbar = 0.02: " << d02 << ", at 0.01: " << d01);
  CHECK(std::abs(d01) <= 0.05);
  CHECK(d01 / d02 == Approx(0.5).margin(0.05));  // first order in ħ
  if (!slow) return;
  const double d005 = scaled_ground(top, 0.005, 90) / target - 1.0;
  INFO("deviation at hbar = 0.005: " << d005);
  CHECK(d005 / d01 == Approx(0.5).margin(0.03));
}

}  // namespace

TEST_CASE("quantum: the ground level of a general heavy top tends to min U + hbar (w_a + w_b)/2", "[quantum]") {
  const lgi::system::Scene richter = lgi::testing::shipped_scene("general_top_richter");
  const QuantumTop top = quantum_top_of(richter);
  REQUIRE(top.symmetry == TopSymmetry::general);
  REQUIRE(!top.is_real());
  check_limit(richter.inertia, top.weight, false);
  // A second top: χ in the 1–3 principal plane (a real Ĥ), not on an axis.
  const Eigen::Matrix3d J = Eigen::Vector3d(0.5, 0.85, 1.0).asDiagonal();
  check_limit(J, Eigen::Vector3d(-0.3, 0.0, 0.9), false);
}

TEST_CASE("quantum: the harmonic limit down to hbar = 0.005", "[quantum][slow]") {
  const lgi::system::Scene richter = lgi::testing::shipped_scene("general_top_richter");
  check_limit(richter.inertia, quantum_top_of(richter).weight, true);
}

}  // namespace test_quantum_harmonic
