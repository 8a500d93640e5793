// The rotor's operators of lgi quantum (experiments/analysis/quantum/
// rotor_operators.hpp; docs/quantum.md), checked as matrices on a Wigner block
// j = |m|..jmax:
//  - the closed-form Clebsch–Gordan coefficients of j ⊗ 1 equal Racah's
//    general formula (coded here independently);
//  - [L̂ᵢ, L̂ⱼ] = −iħ ε_ijk L̂ₖ (the body-fixed, anomalous sign) and
//    [L̂ᵢ, Γ̂ⱼ] = −iħ ε_ijk Γ̂ₖ (Γ̂ turns with the body as L̂ does);
//  - Γ̂ is Hermitian, [Γ̂ᵢ, Γ̂ⱼ] = 0 and Γ̂·Γ̂ = 1 on every row and column with
//    j < jmax (the cut at jmax spoils only the last j);
//  - L̂·Γ̂ = Γ̂·L̂ = mħ (the vertical angular momentum) on the whole block;
//  - L̂² = ħ² j(j+1);
//  - the rotation by π about body axis 1, |j,k⟩ → (−1)^j |j,−k⟩, is
//    exp(−iπ L̂₁/ħ) computed from L̂₁'s eigenvectors.
#include <catch2/catch.hpp>
#include <Eigen/Dense>
#include <cmath>

#include "experiments/analysis/quantum/rotor_operators.hpp"

namespace test_quantum_operators {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi::experiments::quantum;
using Dense = Eigen::MatrixXcd;

namespace {

double factorial(int n) { return std::tgamma(n + 1.0); }

/// Racah's formula for ⟨j1 m1 j2 m2 | J M⟩ (Edmonds eq. 3.6.11), small j only.
double racah_cg(int j1, int m1, int j2, int m2, int J, int M) {
  if (m1 + m2 != M || std::abs(m1) > j1 || std::abs(m2) > j2 || std::abs(M) > J) return 0.0;
  if (J < std::abs(j1 - j2) || J > j1 + j2) return 0.0;
  const double pre = std::sqrt((2.0 * J + 1) * factorial(J + j1 - j2) * factorial(J - j1 + j2) *
                               factorial(j1 + j2 - J) / factorial(j1 + j2 + J + 1)) *
                     std::sqrt(factorial(J + M) * factorial(J - M) * factorial(j1 - m1) * factorial(j1 + m1) *
                               factorial(j2 - m2) * factorial(j2 + m2));
  double sum = 0.0;
  for (int k = 0; k <= j1 + j2 + J; ++k) {
    const int a = j1 + j2 - J - k, b = j1 - m1 - k, c = j2 + m2 - k, d = J - j2 + m1 + k, e = J - j1 - m2 + k;
    if (a < 0 || b < 0 || c < 0 || d < 0 || e < 0) continue;
    sum += (k % 2 ? -1.0 : 1.0) / (factorial(k) * factorial(a) * factorial(b) * factorial(c) * factorial(d) *
                                   factorial(e));
  }
  return pre * sum;
}

Dense dense(const ComplexSparse& a) { return Dense(a); }

/// The largest |entry| over rows and columns with j < jmax (or all).
double interior_max(const Dense& a, const WignerBasis& b, bool interior) {
  const Eigen::Index n = interior ? b.offset(b.jhi) : a.rows();
  return a.topLeftCorner(n, n).cwiseAbs().maxCoeff();
}

}  // namespace

TEST_CASE("quantum: the j x 1 Clebsch-Gordan closed forms equal Racah's formula", "[quantum]") {
  double worst = 0.0;
  for (int j = 0; j <= 7; ++j)
    for (int m1 = -j; m1 <= j; ++m1)
      for (int q = -1; q <= 1; ++q)
        for (int J = std::max(0, j - 1); J <= j + 1; ++J)
          worst = std::max(worst, std::abs(clebsch_gordan_1(j, m1, q, J) - racah_cg(j, m1, 1, q, J, m1 + q)));
  CHECK(worst < 1e-13);
}

TEST_CASE("quantum: body-fixed L and Gamma obey the rotor's algebra on a Wigner block", "[quantum]") {
  const double hbar = 0.7;
  for (const int m : {0, 2, -3}) {
    INFO("m = " << m);
    const WignerBasis b = WignerBasis::up_to(m, 7);
    const RotorOperators ops = rotor_operators(b, hbar);
    std::array<Dense, 3> L, G;
    for (std::size_t i = 0; i < 3; ++i) L[i] = dense(ops.L[i]), G[i] = dense(ops.Gamma[i]);
    const Complex mi(0.0, -hbar);  // −iħ
    for (std::size_t i = 0; i < 3; ++i) {
      const std::size_t j = (i + 1) % 3, k = (i + 2) % 3;
      CHECK(interior_max(L[i] * L[j] - L[j] * L[i] - mi * L[k], b, false) < 1e-12);
      CHECK(interior_max(L[i] * G[j] - G[j] * L[i] - mi * G[k], b, false) < 1e-12);
      CHECK(interior_max(L[j] * G[i] - G[i] * L[j] + mi * G[k], b, false) < 1e-12);
      CHECK(interior_max(L[i] * G[i] - G[i] * L[i], b, false) < 1e-12);
      CHECK(interior_max(G[i] * G[j] - G[j] * G[i], b, true) < 1e-13);
      CHECK(interior_max(G[i] - G[i].adjoint(), b, false) < 1e-15);
      CHECK(interior_max(L[i] - L[i].adjoint(), b, false) < 1e-15);
    }
    const Eigen::Index n = b.size();
    const Dense I = Dense::Identity(n, n);
    CHECK(interior_max(G[0] * G[0] + G[1] * G[1] + G[2] * G[2] - I, b, true) < 1e-13);
    CHECK(interior_max(L[0] * G[0] + L[1] * G[1] + L[2] * G[2] - hbar * m * I, b, false) < 1e-12);
    CHECK(interior_max(G[0] * L[0] + G[1] * L[1] + G[2] * L[2] - hbar * m * I, b, false) < 1e-12);
    Dense l2_expected = Dense::Zero(n, n);
    for (int j = b.jlo; j <= b.jhi; ++j)
      for (int k = -j; k <= j; ++k) l2_expected(b.index(j, k), b.index(j, k)) = hbar * hbar * j * (j + 1.0);
    CHECK(interior_max(L[0] * L[0] + L[1] * L[1] + L[2] * L[2] - l2_expected, b, false) < 1e-12);
    // The cut at jmax is real: Γ̂·Γ̂ differs from 1 in the last j.
    CHECK((G[0] * G[0] + G[1] * G[1] + G[2] * G[2] - I).cwiseAbs().maxCoeff() > 0.1);
    // The phase convention: L̂₁, L̂₃, Γ̂₁, Γ̂₃ real, L̂₂, Γ̂₂ imaginary.
    for (std::size_t i : {0u, 2u}) CHECK(L[i].imag().cwiseAbs().maxCoeff() + G[i].imag().cwiseAbs().maxCoeff() == 0.0);
    CHECK(L[1].real().cwiseAbs().maxCoeff() + G[1].real().cwiseAbs().maxCoeff() == 0.0);
  }
}

TEST_CASE("quantum: the rotation by pi about body axis 1 is |j,k> -> (-1)^j |j,-k>", "[quantum]") {
  const double hbar = 1.0;
  for (int j = 0; j <= 6; ++j) {
    const WignerBasis b = WignerBasis::single(0, j);
    const Dense L1 = dense(rotor_operators(b, hbar).L[0]);
    Eigen::SelfAdjointEigenSolver<Dense> es(L1);
    const Eigen::VectorXcd phase =
        (es.eigenvalues().cast<Complex>() * Complex(0.0, -M_PI / hbar)).array().exp().matrix();
    const Dense rotation = es.eigenvectors() * phase.asDiagonal() * es.eigenvectors().adjoint();
    Dense expected = Dense::Zero(2 * j + 1, 2 * j + 1);
    for (int k = -j; k <= j; ++k) expected(b.index(j, -k), b.index(j, k)) = (j % 2 ? -1.0 : 1.0);
    INFO("j = " << j);
    CHECK((rotation - expected).cwiseAbs().maxCoeff() < 1e-12);
  }
}

}  // namespace test_quantum_operators
