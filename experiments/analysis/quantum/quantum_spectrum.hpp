#pragma once
// The lowest levels of a quantum top (quantum_top.hpp) at fixed m, with
// their quantum numbers and their convergence in jmax (experiments/QUANTUM.md):
//  - a free body: every level of every j = |m|..jmax (Ĥ commutes with L̂²),
//    each j block exact; per j the D₂ classes of the asymmetric rotor
//    (Wang's combinations |j,k⟩ ± (−1)^j |j,−k⟩, King, Hainer & Cross,
//    J. Chem. Phys. 11 (1943) 27), or k for a symmetric rotor;
//  - a heavy top: the lowest `levels` levels of the block cut at jmax, per
//    conserved k or per class where one applies; each compared with the same
//    level (same block, same rank) of the block cut at jmax + jmax_step:
//    change_with_jmax = E(jmax + Δ) − E(jmax) (≤ 0: the cut is variational),
//    converged = |change| ≤ tol · max(|E|, ħ²/(2 J_min)).
#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "experiments/analysis/quantum/quantum_top.hpp"

namespace lgi::experiments::quantum {

struct QuantumSettings {
  double hbar = 0.0;
  int m = 0;
  int jmax = 40;
  int levels = 20;     // heavy tops: how many of the lowest levels
  int jmax_step = 4;   // Δ of the convergence check
  double tol = 1e-8;   // of the convergence check, relative (above)
  bool use_symmetry = true;  // false: one block for a heavy top (a check of the blocks)
  // Heavy tops: called after each eigenvalue solve (two per block: cut at jmax and at
  // jmax + jmax_step) with the solves done and their number (lgi quantum's progress line).
  std::function<void(int, int)> solved;
  // Ctrl-C (lgi quantum): read between the blocks, between a free body's j and inside each
  // Lanczos solve (lowest_levels.hpp); once set, quantum_spectrum throws SolveInterrupted.
  const std::atomic<bool>* stop = nullptr;
};

struct QuantumLevel {
  double energy = 0.0;
  int j = -1;                // −1 unless j is conserved (a free body)
  int k = -1;                // −1 unless k is conserved (k_conserved)
  bool k_conserved = false;
  int parity = -1;           // the symmetry class (QuantumSpectrum::parity_classes), −1 if none
  bool converged = false;
  double change_with_jmax = 0.0;
};

struct QuantumSpectrum {
  std::vector<QuantumLevel> levels;  // ascending in energy
  QuantumTop top;
  Eigen::Index dimension = 0;        // of the block cut at jmax (all classes)
  Eigen::Index dimension_check = 0;  // of the block cut at jmax + Δ
  double energy_unit = 0.0;          // ħ²/(2 J_min), the floor of the tolerance's scale
  std::string method;                // the eigensolver(s) used
  std::string parity_classes;        // what `parity` means
};

/// Throws std::invalid_argument for settings out of range (hbar ≤ 0, jmax < |m|, ...),
/// SolveInterrupted (lowest_levels.hpp) once settings.stop is set.
QuantumSpectrum quantum_spectrum(const QuantumTop& top, const QuantumSettings& settings);

}  // namespace lgi::experiments::quantum
