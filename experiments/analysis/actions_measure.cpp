// The closed-form actions measured on integrated orbits (docs/actions.md §4):
// periods from located crossings, and loop integrals over exactly one period
// with the periodic trapezoid rule (geometric convergence for the analytic
// periodic integrands of an integrable top).
#include <atomic>
#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "experiments/analysis/actions.hpp"
#include "experiments/analysis/actions_support.hpp"
#include "integrators/registry/registry.hpp"
#include "integrators/system/model.hpp"

namespace lgi::experiments {
namespace {

using std::numbers::pi;

/// Keeps every step's state.
class Samples final : public integrators::Observer {
 public:
  std::vector<system::State> states;
  void observe(std::int64_t, double, const system::State& s) override { states.push_back(s); }
};

std::vector<system::State> one_period(const system::Scene& scene, const system::State& x0, const std::string& scheme,
                                      double period, int steps) {
  const integrators::SchemeInfo* info = integrators::find_scheme(scheme);
  if (info == nullptr) throw std::invalid_argument("unknown scheme " + scheme);
  integrators::RunConfig cfg;
  cfg.t_end = period;
  cfg.dt = period / steps;
  cfg.cpu_clock = false;
  Samples samples;
  system::State x = x0;
  const auto stats = info->run(system::make_model(scene), x, cfg, samples);
  if (!stats.ok || static_cast<int>(samples.states.size()) != steps + 1) samples.states.clear();
  return samples.states;
}

double unwrap(double previous, double angle) {
  return previous + std::remainder(angle - previous, 2.0 * pi);
}

}  // namespace

double crossing_period(const system::Scene& scene, const system::State& x0, const std::string& scheme, double dt,
                       const std::function<double(const system::State&)>& g, int periods, double max_time) {
  const integrators::SchemeInfo* info = integrators::find_scheme(scheme);
  if (info == nullptr) throw std::invalid_argument("unknown scheme " + scheme);
  CrossingRecorder recorder(g, periods + 1);
  integrators::RunConfig cfg;
  cfg.t_end = max_time;
  cfg.dt = dt;
  cfg.save_every = std::numeric_limits<std::int64_t>::max();
  cfg.events = &recorder.events();
  cfg.stop = recorder.stop_flag();
  cfg.cpu_clock = false;
  system::State x = x0;
  info->run(system::make_model(scene), x, cfg, recorder);
  const auto& hits = recorder.hits();
  if (static_cast<int>(hits.size()) < periods + 1) return std::nan("");
  return (hits[static_cast<std::size_t>(periods)].t - hits[0].t) / periods;
}

MeasuredLagrange measure_lagrange(const system::Scene& scene, const system::State& x0, const std::string& scheme,
                                  double dt, int steps, int periods) {
  MeasuredLagrange m;
  const Mat3 J_inv = scene.inertia.inverse();
  // u̇ = Γ̇3 = (Γ × Ω)·e3: its rising zeros are the lowest points u = u1 of the nutation.
  auto u_dot = [J_inv](const system::State& s) {
    const Vec3 gamma = s.R.row(2).transpose();
    return gamma.cross(J_inv * s.Pi).z();
  };
  m.period = crossing_period(scene, x0, scheme, dt, u_dot, periods, 1e6);
  if (!std::isfinite(m.period)) return m;
  const auto states = one_period(scene, x0, scheme, m.period, steps);
  if (states.empty()) return m;
  const double A = scene.inertia(0, 0);
  double sum = 0.0, psi = 0.0, phi = 0.0, psi0 = 0.0, phi0 = 0.0;
  for (std::size_t j = 0; j < states.size(); ++j) {
    const system::State& s = states[j];
    const Vec3 gamma = s.R.row(2).transpose(), Omega = J_inv * s.Pi;
    const double sin_theta = std::hypot(gamma.x(), gamma.y());
    // θ̇ = Ω1 cosφ − Ω2 sinφ with (sinφ, cosφ) = (Γ1, Γ2)/sinθ; p_θ θ̇ = A θ̇².
    const double theta_dot = (Omega.x() * gamma.y() - Omega.y() * gamma.x()) / sin_theta;
    if (j < states.size() - 1) sum += A * theta_dot * theta_dot;
    const double psi_j = std::atan2(s.R(0, 2), -s.R(1, 2)), phi_j = std::atan2(gamma.x(), gamma.y());
    if (j == 0) psi = psi0 = psi_j, phi = phi0 = phi_j;
    else psi = unwrap(psi, psi_j), phi = unwrap(phi, phi_j);
  }
  m.action_theta = sum * (m.period / steps) / (2.0 * pi);
  m.frequencies = {(psi - psi0) / m.period, (phi - phi0) / m.period, 2.0 * pi / m.period};
  m.ok = true;
  return m;
}

MeasuredEuler measure_euler(const system::Scene& scene, const system::State& x0, const std::string& scheme,
                            double period, int steps, int pole) {
  MeasuredEuler m;
  const auto states = one_period(scene, x0, scheme, period, steps);
  if (states.empty()) return m;
  const Mat3 J_inv = scene.inertia.inverse();
  const int a = (pole + 1) % 3, b = (pole + 2) % 3;
  // Space frame (x, y, z) with z = m/|m|: ψ of the pole axis about m.
  const Vec3 mom = x0.R * x0.Pi, z = mom.normalized();
  const Vec3 x = (std::abs(z.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(z).normalized(), y = z.cross(x);
  double loop = 0.0, psi = 0.0, psi0 = 0.0;
  for (std::size_t j = 0; j < states.size(); ++j) {
    const system::State& s = states[j];
    const Vec3 Pi = s.Pi, Pi_dot = Pi.cross(J_inv * Pi);
    // Deprit's l = atan2(Π_a, Π_b): l̇ = (Π̇_a Π_b − Π_a Π̇_b)/(Π_a² + Π_b²); the loop integrand is L l̇.
    const double l_dot = (Pi_dot[a] * Pi[b] - Pi[a] * Pi_dot[b]) / (Pi[a] * Pi[a] + Pi[b] * Pi[b]);
    if (j < states.size() - 1) loop += Pi[pole] * l_dot;
    const Vec3 axis = s.R.col(pole);
    const double psi_j = std::atan2(axis.dot(x), -axis.dot(y));
    if (j == 0) psi = psi0 = psi_j;
    else psi = unwrap(psi, psi_j);
  }
  m.action_l = std::abs(loop * (period / steps)) / (2.0 * pi);
  m.omega_g = (psi - psi0) / period;
  m.ok = true;
  return m;
}

}  // namespace lgi::experiments
