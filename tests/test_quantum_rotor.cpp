// The free rotor's levels from lgi quantum's library
// (experiments/analysis/quantum/quantum_spectrum.hpp) against independent
// references (docs/quantum.md):
//  - the asymmetric rotor, every j <= 12, on two sets of moments and two m:
//    the j block of the textbook matrix elements (King, Hainer & Cross,
//    J. Chem. Phys. 11 (1943) 27: ⟨k|H|k⟩ and ⟨k±2|H|k⟩), coded here and
//    diagonalised whole, agrees to 1e-10 relative, and each level's D2 class
//    equals that of the reference eigenvector; every j holds 2j+1 levels with
//    the class sizes of Wang's factorisation;
//  - the symmetric rotor (oblate, prolate, and with its axis first in the
//    scene) agrees with E = ħ²[j(j+1)/(2J₁) + k²(1/(2J₃) − 1/(2J₁))].
#include <catch2/catch.hpp>
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>

#include "experiments/analysis/quantum/quantum_spectrum.hpp"

namespace test_quantum_rotor {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi::experiments::quantum;

namespace {

struct Reference {
  std::vector<double> energy;
  std::vector<int> parity;  // 2 [C2(3) = −1] + [C2(1) = −1] of each eigenvector
};

/// The textbook j block of Σ L_i²/(2J_i) in |j,k⟩, diagonalised whole, and the
/// D2 class of each eigenvector from C2(3)|k⟩ = (−1)^k|k⟩ and C2(1)|k⟩ = (−1)^j|−k⟩
/// (tests/test_quantum_operators.cpp checks the latter against exp(−iπL₁/ħ)).
Reference textbook_levels(int j, const Eigen::Vector3d& J, double hbar) {
  const double bx = 0.5 / J(0), by = 0.5 / J(1), bz = 0.5 / J(2), jj = j * (j + 1.0);
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(2 * j + 1, 2 * j + 1);
  Eigen::MatrixXd c2z = Eigen::MatrixXd::Zero(2 * j + 1, 2 * j + 1), c2x = c2z;
  for (int k = -j; k <= j; ++k) {
    h(j + k, j + k) = 0.5 * (bx + by) * (jj - k * k) + bz * k * k;
    if (k + 2 <= j) {
      const double v = 0.25 * (bx - by) * std::sqrt((jj - k * (k + 1.0)) * (jj - (k + 1.0) * (k + 2.0)));
      h(j + k + 2, j + k) = h(j + k, j + k + 2) = v;
    }
    c2z(j + k, j + k) = (k % 2 ? -1.0 : 1.0);
    c2x(j - k, j + k) = (j % 2 ? -1.0 : 1.0);
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(hbar * hbar * h);
  Reference r;
  for (Eigen::Index i = 0; i < es.eigenvalues().size(); ++i) {
    const Eigen::VectorXd v = es.eigenvectors().col(i);
    const double z = v.dot(c2z * v), x = v.dot(c2x * v);
    // A level is in one class; near-degenerate pairs of high j (their splitting
    // ~1e-12 relative at j = 12) mix in the reference's eigenvectors slightly.
    REQUIRE(std::abs(std::abs(z) - 1.0) < 1e-6);
    REQUIRE(std::abs(std::abs(x) - 1.0) < 1e-6);
    r.energy.push_back(es.eigenvalues()(i));
    r.parity.push_back(2 * (z < 0 ? 1 : 0) + (x < 0 ? 1 : 0));
  }
  return r;
}

std::map<int, std::vector<QuantumLevel>> by_j(const QuantumSpectrum& q) {
  std::map<int, std::vector<QuantumLevel>> out;
  for (const auto& l : q.levels) out[l.j].push_back(l);
  return out;
}

}  // namespace

TEST_CASE("quantum: the free asymmetric rotor agrees with the textbook j blocks for every j <= 12", "[quantum]") {
  const double hbar = 0.37;
  for (const Eigen::Vector3d& J : {Eigen::Vector3d(1.0, 1.5, 2.0), Eigen::Vector3d(2.0, 1.0, 2.0 / 3.0)})
    for (const int m : {0, -3}) {
      const QuantumTop top = quantum_top(J, Eigen::Vector3d::Zero());
      REQUIRE(top.symmetry == TopSymmetry::free_asymmetric);
      QuantumSettings s;
      s.hbar = hbar, s.m = m, s.jmax = 12;
      const QuantumSpectrum q = quantum_spectrum(top, s);
      const auto levels = by_j(q);
      REQUIRE(levels.size() == static_cast<std::size_t>(13 - std::abs(m)));
      double worst = 0.0;
      for (const auto& [j, block] : levels) {
        INFO("J = " << J.transpose() << ", m = " << m << ", j = " << j);
        REQUIRE(block.size() == static_cast<std::size_t>(2 * j + 1));
        const Reference ref = textbook_levels(j, J, hbar);
        std::array<int, 4> classes{};
        for (std::size_t i = 0; i < block.size(); ++i) {
          const double scale = std::max(std::abs(ref.energy[i]), hbar * hbar / (2.0 * J.maxCoeff()));  // j = 0: E = 0
          worst = std::max(worst, std::abs(block[i].energy - ref.energy[i]) / scale);
          // The class of the reference level at this energy (either, within a near-degenerate pair).
          bool same_class = false;
          for (std::size_t r = 0; r < ref.energy.size(); ++r)
            if (std::abs(ref.energy[r] - block[i].energy) <= 1e-10 * scale && ref.parity[r] == block[i].parity)
              same_class = true;
          CHECK(same_class);
          CHECK(block[i].converged);
          CHECK(block[i].change_with_jmax == 0.0);
          CHECK(block[i].k == -1);
          REQUIRE((block[i].parity >= 0 && block[i].parity <= 3));
          ++classes[static_cast<std::size_t>(block[i].parity)];
        }
        // Wang's factorisation: A holds j/2 + 1 (j even) or (j − 1)/2 (odd), each B the rest in thirds.
        const int a = j % 2 == 0 ? j / 2 + 1 : (j - 1) / 2, b = j % 2 == 0 ? j / 2 : (j + 1) / 2;
        CHECK(classes == std::array<int, 4>{a, b, b, b});
      }
      CHECK(worst < 1e-10);
    }
}

TEST_CASE("quantum: the free symmetric rotor agrees with its closed form", "[quantum]") {
  const double hbar = 0.8;
  // (J1 = J2, J3): oblate, prolate, and a scene with its symmetry axis first (reframed to third).
  for (const Eigen::Vector3d& J : {Eigen::Vector3d(1.0, 1.0, 1.7), Eigen::Vector3d(2.0, 2.0, 0.5),
                                   Eigen::Vector3d(0.6, 1.1, 1.1)}) {
    const QuantumTop top = quantum_top(J, Eigen::Vector3d::Zero());
    REQUIRE(top.symmetry == TopSymmetry::free_symmetric);
    const double j1 = top.moments(0), j3 = top.moments(2);
    CHECK(top.moments(1) == j1);
    QuantumSettings s;
    s.hbar = hbar, s.m = 1, s.jmax = 10;
    const QuantumSpectrum q = quantum_spectrum(top, s);
    CHECK(q.levels.size() == static_cast<std::size_t>(11 * 11 - 1));
    double worst = 0.0;
    for (const auto& l : q.levels) {
      REQUIRE(l.k_conserved);
      const double e = hbar * hbar * (l.j * (l.j + 1.0) / (2 * j1) + l.k * l.k * (1 / (2 * j3) - 1 / (2 * j1)));
      worst = std::max(worst, std::abs(l.energy - e) / std::max(std::abs(e), 1e-300));
    }
    CHECK(worst < 1e-12);
  }
}

}  // namespace test_quantum_rotor
