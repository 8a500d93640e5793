#include "experiments/analysis/level_set_draw.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace lgi::experiments {

using lie::Mat3;
using lie::Vec3;

LevelSetBody level_set_body(const system::Scene& scene) {
  LevelSetBody b{scene.inertia, scene.inertia.inverse()};
  if (const auto& g = scene.declared<system::GravityTerm>())
    b.weight = scene.mass.value_or(0.0) * g->g * scene.center_of_mass.value_or(Vec3::Zero());
  b.j_min = Eigen::SelfAdjointEigenSolver<Mat3>(scene.inertia, Eigen::EigenvaluesOnly).eigenvalues().minCoeff();
  return b;
}

double sampled_minimum(const LevelSetBody& b, double l) {
  constexpr int n = 20000;
  double lowest = INFINITY;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int k = 0; k < n; ++k) {
    const double z = 1.0 - (2.0 * k + 1.0) / n, r = std::sqrt(1.0 - z * z);
    const Vec3 gamma(r * std::cos(golden * k), r * std::sin(golden * k), z);
    lowest = std::min(lowest, b.lowest_energy(gamma, l));
  }
  return lowest;
}

double liouville_gamma_density(const LevelSetBody& b, double h, double l, const Vec3& gamma) {
  return b.lowest_energy(gamma, l) < h ? 1.0 / std::sqrt(gamma.dot(b.J * gamma)) : 0.0;
}

/// γ uniform on the sphere among the directions where the level is reached
/// (rejection); with the Liouville measure each is kept with probability
/// √(J_min/γᵀJγ) ≤ 1, the density (γᵀJγ)^(−1/2) over its largest value.
/// Then Π = l Jγ/(γᵀJγ) + u with u ⊥ γ on the ellipse
/// ½uᵀJ⁻¹u = h − V(γ) − l²/(2γᵀJγ), at a uniform angle α of the
/// parametrisation u = √(2r) [e_a e_b] L⁻ᵀ(cos α, sin α), A = LLᵀ: the
/// Liouville measure's conditional law on the ellipse (docs/atlas.md §6).
bool draw_level_point(const LevelSetBody& b, double h, double l, LevelMeasure measure, CounterRng& rng, Vec3& gamma,
                      Vec3& Pi) {
  for (int attempt = 0; attempt < 1000000; ++attempt) {
    const double z = 2.0 * rng.uniform() - 1.0, angle = 2.0 * std::numbers::pi * rng.uniform();
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const Vec3 g(r * std::cos(angle), r * std::sin(angle), z);
    const double gJg = g.dot(b.J * g);
    const double excess = h - b.weight.dot(g) - l * l / (2.0 * gJg);
    if (!(excess >= 0.0)) continue;
    if (measure == LevelMeasure::liouville && !(rng.uniform() * std::sqrt(gJg) < std::sqrt(b.j_min))) continue;
    const Vec3 ea = g.unitOrthogonal(), eb = g.cross(ea);
    Eigen::Matrix2d A;
    A << ea.dot(b.J_inv * ea), ea.dot(b.J_inv * eb), eb.dot(b.J_inv * ea), eb.dot(b.J_inv * eb);
    const Eigen::Matrix2d L = A.llt().matrixL();
    const double alpha = 2.0 * std::numbers::pi * rng.uniform();
    const Eigen::Vector2d y =
        std::sqrt(2.0 * excess) * L.transpose().triangularView<Eigen::Upper>().solve(
                                      Eigen::Vector2d(std::cos(alpha), std::sin(alpha)));
    gamma = g;
    Pi = (l / gJg) * (b.J * g) + y.x() * ea + y.y() * eb;
    return true;
  }
  return false;
}

}  // namespace lgi::experiments
