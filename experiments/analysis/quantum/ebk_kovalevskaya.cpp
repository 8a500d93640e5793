// EBK levels of the Kovalevskaya top from numerical tori (ebk_kovalevskaya.hpp; docs/quantum.md §10).
#include "experiments/analysis/quantum/ebk_kovalevskaya.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>

#include "experiments/analysis/kovalevskaya_diagram.hpp"
#include "experiments/analysis/kovalevskaya_torus.hpp"
#include "experiments/analysis/quantum/lowest_levels.hpp"  // SolveInterrupted
#include "integrators/system/terms/gravity.hpp"

namespace lgi::experiments::quantum {
namespace {

HeavyTopBody body_of(const system::Scene& scene) {
  HeavyTopBody body;
  body.J = scene.inertia;
  if (const auto gravity = scene.declared<system::GravityTerm>())
    body.weight = scene.mass.value_or(0.0) * gravity->g * scene.center_of_mass.value_or(Vec3::Zero());
  if (!kovalevskaya_scale(body) || !scene.declares_only<system::GravityTerm>())
    throw std::invalid_argument(scene.file + ": not a Kovalevskaya top (gravity only, J = J3 diag(2, 2, 1), centre "
                                             "of mass on e1)");
  return body;
}

/// The small oscillations about the hanging position Γ = −sign(c) e1 at ℓ = 0: the swing about
/// body axis 2 (moment J2 = 2J3, Γ moves along e3) is the slow one, ω² = |c|/J2, the swing about
/// axis 3 (Γ along e2) the fast one, ω² = |c|/J3.
struct Harmonic {
  double c = 1.0, sign = 1.0, omega_slow = 1.0, omega_fast = 1.0;
  explicit Harmonic(const HeavyTopBody& b)
      : c(std::abs(b.weight.x())), sign(b.weight.x() > 0.0 ? 1.0 : -1.0), omega_slow(std::sqrt(c / b.J(1, 1))),
        omega_fast(std::sqrt(c / b.J(2, 2))) {}
  double energy(double hbar, int n_slow, int n_fast) const {
    return -c + hbar * (omega_slow * (n_slow + 0.5) + omega_fast * (n_fast + 0.5));
  }
};

/// A state of the harmonic torus (I_slow, I_fast): the slow swing at its turning point, the fast
/// one at its centre, then Π moved along Γ to Π·Γ = ℓ.
StateVec6 harmonic_state(const HeavyTopBody& b, const Harmonic& o, double l, double I_slow, double I_fast) {
  const double a = std::sqrt(2.0 * o.omega_slow * I_slow / o.c);
  const Vec3 g(-o.sign * std::cos(a), 0.0, std::sin(a));
  Vec3 Pi(0.0, 0.0, std::sqrt(2.0 * b.J(2, 2) * o.omega_fast * I_fast));
  Pi += (l - Pi.dot(g)) * g;
  StateVec6 x;
  x << g, Pi;
  return x;
}

struct Evaluation {
  bool ok = false;
  StateVec6 x;
  Eigen::Vector2d F = Eigen::Vector2d::Zero();  // (I_slow, I_fast)/ħ − (n + ½)
  int mu_a = 0, mu_b = 0;
  std::string status;
};

}  // namespace

bool is_kovalevskaya_scene(const system::Scene& scene) {
  try {
    body_of(scene);
    return true;
  } catch (const std::invalid_argument&) {
    return false;
  }
}

KovalevskayaEbkLevel kovalevskaya_ebk_level(const system::Scene& scene, double hbar, double l, int n_slow,
                                            int n_fast, const KovalevskayaEbkOptions& options) {
  const HeavyTopBody body = body_of(scene);
  const SecondIntegralFunction K = kovalevskaya_k_function(body);
  const Harmonic osc(body);
  KovalevskayaEbkLevel r;
  r.n_slow = n_slow, r.n_fast = n_fast;
  const Eigen::Vector2d target(n_slow + 0.5, n_fast + 0.5);
  const auto evaluate = [&](double h, double k, const StateVec6& start) {
    if (options.stop && options.stop->load(std::memory_order_relaxed)) throw SolveInterrupted();
    Evaluation e;
    const std::optional<StateVec6> x = kovalevskaya_level_point(body, l, h, k, start);
    if (!x) {
      e.status = "no point of the level (h, k) near the previous torus";
      return e;
    }
    ++r.tori;
    const KovalevskayaTorus t = kovalevskaya_torus(scene, body, state_at(*x), options.torus, options.maslov_returns);
    e.x = *x, e.mu_a = t.maslov.mu_a, e.mu_b = t.maslov.mu_b;
    if (!t.torus.ok) e.status = "torus failed: " + t.torus.status;
    else if (!t.maslov.ok) e.status = "Maslov indices not found: " + t.maslov.status;
    else if (!t.basis.ok) e.status = "no libration basis (Maslov indices " + std::to_string(t.maslov.mu_a) + ", " +
                                     std::to_string(t.maslov.mu_b) + "): outside the region of the hanging position";
    else e.ok = true, e.F = Eigen::Vector2d(t.basis.action_slow, t.basis.action_fast) / hbar - target;
    return e;
  };
  StateVec6 x = harmonic_state(body, osc, l, hbar * target(0), hbar * target(1));
  double h = 0.5 * x.tail<3>().dot(body.J.inverse() * x.tail<3>()) + body.weight.dot(x.head<3>());
  double k = K(x.head<3>(), x.tail<3>());
  Evaluation e = evaluate(h, k, x);
  Eigen::Matrix2d D = Eigen::Matrix2d::Zero();  // ∂F/∂(h, k), by finite differences
  bool have_jacobian = false;
  for (int it = 0; e.ok && it < options.max_iterations; ++it) {
    r.residual = e.F.lpNorm<Eigen::Infinity>(), r.mu_a = e.mu_a, r.mu_b = e.mu_b;
    if (r.residual < options.tolerance) break;
    if (!have_jacobian) {
      const double dh = 0.02 * hbar, dk = 0.02 * hbar;
      const Evaluation eh = evaluate(h + dh, k, e.x), ek = evaluate(h, k + dk, e.x);
      if (!eh.ok || !ek.ok) {
        e = eh.ok ? ek : eh;
        break;
      }
      D.col(0) = (eh.F - e.F) / dh, D.col(1) = (ek.F - e.F) / dk;
      have_jacobian = true;
    }
    const Eigen::Vector2d step = -D.partialPivLu().solve(e.F);
    const Evaluation next = evaluate(h + step(0), k + step(1), e.x);
    if (!next.ok) {
      e = next;
      break;
    }
    // A chord step that does not halve the residual gets a new Jacobian.
    if (!(next.F.lpNorm<Eigen::Infinity>() < 0.5 * r.residual)) have_jacobian = false;
    h += step(0), k += step(1), e = next;
  }
  if (!e.ok) {
    r.status = e.status;
    return r;
  }
  r.residual = e.F.lpNorm<Eigen::Infinity>(), r.mu_a = e.mu_a, r.mu_b = e.mu_b;
  r.energy = h, r.k = k;
  r.ok = r.residual < options.tolerance;
  r.status = r.ok ? "ok" : "no convergence in " + std::to_string(options.max_iterations) + " steps";
  return r;
}

int kovalevskaya_ebk_class(const QuantumSpectrum& q, int m, int n_slow, int n_fast) {
  // Near the hanging position the body's c axis is the space vertical (reversed), so C₂ about it is
  // the rotation by π about the vertical, e^{−iπm}, times the oscillators' parity.
  const int c2_odd = (n_slow + n_fast + std::abs(m)) % 2;
  if (m != 0) return c2_odd;
  // The frame's axis 2 in scene body coordinates: along e3 the slow mode moves Γ, along e2 the fast one.
  const bool slow_flips = std::abs(q.top.frame(2, 1)) > std::abs(q.top.frame(1, 1));
  return 2 * c2_odd + (slow_flips ? n_slow : n_fast) % 2;
}

std::vector<EbkRow> ebk_kovalevskaya_table(const system::Scene& scene, const QuantumSpectrum& q, double hbar, int m,
                                           const KovalevskayaEbkOptions& options,
                                           std::vector<KovalevskayaEbkLevel>* solved) {
  const Harmonic osc(body_of(scene));
  std::vector<EbkRow> rows;
  if (q.levels.empty()) return rows;
  const double top = q.levels.back().energy + hbar * osc.omega_slow;
  std::map<int, std::vector<KovalevskayaEbkLevel>> by_class;
  for (int ns = 0; osc.energy(hbar, ns, 0) <= top; ++ns)
    for (int nf = 0; osc.energy(hbar, ns, nf) <= top; ++nf) {
      KovalevskayaEbkLevel level = kovalevskaya_ebk_level(scene, hbar, hbar * m, ns, nf, options);
      if (solved) solved->push_back(level);
      by_class[kovalevskaya_ebk_class(q, m, ns, nf)].push_back(level);
    }
  // Within a class by the EBK energy (the harmonic estimate where the solve failed).
  const auto key = [&](const KovalevskayaEbkLevel& a) { return a.ok ? a.energy : osc.energy(hbar, a.n_slow, a.n_fast); };
  for (auto& [c, levels] : by_class)
    std::stable_sort(levels.begin(), levels.end(), [&](const auto& a, const auto& b) { return key(a) < key(b); });
  std::map<int, std::size_t> rank;
  for (const QuantumLevel& level : q.levels) {
    EbkRow row;
    row.m = m, row.k = -1, row.n = -1;
    row.energy_exact = level.energy, row.converged = level.converged;
    row.energy_ebk = KovalevskayaEbkLevel::nan;
    const auto& levels = by_class[level.parity];
    const std::size_t i = rank[level.parity]++;
    if (i < levels.size()) {
      row.n = levels[i].n_slow, row.n_fast = levels[i].n_fast;
      row.energy_ebk = levels[i].energy;
    }
    rows.push_back(row);
  }
  return rows;
}

}  // namespace lgi::experiments::quantum
