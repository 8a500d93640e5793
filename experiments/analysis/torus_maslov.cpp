// The Maslov indices of a numerical torus's cycles (torus_maslov.hpp; docs/actions.md §5).
#include "experiments/analysis/torus_maslov.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <numeric>
#include <vector>

#include "experiments/analysis/actions_support.hpp"
#include "integrators/registry/registry.hpp"
#include "integrators/system/model.hpp"

namespace lgi::experiments {
namespace {

using std::numbers::pi;

/// A Hamiltonian field of the Lie–Poisson brackets at (Γ, Π): (Γ × ∇_Π F, Π × ∇_Π F + Γ × ∇_Γ F).
/// Both fields of the plane use the same formula, so the bracket's overall sign does not matter.
void hamiltonian_field(const Vec3& g, const Vec3& Pi, const Vec3& grad_g, const Vec3& grad_Pi, Vec3& dg, Vec3& dPi) {
  dg = g.cross(grad_Pi);
  dPi = Pi.cross(grad_Pi) + g.cross(grad_g);
}

/// The tangent vector (dΓ, dΠ) in the reduced chart (θ, φ, p_θ, p_φ) of docs/actions.md:
/// Γ = (sinθ sinφ, sinθ cosφ, cosθ), p_θ = Π1 cosφ − Π2 sinφ, p_φ = Π3.
std::complex<double> chart_column(const Vec3& g, const Vec3& Pi, const Vec3& dg, const Vec3& dPi, int row) {
  const double s2 = g.x() * g.x() + g.y() * g.y(), phi = std::atan2(g.x(), g.y());
  const double dtheta = -dg.z() / std::sqrt(s2), dphi = (g.y() * dg.x() - g.x() * dg.y()) / s2;
  const double dp_theta =
      dPi.x() * std::cos(phi) - dPi.y() * std::sin(phi) - (Pi.x() * std::sin(phi) + Pi.y() * std::cos(phi)) * dphi;
  return row == 0 ? std::complex<double>(dtheta, dp_theta) : std::complex<double>(dphi, dPi.z());
}

/// arg det(Q + iP) along a sequence, unwrapped: the sum of the steps, each taken in (−π, π].
struct Unwrapped {
  double total = 0.0, largest = 0.0, last = 0.0;
  bool started = false;
  void add(double phase) {
    if (started) {
      const double step = std::remainder(phase - last, 2.0 * pi);
      total += step, largest = std::max(largest, std::abs(step));
    }
    last = phase, started = true;
  }
};

/// Every step's unwrapped phase along the flow, until `wanted` crossings of the torus's section.
class PhaseRecorder final : public CrossingRecorder {
 public:
  PhaseRecorder(const HeavyTopBody& body, const SecondIntegralFunction& K, const SectionChoice& section, int wanted)
      : CrossingRecorder(
            [section](const system::State& s) {
              const Point6 p = (Point6() << s.Pi, s.R.row(2).transpose()).finished();
              return p[section.coordinate] - section.level;
            },
            wanted),
        body_(body), K_(K) {}
  void observe(std::int64_t, double t, const system::State& s) override {
    poll_interrupt();
    if (!t_.empty() && !(t > t_.back())) return;
    phase_.add(lagrangian_phase(body_, K_, s.R.row(2).transpose(), s.Pi));
    t_.push_back(t), f_.push_back(phase_.total);
  }
  /// The weighted Birkhoff mean of ḟ, by parts (docs/actions.md §3).
  double mean_rate() const {
    const double t0 = t_.front(), tau = t_.back() - t0;
    double w_sum = 0.0, fw = 0.0;
    for (std::size_t j = 0; j < t_.size(); ++j) {
      w_sum += birkhoff_weight((t_[j] - t0) / tau);
      fw += birkhoff_weight_derivative((t_[j] - t0) / tau) * f_[j];
    }
    return -fw / (tau * w_sum);
  }
  std::size_t samples() const { return t_.size(); }

 private:
  HeavyTopBody body_;
  SecondIntegralFunction K_;
  Unwrapped phase_;
  std::vector<double> t_, f_;
};

}  // namespace

double lagrangian_phase(const HeavyTopBody& body, const SecondIntegralFunction& K, const Vec3& g, const Vec3& Pi) {
  // ∇K by central differences (K is a polynomial; the step leaves ~1e-10 relative, far below
  // what a phase needs).
  Vec3 Kg, KPi;
  for (int i = 0; i < 3; ++i) {
    const double hg = 1e-6 * (1.0 + std::abs(g[i])), hp = 1e-6 * (1.0 + std::abs(Pi[i]));
    Vec3 gp = g, gm = g, pp = Pi, pm = Pi;
    gp[i] += hg, gm[i] -= hg, pp[i] += hp, pm[i] -= hp;
    Kg[i] = (K(gp, Pi) - K(gm, Pi)) / (2.0 * hg);
    KPi[i] = (K(g, pp) - K(g, pm)) / (2.0 * hp);
  }
  Vec3 dg1, dPi1, dg2, dPi2;
  hamiltonian_field(g, Pi, body.weight, body.J.inverse() * Pi, dg1, dPi1);
  hamiltonian_field(g, Pi, Kg, KPi, dg2, dPi2);
  const std::complex<double> z00 = chart_column(g, Pi, dg1, dPi1, 0), z10 = chart_column(g, Pi, dg1, dPi1, 1);
  const std::complex<double> z01 = chart_column(g, Pi, dg2, dPi2, 0), z11 = chart_column(g, Pi, dg2, dPi2, 1);
  return std::arg(z00 * z11 - z01 * z10);
}

TorusMaslov torus_maslov(const system::Scene& scene, const HeavyTopBody& body, const system::State& x0,
                         const NumericalTorus& torus, const SecondIntegralFunction& K,
                         const NumericalTorusOptions& options, int returns) {
  TorusMaslov m;
  if (!torus.ok || torus.circle.size() < 16) {
    m.status = "no torus";
    return m;
  }
  // Cycle a: the section points in the order of α = jρ (ρ as reported: cycle a oriented so that I_a ≥ 0).
  std::vector<std::size_t> order(torus.circle.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  const auto alpha = [&](std::size_t j) {
    const double a = static_cast<double>(j) * torus.rotation_number;
    return a - std::floor(a);
  };
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return alpha(i) < alpha(j); });
  Unwrapped loop;
  double action = 0.0;  // ∮λ along the points, a check of the orientation
  for (std::size_t i = 0; i <= order.size(); ++i) {
    const Point6& p = torus.circle[order[i % order.size()]];
    loop.add(lagrangian_phase(body, K, p.tail<3>(), p.head<3>()));
    if (i > 0) {
      const Point6& q = torus.circle[order[i - 1]];
      const Vec3 gp = p.tail<3>(), gq = q.tail<3>(), Pm = 0.5 * (p.head<3>() + q.head<3>()), gm = 0.5 * (gp + gq);
      const double phi_p = std::atan2(gp.x(), gp.y()), phi_q = std::atan2(gq.x(), gq.y());
      const double dphi = std::remainder(phi_p - phi_q, 2.0 * pi), phim = std::atan2(gm.x(), gm.y());
      const double dtheta = std::acos(std::clamp(gp.z(), -1.0, 1.0)) - std::acos(std::clamp(gq.z(), -1.0, 1.0));
      action += (Pm.x() * std::cos(phim) - Pm.y() * std::sin(phim)) * dtheta + Pm.z() * dphi;
    }
  }
  m.largest_step = loop.largest;
  m.mu_a_measured = -loop.total / pi;  // a libration, run with the flow, turns the phase by −2π
  m.mu_a = static_cast<int>(std::lround(m.mu_a_measured));
  // Cycle b from the mean rate of the phase along the flow.
  const integrators::SchemeInfo* info = integrators::find_scheme(options.scheme);
  if (info == nullptr) {
    m.status = "unknown scheme";
    return m;
  }
  const system::AnyModel model = system::make_model(scene);
  PhaseRecorder recorder(body, K, torus.section, returns);
  integrators::RunConfig cfg;
  cfg.t_end = options.max_time, cfg.dt = options.dt, cfg.events = &recorder.events();
  cfg.stop = recorder.stop_flag(), cfg.cpu_clock = false;
  system::State x = x0;
  info->run(model, x, cfg, recorder);
  if (recorder.samples() < 100 || static_cast<int>(recorder.hits().size()) < returns) {
    m.status = "the flow run ended early";
    return m;
  }
  m.mu_b_measured = (-2.0 * recorder.mean_rate() - m.mu_a * torus.omega_a) / torus.omega_b;
  m.mu_b = static_cast<int>(std::lround(m.mu_b_measured));
  // A step above π/2 between section points could hide a turn; a non-integer winding or
  // rate, or an orientation against I_a ≥ 0, means the indices are not trustworthy.
  if (!(action > 0.0)) m.status = "the section points run against cycle a's orientation";
  else if (m.largest_step > 0.5 * pi) m.status = "the section points are too sparse for the phase";
  else if (std::abs(m.mu_a_measured - m.mu_a) > 1e-6) m.status = "the winding along cycle a is not an integer";
  else if (std::abs(m.mu_b_measured - m.mu_b) > 0.05) m.status = "the rate along the flow is not (mu_a w_a + mu_b w_b)/2";
  else m.ok = true, m.status = "ok";
  return m;
}

}  // namespace lgi::experiments
