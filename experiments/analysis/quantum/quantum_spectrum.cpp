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

/// The rows and columns of `idx` (ascending) of h.
ComplexSparse restrict_to(const ComplexSparse& h, const std::vector<Index>& idx) {
  std::vector<Index> map(static_cast<std::size_t>(h.rows()), -1);
  for (std::size_t i = 0; i < idx.size(); ++i) map[static_cast<std::size_t>(idx[i])] = static_cast<Index>(i);
  std::vector<Eigen::Triplet<Complex>> t;
  for (Index c = 0; c < h.outerSize(); ++c) {
    const Index cc = map[static_cast<std::size_t>(c)];
    if (cc < 0) continue;
    for (ComplexSparse::InnerIterator it(h, c); it; ++it) {
      const Index rr = map[static_cast<std::size_t>(it.row())];
      if (rr >= 0) t.emplace_back(rr, cc, it.value());
    }
  }
  ComplexSparse out(static_cast<Index>(idx.size()), static_cast<Index>(idx.size()));
  out.setFromTriplets(t.begin(), t.end());
  out.makeCompressed();
  return out;
}

/// A block of the heavy top: its basis positions (in the basis up to jmax + Δ,
/// whose leading part is the basis up to jmax) and its labels.
struct Block {
  std::vector<Index> idx, idx_cut;  // cut: the positions with j ≤ jmax
  int k = -1, parity = -1;
};

std::vector<Block> heavy_blocks(const QuantumTop& top, const WignerBasis& big, int jmax) {
  std::vector<Block> blocks;
  const auto add = [&](auto&& member, int k, int parity) {
    Block bl{{}, {}, k, parity};
    for (int j = big.jlo; j <= big.jhi; ++j)
      for (int kk = -j; kk <= j; ++kk)
        if (member(kk)) {
          bl.idx.push_back(big.index(j, kk));
          if (j <= jmax) bl.idx_cut.push_back(big.index(j, kk));
        }
    if (!bl.idx_cut.empty()) blocks.push_back(std::move(bl));
  };
  if (top.symmetry == TopSymmetry::symmetric_heavy) {
    for (int k = -big.jhi; k <= big.jhi; ++k) add([k](int kk) { return kk == k; }, k, -1);
  } else if (top.symmetry == TopSymmetry::axial_heavy) {
    add([](int kk) { return kk % 2 == 0; }, -1, 0);
    add([](int kk) { return kk % 2 != 0; }, -1, 1);
  } else {
    add([](int) { return true; }, -1, -1);
  }
  return blocks;
}

void heavy_levels(const QuantumTop& top, const QuantumSettings& s, QuantumSpectrum& out) {
  const WignerBasis big = WignerBasis::up_to(s.m, s.jmax + s.jmax_step);
  const RotorOperators ops = rotor_operators(big, s.hbar);
  const ComplexSparse h = kinetic_energy(ops, top.moments) + potential_energy(ops, top.weight);
  const double lower = -top.weight.norm();  // T ≥ 0 and c·Γ̂ ≥ −|c| on any cut
  const bool k_conserved = top.symmetry == TopSymmetry::symmetric_heavy;
  std::set<std::string> methods;
  std::vector<QuantumLevel> all;
  for (const Block& bl : heavy_blocks(top, big, s.jmax)) {
    const LowestLevels cut = lowest_levels(restrict_to(h, bl.idx_cut), s.levels, lower);
    const LowestLevels check = lowest_levels(restrict_to(h, bl.idx), s.levels, lower);
    methods.insert(cut.method), methods.insert(check.method);
    for (std::size_t i = 0; i < cut.values.size(); ++i) {
      QuantumLevel l{cut.values[i], -1, k_conserved ? bl.k : -1, k_conserved, bl.parity, false, 0.0};
      l.change_with_jmax = check.values[i] - cut.values[i];
      l.converged = std::abs(l.change_with_jmax) <= s.tol * std::max(std::abs(l.energy), out.energy_unit);
      all.push_back(l);
    }
    out.dimension += static_cast<Index>(bl.idx_cut.size());
    out.dimension_check += static_cast<Index>(bl.idx.size());
  }
  std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.energy < b.energy; });
  if (all.size() > static_cast<std::size_t>(s.levels)) all.resize(static_cast<std::size_t>(s.levels));
  out.levels = std::move(all);
  for (const std::string& m : methods) out.method += (out.method.empty() ? "" : "; ") + m;
  out.parity_classes = top.symmetry == TopSymmetry::axial_heavy ? c2_classes : "none (-1)";
}

}  // namespace

QuantumSpectrum quantum_spectrum(const QuantumTop& top, const QuantumSettings& s) {
  if (!(s.hbar > 0.0) || !std::isfinite(s.hbar)) throw std::invalid_argument("hbar: must be a positive number");
  if (s.jmax < std::abs(s.m)) throw std::invalid_argument("jmax: must be at least |m|");
  if (s.levels < 1) throw std::invalid_argument("levels: must be at least 1");
  if (s.jmax_step < 1) throw std::invalid_argument("jmax_step: must be at least 1");
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
