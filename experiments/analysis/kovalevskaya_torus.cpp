// The Kovalevskaya torus through a chosen level (kovalevskaya_torus.hpp).
#include "experiments/analysis/kovalevskaya_torus.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "experiments/analysis/kovalevskaya_diagram.hpp"

namespace lgi::experiments {

SecondIntegralFunction kovalevskaya_k_function(const HeavyTopBody& body) {
  const std::optional<KovalevskayaScale> scale = kovalevskaya_scale(body);
  if (!scale) throw std::invalid_argument("not a Kovalevskaya top (J = J3 diag(2, 2, 1), centre of mass on e1)");
  return [body, s = *scale](const Vec3& g, const Vec3& Pi) { return kovalevskaya_k(body, s, g, Pi); };
}

SecondIntegral kovalevskaya_k_integral(const HeavyTopBody& body) {
  const SecondIntegralFunction K = kovalevskaya_k_function(body);
  return [K](const StateVec6& x) {
    IntegralValue v;
    v.value = K(x.head<3>(), x.tail<3>());
    for (int i = 0; i < 6; ++i) {
      const double step = 1e-6 * (1.0 + std::abs(x(i)));
      StateVec6 p = x, m = x;
      p(i) += step, m(i) -= step;
      v.gradient(i) = (K(p.head<3>(), p.tail<3>()) - K(m.head<3>(), m.tail<3>())) / (2.0 * step);
    }
    return v;
  };
}

std::optional<StateVec6> kovalevskaya_level_point(const HeavyTopBody& body, double l, double h, double k,
                                                  const std::optional<StateVec6>& start, int seeds) {
  const SecondIntegral K = kovalevskaya_k_integral(body);
  if (start) {
    StateVec6 x = *start;
    if (project_to_level_set(body, l, h, k, K, x)) return x;
    return std::nullopt;
  }
  for (StateVec6 x : energy_surface_lattice(body, l, h, seeds))
    if (project_to_level_set(body, l, h, k, K, x)) return x;
  return std::nullopt;
}

system::State state_at(const StateVec6& x) {
  const Vec3 g = x.head<3>().normalized();
  const Vec3 f1 = (std::abs(g.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(g).normalized();
  system::State s;
  s.Pi = x.tail<3>();
  s.R.row(0) = f1.transpose();
  s.R.row(1) = g.cross(f1).transpose();
  s.R.row(2) = g.transpose();
  return s;
}

LibrationBasis libration_basis(const NumericalTorus& t, const TorusMaslov& mu) {
  LibrationBasis out;
  if (!t.ok || !mu.ok) return out;
  const Eigen::Vector2d I(t.action_a, t.action_b), w(t.omega_a, t.omega_b);
  int found = 0;
  // Unimodular changes with small entries: cycles a' = p a + q b, b' = r a + s b carry the
  // actions M I and the frequencies M^{-T} ω (ω·I is kept).
  for (int p = -3; p <= 3; ++p)
    for (int q = -3; q <= 3; ++q)
      for (int r = -3; r <= 3; ++r)
        for (int s = -3; s <= 3; ++s) {
          if (std::abs(p * s - q * r) != 1) continue;
          if (p * mu.mu_a + q * mu.mu_b != 2 || r * mu.mu_a + s * mu.mu_b != 2) continue;
          Eigen::Matrix2d M;
          M << p, q, r, s;
          const Eigen::Vector2d Ip = M * I, wp = M.inverse().transpose() * w;
          if (!(wp(0) > 0.0 && wp(1) > 0.0) || !(wp(0) < wp(1))) continue;  // slow first
          ++found;
          out.action_slow = Ip(0), out.action_fast = Ip(1), out.omega_slow = wp(0), out.omega_fast = wp(1);
          out.change << p, q, r, s;
        }
  out.ok = found == 1;
  return out;
}

KovalevskayaTorus kovalevskaya_torus(const system::Scene& scene, const HeavyTopBody& body, const system::State& x0,
                                     const NumericalTorusOptions& options, int maslov_returns) {
  KovalevskayaTorus r;
  const SecondIntegralFunction K = kovalevskaya_k_function(body);
  r.k = K(x0.R.row(2).transpose(), x0.Pi);
  r.torus = numerical_torus(scene, x0, options);
  if (r.torus.ok) r.maslov = torus_maslov(scene, body, x0, r.torus, K, options, maslov_returns);
  r.basis = libration_basis(r.torus, r.maslov);
  return r;
}

}  // namespace lgi::experiments
