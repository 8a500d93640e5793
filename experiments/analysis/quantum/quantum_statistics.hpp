#pragma once
// The spectral statistics of a quantum top's levels, per symmetry class and
// unfolded with Weyl's law (weyl_law.hpp; docs/quantum.md §8;
// docs/spectral_statistics.md; experiments/QUANTUM.md):
//  - a free body: per j and D₂ class (`parity`), unfolded by N̄_j(E)/4 (an
//    asymmetric rotor) or per j by N̄_j (a symmetric one, whose k, −k pairs
//    are degenerate and show as zero spacings);
//  - a symmetric heavy top (k conserved): all k together, which is the
//    integrable case of Berry & Tabor, unfolded by N̄(E); at m = 0 only
//    k ≥ 0 (E(k) = E(−k)) and by N̄(E)/2;
//  - otherwise per `parity` class, unfolded by N̄(E)/(number of classes).
// Only converged levels enter (a heavy top's unconverged levels are its highest),
// and only those with energy_low ≤ E ≤ energy_high (an energy window, to
// compare with the classical chaotic fraction at the same (ℓ, h)).
// `stop` (Ctrl-C in lgi quantum) is read at every Weyl count of the unfolding, so at least once
// per class: once set, SolveInterrupted (lowest_levels.hpp).
#include <atomic>
#include <limits>
#include <vector>

#include "experiments/analysis/quantum/quantum_spectrum.hpp"
#include "experiments/analysis/spectral/spectral_statistics.hpp"

namespace lgi::experiments::quantum {

struct QuantumClassStatistics {
  int j = -1;       // the free body's j, −1 otherwise
  int parity = -1;  // the class, −1 where none
  spectral::ClassStatistics statistics;
};

std::vector<QuantumClassStatistics> quantum_statistics(const QuantumSpectrum& spectrum, double hbar, int m,
                                                       const spectral::StatisticsOptions& options = {},
                                                       double energy_low = -std::numeric_limits<double>::infinity(),
                                                       double energy_high = std::numeric_limits<double>::infinity(),
                                                       const std::atomic<bool>* stop = nullptr);

/// The Brody fit of the spacings of every class with enough levels taken
/// together (each class unfolded and spaced on its own, then pooled; Haake ch. 4).
struct PooledBrody {
  spectral::BrodyFit fit;
  std::size_t spacings = 0;
};
PooledBrody pooled_brody(const std::vector<QuantumClassStatistics>& classes);

}  // namespace lgi::experiments::quantum
