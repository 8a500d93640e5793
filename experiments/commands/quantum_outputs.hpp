#pragma once
// The optional groups of lgi quantum (experiments/QUANTUM.md): /ebk (--ebk,
// EBK levels beside the exact ones: a Lagrange top, a free body or a
// Kovalevskaya top) and /statistics
// (--statistics, per symmetry class, unfolded with Weyl's law).
#include <atomic>
#include <string>
#include <vector>

#include "experiments/analysis/quantum/quantum_spectrum.hpp"
#include "experiments/io/table_file.hpp"
#include "integrators/system/scene.hpp"

namespace lgi::experiments {

/// /ebk: n, m, k, energy_ebk, energy_exact, difference, converged, j, axis, n_fast (one row per level).
/// A Kovalevskaya top (its scene given) gets the EBK levels of its numerical tori; each solved level
/// adds a line to `notes`; its tori read `stop` (Ctrl-C: quantum::SolveInterrupted).
TableGroup ebk_group(const quantum::QuantumSpectrum& spectrum, double hbar, int m,
                     const system::Scene* kovalevskaya = nullptr, std::vector<std::string>* notes = nullptr,
                     const std::atomic<bool>* stop = nullptr);

/// /weyl: weyl_count, Weyl's smooth count N̄(E) at each /spectrum row's energy
/// (a free body: N̄_j(E) of the row's j).
/// `stop` (Ctrl-C), read before each row: once set, SolveInterrupted.
TableGroup weyl_group(const quantum::QuantumSpectrum& spectrum, double hbar, int m,
                      const std::atomic<bool>* stop = nullptr);

/// /statistics: per class (j, parity, levels, Brody β ± error, ...), the
/// spacing histograms (classes × bins), Σ²(L) and Δ₃(L) (classes × lengths)
/// and the Poisson and GOE references.
/// Only converged levels with energy_low ≤ E ≤ energy_high enter; the attributes state the window and
/// the Brody fit of all classes' spacings pooled.
/// `stop` (Ctrl-C): read at every Weyl count (quantum_statistics.hpp); once set, SolveInterrupted.
TableGroup statistics_group(const quantum::QuantumSpectrum& spectrum, double hbar, int m, double energy_low,
                            double energy_high, const std::atomic<bool>* stop = nullptr);

}  // namespace lgi::experiments
