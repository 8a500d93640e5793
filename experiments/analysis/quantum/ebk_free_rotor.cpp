// EBK levels of the free rotor at fixed j (ebk_free_rotor.hpp; docs/quantum.md §9).
#include "experiments/analysis/quantum/ebk_free_rotor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "experiments/analysis/actions.hpp"

namespace lgi::experiments::quantum {

std::optional<EulerCap> euler_cap_action(const Eigen::Vector3d& moments, double G, double h) {
  const auto a = euler_actions_at(moments, 0.0, G, h);
  if (!a) return std::nullopt;
  // I_l is the Deprit action with the pole on the largest axis (docs/actions.md §2):
  // about that axis I_l = G − I_cap, about the smallest I_l = I_cap.
  return EulerCap{a->around == a->pole ? G - a->actions(2) : a->actions(2), a->around};
}

std::optional<double> ebk_euler_level(const Eigen::Vector3d& J, double hbar, int j, int n, bool about_largest) {
  const double G = hbar * (j + 0.5), target = hbar * (n + 0.5);
  const double h_sep = G * G / (2.0 * (J.sum() - J.minCoeff() - J.maxCoeff()));
  // The open energy interval of the tori about the chosen axis: the steady
  // rotation (I_cap = 0) at one end, the separatrix at the other.
  const double h_steady = G * G / (2.0 * (about_largest ? J.maxCoeff() : J.minCoeff()));
  double inner = h_steady, outer = h_sep;  // I_cap(inner) < target ≤ I_cap(outer) is kept
  const auto cap = [&](double h) { const auto c = euler_cap_action(J, G, h); return c ? c->action : std::nan(""); };
  const double near_sep = h_sep + (h_steady - h_sep) * 1e-13;
  if (!(cap(near_sep) > target)) return std::nullopt;
  outer = near_sep;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (inner + outer);
    if (mid == inner || mid == outer) break;
    (cap(mid) < target ? inner : outer) = mid;
  }
  return 0.5 * (inner + outer);
}

namespace {

void asymmetric_rows(const QuantumSpectrum& q, double hbar, int m, std::vector<EbkRow>& rows) {
  const Eigen::Vector3d& J = q.top.moments;
  Eigen::Index largest = 0, smallest = 0;
  J.maxCoeff(&largest), J.minCoeff(&smallest);
  const double mid = J.sum() - J(largest) - J(smallest);
  for (std::size_t first = 0; first < q.levels.size();) {
    const int j = q.levels[first].j;
    std::size_t last = first;
    while (last < q.levels.size() && q.levels[last].j == j) ++last;
    const double G = hbar * (j + 0.5), h_sep = G * G / (2.0 * mid);
    const std::size_t size = last - first;
    for (std::size_t i = 0; i < size; ++i) {
      const QuantumLevel& l = q.levels[first + i];
      EbkRow r;
      const bool low = l.energy < h_sep;  // below the separatrix: about the largest axis
      r.n = static_cast<int>((low ? i : size - 1 - i) / 2), r.m = m, r.k = -1, r.j = j;
      r.axis = static_cast<int>(low ? largest : smallest);
      r.energy_exact = l.energy, r.converged = l.converged;
      const auto e = ebk_euler_level(J, hbar, j, r.n, low);
      r.energy_ebk = e ? *e : std::numeric_limits<double>::quiet_NaN();
      rows.push_back(r);
    }
    first = last;
  }
}

}  // namespace

std::vector<EbkRow> ebk_free_rotor_table(const QuantumSpectrum& q, double hbar, int m) {
  std::vector<EbkRow> rows;
  rows.reserve(q.levels.size());
  if (q.top.symmetry == TopSymmetry::free_asymmetric) {
    asymmetric_rows(q, hbar, m, rows);
  } else if (q.top.symmetry == TopSymmetry::free_symmetric) {
    const double A = q.top.moments(0), C = q.top.moments(2);
    for (const QuantumLevel& l : q.levels) {
      EbkRow r;
      r.n = l.j - std::abs(l.k), r.m = m, r.k = l.k, r.j = l.j, r.axis = 2;
      r.energy_exact = l.energy, r.converged = l.converged;
      r.energy_ebk = hbar * hbar * ((l.j + 0.5) * (l.j + 0.5) / (2.0 * A) + l.k * l.k * (0.5 / C - 0.5 / A));
      rows.push_back(r);
    }
  } else {
    throw std::invalid_argument("EBK of a free rotor: the top is not free");
  }
  return rows;
}

std::vector<EbkRow> ebk_table(const QuantumSpectrum& q, double hbar, int m) {
  if (q.top.is_free()) return ebk_free_rotor_table(q, hbar, m);
  if (q.top.symmetry == TopSymmetry::symmetric_heavy) return ebk_lagrange_table(q, hbar, m);
  throw std::invalid_argument("--ebk: needs a free body or a Lagrange top (J1 = J2, centre of mass on the symmetry "
                              "axis)");
}

}  // namespace lgi::experiments::quantum
