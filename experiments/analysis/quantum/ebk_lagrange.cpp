// EBK levels of the Lagrange top (ebk_lagrange.hpp; docs/quantum.md §7).
#include "experiments/analysis/quantum/ebk_lagrange.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

namespace lgi::experiments::quantum {
namespace {

/// I_θ at energy h, 0 where no torus exists (below the bottom, or on it).
double nutation_action(const LagrangeBody& b, double l, double L3, double h) {
  const auto a = lagrange_actions(b, l, L3, h);
  return a ? a->actions(2) : 0.0;
}

}  // namespace

std::optional<double> ebk_lagrange_level(const LagrangeBody& b, double hbar, int n, int m, int k, double energy_cap) {
  const double l = m * hbar, L3 = k * hbar, target = hbar * (n + 0.5);
  // Below −|w| + L3²/(2C) no torus exists (the centrifugal term is ≥ 0).
  double lo = -std::abs(b.w) + L3 * L3 / (2.0 * b.C);
  double step = std::max(hbar, 1e-3 * (std::abs(b.w) + 1.0)), hi = lo + step;
  while (nutation_action(b, l, L3, hi) < target) {
    lo = hi, step *= 2.0, hi = lo + step;
    if (hi > energy_cap || !std::isfinite(hi)) return std::nullopt;
  }
  // I_θ increases with h (∂I_θ/∂h = J0/π): bisection keeps I(lo) < target ≤ I(hi).
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (nutation_action(b, l, L3, mid) < target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

std::vector<EbkRow> ebk_lagrange_table(const QuantumSpectrum& q, double hbar, int m) {
  if (q.top.symmetry != TopSymmetry::symmetric_heavy)
    throw std::invalid_argument("--ebk: needs a Lagrange top (J1 = J2, centre of mass on the symmetry axis)");
  const LagrangeBody body{q.top.moments(0), q.top.moments(2), q.top.weight(2)};
  // The levels are in ascending energy, so a level's rank among those of its
  // k is its rank n in the k block (the lowest levels of each block come first).
  std::map<int, int> seen;
  std::vector<EbkRow> rows;
  rows.reserve(q.levels.size());
  for (const QuantumLevel& l : q.levels) {
    EbkRow r;
    r.n = seen[l.k]++, r.m = m, r.k = l.k, r.energy_exact = l.energy, r.converged = l.converged;
    const auto e = ebk_lagrange_level(body, hbar, r.n, m, l.k);
    r.energy_ebk = e ? *e : std::numeric_limits<double>::quiet_NaN();
    rows.push_back(r);
  }
  return rows;
}

}  // namespace lgi::experiments::quantum
