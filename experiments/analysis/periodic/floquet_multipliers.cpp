// classify_orbit (periodic_orbit.hpp): the Floquet multipliers of a corrected
// orbit from its monodromy's pieces (euler_poisson_flow.hpp, MonodromyPiece),
// each in the adapted bases at its two ends (experiments/PERIODIC.md, "Multipliers").
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <utility>
#include <cmath>

#include "experiments/analysis/periodic/periodic_orbit.hpp"

namespace lgi::experiments {

namespace {

/// Q: (n₁, n₂, n₃, f̂, w₁, w₂) of classify_orbit's comment, from a QR of [∇H ∇C ∇|Γ|² f].
Mat6 adapted_basis(const PeriodicFlow& body, const Vec6& x) {
  Eigen::Matrix<double, 6, 4> G;
  G.leftCols<3>() = flow_invariants(body, x).gradients.transpose();
  G.col(3) = flow_field(body, x);
  const Eigen::HouseholderQR<Eigen::Matrix<double, 6, 4>> qr(G);
  return qr.householderQ() * Mat6::Identity();
}

/// Q's blocks of columns (n: 0–2, f̂: 3, w: 4–5) each turned within its span to lie
/// nearest `to`'s (orthogonal Procrustes: the polar factor of Q_bᵀ to_b). Between
/// nearby points a Householder basis may jump by more than signs (a reflector's
/// sign choice turns the w pair), so the piece's end basis is made the next
/// start's, transported: the blocks' product then telescopes.
Mat6 aligned(const Mat6& Q, const Mat6& to) {
  Mat6 out;
  for (const auto& [first, size] : {std::pair{0, 3}, std::pair{3, 1}, std::pair{4, 2}}) {
    const Eigen::MatrixXd C = Q.middleCols(first, size).transpose() * to.middleCols(first, size);
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(C, Eigen::ComputeFullU | Eigen::ComputeFullV);
    out.middleCols(first, size) = Q.middleCols(first, size) * (svd.matrixU() * svd.matrixV().transpose());
  }
  return out;
}

/// The diagonal blocks of B = ∏ B_k, B_k = Q(end_k)ᵀ M_k Q(start_k): the
/// product of the pieces' blocks (exact for block-triangular factors), and
/// det P as the product of the pieces' 2×2 determinants.
struct BlockProduct {
  Eigen::Matrix3d N = Eigen::Matrix3d::Identity();
  double flow = 1.0;  // C_ff
  Eigen::Matrix2d P = Eigen::Matrix2d::Identity();
  double det_P = 1.0;
  double defect = 0.0;  // the largest entry taken as zero in any B_k
  Mat6 Q0 = Mat6::Identity();
};

BlockProduct block_product(const PeriodicFlow& body, const std::vector<MonodromyPiece>& pieces) {
  BlockProduct b;
  b.Q0 = adapted_basis(body, pieces.front().start);
  Mat6 Q = b.Q0;
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    const Mat6 Q_next = k + 1 < pieces.size() ? adapted_basis(body, pieces[k + 1].start) : b.Q0;
    // The left basis at the piece's own end: the discrete map keeps H, C and |Γ|², so
    // ∇I(end)ᵀ M_k = ∇I(start)ᵀ without the error (∇I(x_{k+1}) − ∇I(end))ᵀ M_k of a basis at
    // the next start (multiple shooting's matching residual, or single shooting's x_T − x0).
    const Mat6 Q_end = aligned(adapted_basis(body, pieces[k].end), Q_next);
    const Mat6 B = Q_end.transpose() * pieces[k].monodromy * Q;
    b.defect = std::max({b.defect, B.topRightCorner<3, 3>().cwiseAbs().maxCoeff(), B.block<2, 1>(4, 3).cwiseAbs().maxCoeff()});
    b.N = B.topLeftCorner<3, 3>() * b.N;
    b.flow *= B(3, 3);
    const Eigen::Matrix2d P_k = B.bottomRightCorner<2, 2>();
    b.P = P_k * b.P;
    b.det_P *= P_k.determinant();
    Q = Q_next;
  }
  return b;
}

/// The roots of μ² − tr μ + det: the larger by the formula, the smaller as det over it
/// (no cancellation), so μ₄μ₅ = det to round-off; a complex pair when tr² < 4 det.
std::array<std::complex<double>, 2> pair_of(double tr, double det) {
  const double disc = tr * tr - 4.0 * det;
  if (disc < 0.0) {
    const std::complex<double> mu(0.5 * tr, 0.5 * std::sqrt(-disc));
    return {mu, std::conj(mu)};
  }
  const double big = 0.5 * (tr + std::copysign(std::sqrt(disc), tr));
  return {big, big != 0.0 ? det / big : 0.0};
}

}  // namespace

void classify_orbit(const PeriodicFlow& body, PeriodicOrbit& o) {
  const std::vector<MonodromyPiece> whole{{o.x0, o.x0, o.monodromy}};
  const BlockProduct b = block_product(body, o.pieces.empty() ? whole : o.pieces);
  o.invariance_defect = b.defect;
  o.reduced_monodromy = b.P;
  o.section_basis = b.Q0.rightCols<2>();
  o.reduced_trace = b.P.trace();
  const Eigen::EigenSolver<Eigen::Matrix3d> normal(b.N, false);
  std::array<std::complex<double>, 6> mu{};
  for (int k = 0; k < 3; ++k) mu[static_cast<std::size_t>(k)] = normal.eigenvalues()(k);
  mu[3] = b.flow;
  const auto pair = pair_of(o.reduced_trace, b.det_P);
  mu[4] = pair[0], mu[5] = pair[1];
  std::sort(mu.begin(), mu.begin() + 4, [](auto a, auto c) { return std::abs(a - 1.0) < std::abs(c - 1.0); });
  o.multipliers = mu;
  std::complex<double> product = 1.0;
  o.trivial_deviation = 0.0;
  for (std::size_t k = 0; k < 6; ++k) {
    product *= mu[k];
    if (k < 4) o.trivial_deviation = std::max(o.trivial_deviation, std::abs(mu[k] - 1.0));
  }
  o.product_deviation = std::abs(product - 1.0);
  // The nontrivial pair (μ, 1/μ) of the 2×2 P: on the unit circle (|tr P| < 2),
  // real positive (tr P > 2) or real negative (tr P < −2). |tr P| within
  // 1e-10 of 2 (|μ| − 1 below 1e-5: round-off cannot tell) counts as elliptic.
  const double tr = o.reduced_trace;
  o.stability = std::abs(tr) <= 2.0 + 1e-10 ? "elliptic" : (tr > 0.0 ? "hyperbolic" : "inverse_hyperbolic");
  o.degenerate = o.rank_ratio < 1e-7 && std::abs(mu[5] - 1.0) <= 1e-5 && std::abs(mu[4] - 1.0) <= 1e-5;
}

}  // namespace lgi::experiments
