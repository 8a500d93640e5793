#include "experiments/analysis/periodic/lyapunov_families.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "experiments/analysis/cardan_equilibria.hpp"

namespace lgi::experiments {

namespace {

Vec6 state_of(const RelativeEquilibrium& e) {
  Vec6 x;
  x << e.angular_momentum, e.gamma;
  return x;
}

/// Minimum-norm Newton steps onto Π·Γ = ℓ, |Γ|² = 1 (a Cardan top: p1 = ℓ, q1 = 0).
Vec6 project_to_leaf(const PeriodicFlow& body, Vec6 x, double l) {
  const Eigen::Vector2d level = invariant_levels(body, 0.0, l).tail<2>();
  for (int it = 0; it < 8; ++it) {
    const Invariants inv = flow_invariants(body, x);
    const Eigen::Vector2d r = inv.value.tail<2>() - level;
    const Eigen::Matrix<double, 2, 6> G = inv.gradients.bottomRows<2>();
    x -= G.transpose() * (G * G.transpose()).ldlt().solve(r);
  }
  return x;
}

/// The real part of the eigenvector of the linearisation at x_e nearest iω, unit length.
Vec6 mode_direction(const PeriodicFlow& body, const Vec6& xe, double omega) {
  const Eigen::EigenSolver<Mat6> es(flow_jacobian(body, xe));
  int best = 0;
  for (int k = 1; k < 6; ++k)
    if (std::abs(es.eigenvalues()(k) - std::complex<double>(0.0, omega)) <
        std::abs(es.eigenvalues()(best) - std::complex<double>(0.0, omega)))
      best = k;
  Vec6 u = es.eigenvectors().col(best).real();
  if (u.norm() < 1e-3 * es.eigenvectors().col(best).norm()) u = es.eigenvectors().col(best).imag();
  return u.normalized();
}

/// Appends `family` and, with s.switch_branches, the doubled family of each of
/// its period doublings, numbered from next_family on.
void append_with_branches(const PeriodicFlow& body, std::vector<FamilyOrbit>& all, const std::vector<FamilyOrbit>& family,
                          int& next_family, const FamilySettings& s) {
  const std::size_t last = all.size() + family.size() - 1;
  all.insert(all.end(), family.begin(), family.end());
  if (!s.switch_branches) return;
  for (const FamilyOrbit& r : family) {
    if (r.event != "period_doubling") continue;
    std::string why_not;
    const std::vector<FamilyOrbit> doubled = doubled_family(body, r, next_family, s, why_not);
    if (doubled.empty()) {  // said on the parent's last row
      all[last].family_end += "; no doubled family at h = " + std::to_string(r.orbit.h) + ": " + why_not;
      continue;
    }
    all.insert(all.end(), doubled.begin(), doubled.end());
    ++next_family;
  }
}

/// The Lyapunov family from its first orbit at an equilibrium (x_e, h_e):
/// continued in h, or (s.shooting.in_l) one natural step in h away from the
/// equilibrium and then in ℓ at that h. Empty rows' family_end says why it ended early.
std::vector<FamilyOrbit> family_from(const PeriodicFlow& body, const FamilyOrbit& first, const Vec6& xe, double h_e,
                                     double direction, const FamilySettings& s) {
  const double away = first.orbit.h >= h_e ? 1.0 : -1.0;
  std::vector<FamilyOrbit> rows{first};
  if (!s.shooting.in_l || s.steps == 0) {
    continue_rows(body, rows, away * s.h_step, &xe, h_e, s);
    return rows;
  }
  FamilySettings in_h = s;
  in_h.shooting.in_l = false, in_h.steps = 1, in_h.locate_events = false;
  in_h.h_min = -INFINITY, in_h.h_max = INFINITY;
  continue_rows(body, rows, away * (s.start_h_step > 0.0 ? s.start_h_step : s.h_step), &xe, h_e, in_h);
  if (rows.size() < 2) return rows;
  // The level of the family: the second orbit, corrected again with ℓ as its parameter.
  const PeriodicOrbit& o = rows[1].orbit;
  FamilyOrbit second = rows[1];
  second.family_end.clear();
  second.orbit = correct_orbit(body, o.x0, o.period, o.h, o.l, s.shooting);
  if (!second.orbit.converged) {
    rows.resize(1);
    rows[0].family_end = "the orbit at h = " + std::to_string(o.h) + " did not converge with l as the parameter";
    return rows;
  }
  std::vector<FamilyOrbit> in_l{second};
  FamilySettings rest = s;
  rest.steps = s.steps - 1;
  continue_rows(body, in_l, direction * s.h_step, nullptr, 0.0, rest);
  rows.resize(1);
  rows[0].family_end.clear();
  for (FamilyOrbit& r : in_l) r.index += 1, rows.push_back(std::move(r));
  return rows;
}

/// A linearly stable equilibrium whose modes start families: its state, energy,
/// row in the equilibria table, the scale of the start amplitude and its frequencies.
struct ModeStart {
  Vec6 xe = Vec6::Zero();
  double h = 0.0, scale = 1.0;
  int row = 0;
  std::vector<double> omegas;
};

/// √(−μ) for the negative roots μ of μ² + g1 μ + g2, ascending.
std::vector<double> frequencies_of(double g1, double g2) {
  const double disc = g1 * g1 - 4.0 * g2;
  if (!(disc >= 0.0)) return {};
  const double s = std::sqrt(disc);
  std::vector<double> w;
  for (const double mu : {0.5 * (-g1 - s), 0.5 * (-g1 + s)})
    if (mu < 0.0) w.push_back(std::sqrt(-mu));
  std::sort(w.begin(), w.end());
  return w;
}

/// The Lyapunov families of every mode of every start (lyapunov_families' comment).
std::vector<FamilyOrbit> families_of_starts(const PeriodicFlow& body, double l, const std::vector<ModeStart>& starts,
                                            const FamilySettings& s, std::vector<std::string>& failures,
                                            double direction,
                                            const std::function<bool(std::size_t, std::size_t)>& mode_done) {
  std::vector<FamilyOrbit> all;
  std::size_t modes = 0, done = 0;
  for (const ModeStart& e : starts) modes += e.omegas.size();
  int family = 0;
  for (const ModeStart& e : starts) {
    for (const double omega : e.omegas) {
      const std::size_t rows_before = all.size(), failures_before = failures.size();
      // After the mode: false drops it (a signal may have cut it short) and stops.
      const auto stop_after_mode = [&] {
        if (!mode_done || mode_done(++done, modes)) return false;
        all.erase(all.begin() + static_cast<std::ptrdiff_t>(rows_before), all.end());
        failures.resize(failures_before);
        return true;
      };
      const Vec6 start = project_to_leaf(body, e.xe + s.amplitude * e.scale * mode_direction(body, e.xe, omega), l);
      const double h0 = flow_invariants(body, start).value(0);
      ShootingSettings at_l = s.shooting;  // the first orbit at ℓ, even for a family continued in ℓ
      at_l.in_l = false;
      const PeriodicOrbit o = correct_orbit(body, start, 2.0 * std::numbers::pi / omega, h0, l, at_l);
      if (!o.converged) {
        failures.push_back("equilibrium " + std::to_string(e.row) + ", omega = " + std::to_string(omega) +
                           ": the first orbit: " + correction_failure(o, at_l));
        if (stop_after_mode()) return all;
        continue;
      }
      FamilyOrbit first;
      first.family = family, first.equilibrium = e.row, first.omega = omega, first.orbit = o;
      const std::vector<FamilyOrbit> rows = family_from(body, first, e.xe, e.h, direction, s);
      int next = family + 1;
      append_with_branches(body, all, rows, next, s);
      family = next;
      if (stop_after_mode()) return all;
    }
  }
  return all;
}

}  // namespace

std::vector<double> equilibrium_frequencies(const RelativeEquilibrium& e) { return frequencies_of(e.g1, e.g2); }

std::vector<FamilyOrbit> continue_family(const PeriodicFlow& body, const Vec6& x0, double T, double h, double l,
                                         double direction, int family, const FamilySettings& s,
                                         std::vector<std::string>& failures) {
  const PeriodicOrbit o = correct_orbit(body, x0, T, h, l, s.shooting);
  if (!o.converged) {
    failures.push_back("seed at h = " + std::to_string(h) + ", T = " + std::to_string(T) +
                       ": " + correction_failure(o, s.shooting));
    return {};
  }
  FamilyOrbit first;
  first.family = family, first.omega = 2.0 * std::numbers::pi / o.period, first.orbit = o;
  std::vector<FamilyOrbit> rows{first};
  continue_rows(body, rows, direction * s.h_step, nullptr, 0.0, s);
  std::vector<FamilyOrbit> all;
  int next = family + 1;
  append_with_branches(body, all, rows, next, s);
  return all;
}

std::vector<FamilyOrbit> lyapunov_families(const HeavyTopBody& body, double l, const FamilySettings& s,
                                           std::vector<std::string>& failures, double direction,
                                           const std::function<bool(std::size_t, std::size_t)>& mode_done) {
  const EquilibriumSet set = equilibria_at(body, l);
  std::vector<ModeStart> starts;
  for (std::size_t i = 0; i < set.rows.size(); ++i) {
    const RelativeEquilibrium& e = set.rows[i];
    if (e.stability != EquilibriumStability::stable) continue;
    const Vec6 xe = state_of(e);
    starts.push_back({xe, e.h, xe.norm(), static_cast<int>(i), equilibrium_frequencies(e)});
  }
  return families_of_starts(body, l, starts, s, failures, direction, mode_done);
}

Vec6 cardan_equilibrium_state(const system::CardanTop& top, const Vec3& q, double omega, double l) {
  Vec6 x;
  x << 0.0, q(1), q(2), top.mass_matrix(q) * Vec3(omega, 0.0, 0.0);
  x(3) = l;  // p1 = M₁₁ ω = ℓ, to the last bit
  return x;
}

std::vector<FamilyOrbit> cardan_lyapunov_families(const system::CardanTop& top, double l, const FamilySettings& s,
                                                  std::vector<std::string>& failures, double direction,
                                                  const std::function<bool(std::size_t, std::size_t)>& mode_done) {
  const std::vector<CardanEquilibrium> rows = cardan_equilibria_at(top, l);
  std::vector<ModeStart> starts;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const CardanEquilibrium& e = rows[i];
    // A circle of equilibria (degenerate) has a zero frequency and no isolated family.
    if (e.stability != EquilibriumStability::stable || e.degenerate) continue;
    const Vec6 xe = cardan_equilibrium_state(top, e.q, e.omega, l);
    starts.push_back({xe, e.h, std::max(1.0, xe.norm()), static_cast<int>(i), frequencies_of(e.g1, e.g2)});
  }
  return families_of_starts(PeriodicFlow(top), l, starts, s, failures, direction, mode_done);
}

}  // namespace lgi::experiments
