#include "experiments/analysis/quantum/quantum_spectrum.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

#include "experiments/analysis/quantum/lowest_levels.hpp"
#include "experiments/analysis/quantum/rotor_operators.hpp"

namespace lgi::experiments::quantum {
namespace {

using Index = Eigen::Index;

constexpr const char* d2_classes =
    "free asymmetric rotor, D2 classes by the rotations by pi about body axes 3 and 1: "
    "parity = 2 [C2(3) = -1] + [C2(1) = -1]: 0 = A, 1 = B1, 2 = B3, 3 = B2 (C2(3) = (-1)^k, "
    "C2(1) |j,k> = (-1)^j |j,-k>)";
constexpr const char* c2_classes =
    "c on principal axis 3 of the frame: parity = 0 where C2(3) = +1 (even k), 1 where C2(3) = -1 (odd k)";
constexpr const char* c2_reflection_classes =
    "c on principal axis 3 of the frame, m = 0: parity = 2 [C2(3) = -1] + [U = -1], C2(3) = (-1)^k, U the "
    "reflection in the 1-3 plane, U |j,k,0> = (-1)^k |j,-k,0>";
constexpr const char* reflection_classes =
    "c in the 1-3 plane of the frame, m = 0: parity = 0 where U = +1, 1 where U = -1, U the reflection in the "
    "1-3 plane, U |j,k,0> = (-1)^k |j,-k,0>";

/// The free body's j block, split by D₂ class: rows of Wang's combinations
/// (|k⟩ + s|−k⟩)/√2, s = cx (−1)^j, k ≥ 0 of parity (1 − cz)/2 (k = 0 alone where cx = (−1)^j).
Eigen::MatrixXd wang_vectors(int j, int cz, int cx) {
  const int sj = j % 2 ? -1 : 1;
  std::vector<Eigen::VectorXd> cols;
  for (int k = (cz == 1 ? 0 : 1); k <= j; k += 2) {
    Eigen::VectorXd v = Eigen::VectorXd::Zero(2 * j + 1);
    if (k == 0) {
      if (cx != sj) continue;
      v(j) = 1.0;
    } else {
      v(j + k) = std::sqrt(0.5);
      v(j - k) = cx * sj * std::sqrt(0.5);
    }
    cols.push_back(v);
  }
  Eigen::MatrixXd w(2 * j + 1, static_cast<Index>(cols.size()));
  for (std::size_t i = 0; i < cols.size(); ++i) w.col(static_cast<Index>(i)) = cols[i];
  return w;
}

void free_levels(const QuantumTop& top, const QuantumSettings& s, QuantumSpectrum& out) {
  const bool symmetric = top.symmetry == TopSymmetry::free_symmetric;
  for (int j = std::abs(s.m); j <= s.jmax; ++j) {
    if (s.stop && s.stop->load(std::memory_order_relaxed)) throw SolveInterrupted();
    const WignerBasis b = WignerBasis::single(s.m, j);
    const Eigen::MatrixXd t = Eigen::MatrixXd(kinetic_energy(rotor_operators(b, s.hbar), top.moments).real());
    std::vector<QuantumLevel> block;
    if (symmetric) {  // T is diagonal in k (J₁ = J₂)
      for (int k = -j; k <= j; ++k) block.push_back({t(j + k, j + k), j, k, true, -1, true, 0.0});
    } else {
      for (const int cz : {1, -1})
        for (const int cx : {1, -1}) {
          const Eigen::MatrixXd w = wang_vectors(j, cz, cx);
          if (w.cols() == 0) continue;
          const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(w.transpose() * t * w, Eigen::EigenvaluesOnly);
          const int parity = 2 * (cz == -1 ? 1 : 0) + (cx == -1 ? 1 : 0);
          for (Index i = 0; i < es.eigenvalues().size(); ++i)
            block.push_back({es.eigenvalues()(i), j, -1, false, parity, true, 0.0});
        }
    }
    std::sort(block.begin(), block.end(), [](const auto& x, const auto& y) { return x.energy < y.energy; });
    out.levels.insert(out.levels.end(), block.begin(), block.end());
    out.dimension += 2 * j + 1;
  }
  out.dimension_check = out.dimension;
  out.method = "dense, per j block (exact: Ĥ commutes with L̂², no cut)";
  out.parity_classes = symmetric ? "none (k is conserved)" : d2_classes;
}

/// A block of the heavy top: its basis vectors as the columns of a real
/// sparse matrix over the basis up to jmax + Δ, ordered by j, so that the
/// first `cols_cut` columns (those with j ≤ jmax) span the block cut at jmax.
struct Block {
  std::vector<Eigen::Triplet<Complex>> entries;
  Index cols = 0, cols_cut = 0;
  int k = -1, parity = -1;
};

/// A class of basis vectors: plain |j,k⟩ (of one k, or one parity of k, or
/// all), or the reflection's combinations; labelled (k, parity) in the output.
struct ClassSpec {
  int k = -1, parity = -1;
  int k_parity = -1;  // 0 / 1: only k of this parity; −1: any
  int k_only = 0;     // with exact_k: only this k
  bool exact_k = false;
  int reflection = 0;  // ±1: Wang-type vectors (|k⟩ + ε(−1)^k|−k⟩)/√2 of the m = 0 reflection; 0: plain |k⟩
};

Block make_block(const ClassSpec& c, const WignerBasis& big, int jmax) {
  Block bl{{}, 0, 0, c.k, c.parity};
  const double r = std::sqrt(0.5);
  for (int j = big.jlo; j <= big.jhi; ++j) {
    for (int k = (c.reflection != 0 ? 0 : -j); k <= j; ++k) {
      if (c.exact_k && k != c.k_only) continue;
      if (c.k_parity >= 0 && std::abs(k) % 2 != c.k_parity) continue;
      if (c.reflection == 0 || k == 0) {
        if (c.reflection == -1) continue;  // |j, 0⟩ is even under the reflection
        bl.entries.emplace_back(big.index(j, k), bl.cols, 1.0);
      } else {
        bl.entries.emplace_back(big.index(j, k), bl.cols, r);
        bl.entries.emplace_back(big.index(j, -k), bl.cols, c.reflection * (k % 2 ? -r : r));
      }
      ++bl.cols;
      if (j <= jmax) ++bl.cols_cut;
    }
  }
  return bl;
}

/// The classes of a heavy top (docs/quantum.md §4). At m = 0 with c₂ = 0 the
/// reflection of the body in its 1–3 plane keeps the block: U|j,k,0⟩ = (−1)^k |j,−k,0⟩.
std::vector<ClassSpec> heavy_classes(const QuantumTop& top, const QuantumSettings& s, int kmax) {
  std::vector<ClassSpec> classes;
  const bool reflection = s.use_symmetry && s.m == 0 && top.is_real();
  if (s.use_symmetry && top.symmetry == TopSymmetry::symmetric_heavy) {
    for (int k = -kmax; k <= kmax; ++k) classes.push_back({k, -1, -1, k, true, 0});
  } else if (s.use_symmetry && top.symmetry == TopSymmetry::axial_heavy) {
    for (const int p : {0, 1}) {
      if (!reflection) classes.push_back({-1, p, p, 0, false, 0});
      else
        for (const int e : {1, -1}) classes.push_back({-1, 2 * p + (e == -1 ? 1 : 0), p, 0, false, e});
    }
  } else if (reflection) {
    for (const int e : {1, -1}) classes.push_back({-1, e == -1 ? 1 : 0, -1, 0, false, e});
  } else {
    classes.push_back({-1, -1, -1, 0, false, 0});
  }
  return classes;
}

std::string parity_classes_of(const QuantumTop& top, const QuantumSettings& s) {
  const bool reflection = s.use_symmetry && s.m == 0 && top.is_real();
  if (s.use_symmetry && top.symmetry == TopSymmetry::axial_heavy)
    return reflection ? c2_reflection_classes : c2_classes;
  if (s.use_symmetry && top.symmetry == TopSymmetry::symmetric_heavy) return "none (k is conserved)";
  return reflection ? reflection_classes : "none (-1)";
}

void heavy_levels(const QuantumTop& top, const QuantumSettings& s, QuantumSpectrum& out) {
  const WignerBasis big = WignerBasis::up_to(s.m, s.jmax + s.jmax_step);
  const RotorOperators ops = rotor_operators(big, s.hbar);
  const ComplexSparse h = kinetic_energy(ops, top.moments) + potential_energy(ops, top.weight);
  const double lower = -top.weight.norm();  // T ≥ 0 and c·Γ̂ ≥ −|c| on any cut
  const bool k_conserved = s.use_symmetry && top.symmetry == TopSymmetry::symmetric_heavy;
  std::set<std::string> methods;
  std::vector<QuantumLevel> all;
  const std::vector<ClassSpec> classes = heavy_classes(top, s, big.jhi);
  const int solves = 2 * static_cast<int>(classes.size());
  int done = 0;
  for (const ClassSpec& c : classes) {
    if (s.stop && s.stop->load(std::memory_order_relaxed)) throw SolveInterrupted();
    const Block bl = make_block(c, big, s.jmax);
    if (bl.cols_cut == 0) {
      if (s.solved) s.solved(done += 2, solves);
      continue;
    }
    ComplexSparse w(h.rows(), bl.cols);
    w.setFromTriplets(bl.entries.begin(), bl.entries.end());
    const ComplexSparse hb = ComplexSparse(w.adjoint() * h * w);
    const LowestLevels cut =
        lowest_levels(ComplexSparse(hb.topLeftCorner(bl.cols_cut, bl.cols_cut)), s.levels, lower, s.stop);
    if (s.solved) s.solved(++done, solves);
    const LowestLevels check = lowest_levels(hb, s.levels, lower, s.stop);
    if (s.solved) s.solved(++done, solves);
    methods.insert(cut.method), methods.insert(check.method);
    for (std::size_t i = 0; i < cut.values.size(); ++i) {
      QuantumLevel l{cut.values[i], -1, k_conserved ? bl.k : -1, k_conserved, bl.parity, false, 0.0};
      l.change_with_jmax = check.values[i] - cut.values[i];
      l.converged = std::abs(l.change_with_jmax) <= s.tol * std::max(std::abs(l.energy), out.energy_unit);
      all.push_back(l);
    }
    out.dimension += bl.cols_cut;
    out.dimension_check += bl.cols;
  }
  std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.energy < b.energy; });
  if (all.size() > static_cast<std::size_t>(s.levels)) all.resize(static_cast<std::size_t>(s.levels));
  out.levels = std::move(all);
  for (const std::string& m : methods) out.method += (out.method.empty() ? "" : "; ") + m;
  out.parity_classes = parity_classes_of(top, s);
}

}  // namespace

QuantumSpectrum quantum_spectrum(const QuantumTop& top, const QuantumSettings& s) {
  if (!(s.hbar > 0.0) || !std::isfinite(s.hbar)) throw std::invalid_argument("hbar: must be a positive number");
  if (s.jmax > 400) throw std::invalid_argument("jmax: at most 400");
  if (s.m < -s.jmax || s.m > s.jmax) throw std::invalid_argument("jmax: must be at least |m|");
  if (s.levels < 1) throw std::invalid_argument("levels: must be at least 1");
  if (s.jmax_step < 1 || s.jmax_step > 100) throw std::invalid_argument("jmax_step: must be in 1..100");
  if (!(s.tol > 0.0)) throw std::invalid_argument("tol: must be a positive number");
  QuantumSpectrum out;
  out.top = top;
  out.energy_unit = s.hbar * s.hbar / (2.0 * top.moments.minCoeff());
  if (top.is_free())
    free_levels(top, s, out);
  else
    heavy_levels(top, s, out);
  return out;
}

}  // namespace lgi::experiments::quantum
