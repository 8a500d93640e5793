// The critical periodic orbits of the Kovalevskaya top (kovalevskaya_orbits.hpp).
#include "experiments/analysis/periodic/kovalevskaya_orbits.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "experiments/analysis/kovalevskaya_critical.hpp"
#include "experiments/analysis/kovalevskaya_diagram.hpp"
#include "experiments/io/trajectory_observer.hpp"  // interrupt_requested

namespace lgi::experiments {

AppelrotCheck appelrot_check(const HeavyTopBody& body, const Vec6& x) {
  const Invariants inv = euler_poisson_invariants(body, x);
  return appelrot_check(body, x, inv.value(1), inv.value(0));
}

AppelrotCheck appelrot_check(const HeavyTopBody& body, const Vec6& x, double l, double h) {
  AppelrotCheck a;
  const auto scale = kovalevskaya_scale(body);
  if (!scale) return a;
  const Vec3 Pi = x.head<3>(), gamma = x.tail<3>();
  a.k = kovalevskaya_k(body, *scale, gamma, Pi);
  const AppelrotDistance d = appelrot_distance(scale->l(l), scale->h(h), a.k);
  a.distance = d.distance / (1.0 + a.k);
  if (a.distance <= 1e-6) a.family = d.family;
  // The scaled state: Γ̃ = Γ, Π̃ = Π/(J3 √c) (docs/atlas.md §9).
  a.rank_gap = critical_rank_gap(scaled_kovalevskaya(body), gamma, Pi / (scale->J3 * std::sqrt(scale->c)));
  return a;
}

double hyperplane_return_time(const HeavyTopBody& body, const Vec6& x0, double dt, double t_max) {
  const Vec6 n = euler_poisson_field(body, x0).normalized();
  Vec6 x = x0;
  double g_prev = 0.0, reach = 0.0;
  const auto steps = static_cast<long>(std::ceil(t_max / dt));
  for (long i = 0; i < steps; ++i) {
    Vec6 y = x;
    if (interrupt_requested.load(std::memory_order_relaxed) || !flow_step(body, y, dt)) return 0.0;  // Ctrl-C: no return
    const double g = n.dot(y - x0);
    reach = std::max(reach, (y - x0).norm());
    if (g_prev < 0.0 && g >= 0.0) {  // a crossing in the flow's direction: accept it near x0
      const double tau = g_prev / (g_prev - g);
      if ((x + tau * (y - x) - x0).norm() <= 1e-2 * reach) return (static_cast<double>(i) + tau) * dt;
    }
    x = y, g_prev = g;
  }
  return 0.0;
}

std::vector<CriticalSeed> kovalevskaya_critical_seeds(const HeavyTopBody& body, double l, double h, double dt,
                                                      int lattice) {
  const auto scale = kovalevskaya_scale(body);
  if (!scale) return {};
  const double root_c = std::sqrt(scale->c);
  const auto found =
      kovalevskaya_critical_values(scaled_kovalevskaya(body), scale->l(l), {scale->h(h)}, lattice).front();
  std::vector<CriticalSeed> out;
  for (const CriticalValue& v : found) {
    CriticalSeed s;
    s.x << scale->J3 * root_c * v.Pi, v.gamma;  // back from the scaled top
    s.h = h, s.k = v.k, s.family = v.family;
    char label[96];
    std::snprintf(label, sizeof label, "critical value (h, k) = (%.9g, %.9g)", h, v.k);
    if (euler_poisson_field(body, s.x).norm() <= 1e-9 * (1.0 + s.x.norm())) {
      s.failure = std::string(label) + ": a relative equilibrium, not a circle";
    } else {
      s.period = hyperplane_return_time(body, s.x, dt, 500.0 / root_c);
      if (!(s.period > 0.0)) s.failure = std::string(label) + ": no return within t = " + std::to_string(500.0 / root_c);
    }
    out.push_back(s);
  }
  return out;
}

}  // namespace lgi::experiments
