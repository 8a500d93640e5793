#include "experiments/analysis/quantum/lowest_levels.hpp"

#include <Eigen/Dense>
#include <Spectra/MatOp/SparseSymShiftSolve.h>
#include <Spectra/SymEigsShiftSolver.h>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lgi::experiments::quantum {
namespace {

using RealSparse = Eigen::SparseMatrix<double>;

bool is_real(const ComplexSparse& h) {
  for (Eigen::Index c = 0; c < h.outerSize(); ++c)
    for (ComplexSparse::InnerIterator it(h, c); it; ++it)
      if (it.value().imag() != 0.0) return false;
  return true;
}

/// [[A, −B], [B, A]] for h = A + iB (or A alone when `real`).
RealSparse real_form(const ComplexSparse& h, bool real) {
  const Eigen::Index n = h.rows();
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<std::size_t>(h.nonZeros()) * (real ? 1 : 4));
  for (Eigen::Index c = 0; c < h.outerSize(); ++c)
    for (ComplexSparse::InnerIterator it(h, c); it; ++it) {
      const Eigen::Index r = it.row();
      const double a = it.value().real(), b = it.value().imag();
      t.emplace_back(r, c, a);
      if (real) continue;
      t.emplace_back(r + n, c + n, a);
      if (b != 0.0) t.emplace_back(r + n, c, b), t.emplace_back(r, c + n, -b);
    }
  RealSparse m(real ? n : 2 * n, real ? n : 2 * n);
  m.setFromTriplets(t.begin(), t.end());
  m.makeCompressed();
  return m;
}

/// How many distinct complex eigenvectors the real form's vectors z = x + iy span
/// (a copy (−y, x) of (x, y) is i z, the same complex line).
int complex_rank(const Eigen::MatrixXd& vectors, Eigen::Index n) {
  const Eigen::MatrixXcd z = vectors.topRows(n).cast<Complex>() + Complex(0.0, 1.0) * vectors.bottomRows(n).cast<Complex>();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXcd> gram(z.adjoint() * z, Eigen::EigenvaluesOnly);
  return static_cast<int>((gram.eigenvalues().array() > 1e-6).count());
}

/// Spectra's shift-solve operation that reads `stop` before every product and
/// throws SolveInterrupted once it is set: Spectra's own loop has no stop flag.
class CheckedShiftSolve {
 public:
  using Scalar = double;
  CheckedShiftSolve(const RealSparse& m, const std::atomic<bool>* stop) : op_(m), stop_(stop) {}
  Eigen::Index rows() const { return op_.rows(); }
  Eigen::Index cols() const { return op_.cols(); }
  void set_shift(double sigma) { op_.set_shift(sigma); }
  void perform_op(const double* x_in, double* y_out) const {
    if (stop_ && stop_->load(std::memory_order_relaxed)) throw SolveInterrupted();
    op_.perform_op(x_in, y_out);
  }

 private:
  Spectra::SparseSymShiftSolve<double> op_;
  const std::atomic<bool>* stop_;
};

std::vector<double> spectra_lowest(const RealSparse& m, Eigen::Index nev, double sigma, Eigen::MatrixXd* vectors,
                                   const std::atomic<bool>* stop) {
  CheckedShiftSolve op(m, stop);
  const Eigen::Index ncv = std::min<Eigen::Index>(m.rows(), std::max<Eigen::Index>(2 * nev + 1, nev + 20));
  Spectra::SymEigsShiftSolver<CheckedShiftSolve> eigs(op, nev, ncv, sigma);
  eigs.init();
  eigs.compute(Spectra::SortRule::LargestMagn, 1000, 1e-12, Spectra::SortRule::SmallestAlge);
  if (eigs.info() != Spectra::CompInfo::Successful)
    throw std::runtime_error("quantum: Spectra's Lanczos did not converge for " + std::to_string(nev) +
                             " eigenvalues of a matrix of " + std::to_string(m.rows()) + " rows");
  const Eigen::VectorXd v = eigs.eigenvalues();
  std::vector<Eigen::Index> order(static_cast<std::size_t>(v.size()));
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<Eigen::Index>(i);
  std::sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) { return v(a) < v(b); });
  std::vector<double> out;
  for (const Eigen::Index i : order) out.push_back(v(i));
  if (vectors) {
    const Eigen::MatrixXd all = eigs.eigenvectors();
    vectors->resize(all.rows(), all.cols());
    for (std::size_t i = 0; i < order.size(); ++i) vectors->col(static_cast<Eigen::Index>(i)) = all.col(order[i]);
  }
  return out;
}

/// The lowest n distinct-vector levels of the real form of a complex h.
std::vector<double> complex_lowest(const RealSparse& m, Eigen::Index n, Eigen::Index size, double sigma,
                                   const std::atomic<bool>* stop) {
  const Eigen::Index nev = std::min<Eigen::Index>(2 * n + 2, m.rows() - 1);
  Eigen::MatrixXd vec;
  const std::vector<double> v = spectra_lowest(m, nev, sigma, &vec, stop);  // ascending, with their vectors
  std::vector<double> out;
  const double scale = std::max(std::abs(v.front()), std::abs(v.back())) + 1e-300;
  for (std::size_t a = 0; a < v.size();) {
    std::size_t b = a + 1;
    while (b < v.size() && v[b] - v[b - 1] <= 1e-9 * scale) ++b;  // a cluster of equal values
    const int r = complex_rank(vec.middleCols(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b - a)), size);
    for (int i = 0; i < r; ++i) out.push_back(v[a]);
    a = b;
  }
  // 2n + 2 real vectors hold at least n + 1 distinct complex ones: keep the lowest n.
  out.resize(std::min<std::size_t>(out.size(), static_cast<std::size_t>(n)));
  return out;
}

}  // namespace

std::vector<double> all_levels(const ComplexSparse& h) {
  if (is_real(h)) {
    const Eigen::MatrixXd a = Eigen::MatrixXd(h.real());
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(a, Eigen::EigenvaluesOnly);
    return {es.eigenvalues().data(), es.eigenvalues().data() + es.eigenvalues().size()};
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXcd> es(Eigen::MatrixXcd(h), Eigen::EigenvaluesOnly);
  return {es.eigenvalues().data(), es.eigenvalues().data() + es.eigenvalues().size()};
}

LowestLevels lowest_levels(const ComplexSparse& h, Eigen::Index n, double lower_bound, const std::atomic<bool>* stop) {
  const auto stopped = [stop] { return stop && stop->load(std::memory_order_relaxed); };
  if (stopped()) throw SolveInterrupted();
  const Eigen::Index size = h.rows();
  n = std::min(n, size);
  LowestLevels out;
  if (n <= 0) return out;
  if (size <= dense_limit || 8 * n >= size) {  // many levels: the dense solver is faster than Lanczos
    out.values = all_levels(h);
    if (stopped()) throw SolveInterrupted();
    out.values.resize(static_cast<std::size_t>(n));
    out.method = "dense";
    return out;
  }
  // A shift below the spectrum by a small fraction of its width keeps (Ĥ − σ) well conditioned.
  double width = 0.0;
  for (Eigen::Index c = 0; c < h.outerSize(); ++c)
    for (ComplexSparse::InnerIterator it(h, c); it; ++it) width = std::max(width, std::abs(it.value()));
  const double sigma = lower_bound - 1e-3 * std::max(width, 1e-300);
  if (is_real(h)) {
    out.values = spectra_lowest(real_form(h, true), n, sigma, nullptr, stop);
    out.method = "spectra shift-invert lanczos (real symmetric)";
  } else {
    out.values = complex_lowest(real_form(h, false), n, size, sigma, stop);
    out.method = "spectra shift-invert lanczos (complex hermitian as its real 2n form)";
  }
  return out;
}

}  // namespace lgi::experiments::quantum
