// Spectral statistics of a quantum top (quantum_statistics.hpp).
#include "experiments/analysis/quantum/quantum_statistics.hpp"

#include <algorithm>
#include <memory>
#include <set>

#include "experiments/analysis/quantum/lowest_levels.hpp"  // SolveInterrupted
#include "experiments/analysis/quantum/weyl_law.hpp"
#include "experiments/analysis/spectral/brody_fit.hpp"

namespace lgi::experiments::quantum {

std::vector<QuantumClassStatistics> quantum_statistics(const QuantumSpectrum& q, double hbar, int m,
                                                       const spectral::StatisticsOptions& options, double energy_low,
                                                       double energy_high, const std::atomic<bool>* stop) {
  const QuantumTop& top = q.top;
  // Labels: 4j + parity for a free body (parity ∈ 0..3, or 0 where −1), the parity otherwise.
  std::vector<double> energies;
  std::vector<int> labels;
  std::set<int> classes;
  for (const QuantumLevel& l : q.levels) {
    if (!l.converged || !(l.energy >= energy_low && l.energy <= energy_high)) continue;
    if (top.symmetry == TopSymmetry::symmetric_heavy && m == 0 && l.k < 0) continue;
    energies.push_back(l.energy);
    labels.push_back(top.is_free() ? 4 * l.j + std::max(l.parity, 0)
                                   : (top.symmetry == TopSymmetry::symmetric_heavy ? 0 : l.parity));
    classes.insert(labels.back());
  }
  spectral::ClassCounting counting;
  if (top.is_free()) {
    const double share = top.symmetry == TopSymmetry::free_asymmetric ? 0.25 : 1.0;
    const Eigen::Vector3d J = top.moments;
    counting = [J, hbar, share, stop](int label, double e) {
      if (stop != nullptr && stop->load(std::memory_order_relaxed)) throw SolveInterrupted();
      return share * free_rotor_weyl_count(J, hbar, label / 4, e);
    };
  } else {
    const auto weyl = std::make_shared<WeylCounting>(top, hbar, m);
    const double share = top.symmetry == TopSymmetry::symmetric_heavy
                             ? (m == 0 ? 0.5 : 1.0)
                             : 1.0 / static_cast<double>(std::max<std::size_t>(classes.size(), 1));
    counting = [weyl, share, stop](int, double e) {
      if (stop != nullptr && stop->load(std::memory_order_relaxed)) throw SolveInterrupted();
      return share * (*weyl)(e);
    };
  }
  std::vector<QuantumClassStatistics> out;
  for (spectral::ClassStatistics& c : spectral::statistics_by_class(energies, labels, counting, options)) {
    QuantumClassStatistics r;
    r.j = top.is_free() ? c.label / 4 : -1;
    r.parity = top.is_free() ? (top.symmetry == TopSymmetry::free_asymmetric ? c.label % 4 : -1)
                             : (top.symmetry == TopSymmetry::symmetric_heavy ? -1 : c.label);
    r.statistics = std::move(c);
    out.push_back(std::move(r));
  }
  return out;
}

PooledBrody pooled_brody(const std::vector<QuantumClassStatistics>& classes) {
  std::vector<double> all;
  for (const QuantumClassStatistics& c : classes)
    if (!c.statistics.too_few) all.insert(all.end(), c.statistics.statistics.spacings.begin(),
                                          c.statistics.statistics.spacings.end());
  PooledBrody p;
  p.spacings = all.size();
  if (all.size() >= 2) p.fit = spectral::fit_brody(all);
  return p;
}

}  // namespace lgi::experiments::quantum
