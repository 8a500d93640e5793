// Components of a common level set of a heavy top (level_set_components.hpp).
#include "experiments/analysis/level_set_components.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <functional>

#include "experiments/analysis/accessible_region.hpp"

namespace lgi::experiments {

namespace {

using Mat46 = Eigen::Matrix<double, 4, 6>;

/// The edge lengths of the Euclidean minimum spanning tree of the points (Prim,
/// O(n²)), longest first: cutting the n − 1 longest leaves n single-linkage clusters.
std::vector<double> spanning_tree_edges(const std::vector<StateVec6>& p) {
  const std::size_t n = p.size();
  std::vector<double> best(n, INFINITY), edges;
  std::vector<char> in(n, 0);
  std::size_t next = 0;
  for (std::size_t step = 0; step < n; ++step) {
    const std::size_t i = next;
    in[i] = 1;
    if (step > 0) edges.push_back(best[i]);
    double least = INFINITY;
    for (std::size_t j = 0; j < n; ++j) {
      if (in[j]) continue;
      best[j] = std::min(best[j], (p[i] - p[j]).norm());
      if (best[j] < least) least = best[j], next = j;
    }
  }
  std::sort(edges.begin(), edges.end(), std::greater<>());
  return edges;
}

}  // namespace

/// Moves x onto {H = h, C = ℓ, |Γ|² = 1, K = k} by minimum-norm Gauss–Newton steps
/// (the level set is a surface, so the step J⁺F is the least move); false when the
/// residual does not fall below 1e-11 in 30 steps.
bool project_to_level_set(const HeavyTopBody& b, double l, double h, double k, const SecondIntegral& K, StateVec6& x) {
  const Mat3 Jinv = b.J.inverse();
  for (int it = 0; it < 30; ++it) {
    const IntegralValue q = K(x);
    Eigen::Vector4d F(heavy_top_energy(b, x) - h, x.tail<3>().dot(x.head<3>()) - l, x.head<3>().squaredNorm() - 1.0,
                      q.value - k);
    if (F.lpNorm<Eigen::Infinity>() < 1e-11 * (1.0 + std::abs(k))) return true;
    Mat46 D;
    D.row(0) << b.weight.transpose(), (Jinv * x.tail<3>()).transpose();
    D.row(1) << x.tail<3>().transpose(), x.head<3>().transpose();
    D.row(2) << 2.0 * x.head<3>().transpose(), 0.0, 0.0, 0.0;
    D.row(3) = q.gradient.transpose();
    const Eigen::Matrix4d normal = D * D.transpose();
    Eigen::LDLT<Eigen::Matrix4d> ldlt(normal);
    if (ldlt.info() != Eigen::Success || !(std::abs(ldlt.vectorD().minCoeff()) > 1e-14 * normal.trace())) return false;
    StateVec6 dx = -D.transpose() * ldlt.solve(F);
    const double n = dx.norm();
    if (!std::isfinite(n)) return false;
    if (n > 0.25) dx *= 0.25 / n;  // damped far from the level set
    x += dx;
  }
  return false;
}

double heavy_top_energy(const HeavyTopBody& b, const StateVec6& x) {
  const Vec3 Pi = x.tail<3>();
  return 0.5 * Pi.dot(b.J.inverse() * Pi) + b.weight.dot(x.head<3>());
}

std::vector<StateVec6> energy_surface_lattice(const HeavyTopBody& b, double l, double h, int seeds) {
  std::vector<StateVec6> out;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < seeds; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / seeds, r = std::sqrt(1.0 - z * z);
    const Vec3 g(r * std::cos(golden * i), r * std::sin(golden * i), z);
    const double excess = h - amended_potential(b, l, g);
    if (!(excess >= 0.0)) continue;
    const Vec3 ea = g.unitOrthogonal(), eb = g.cross(ea);
    for (const double a : {0.37 * i, 0.37 * i + 0.5 * std::numbers::pi}) {
      Vec3 d = std::cos(a) * ea + std::sin(a) * eb;
      d *= std::sqrt(2.0 * excess / d.dot(b.J.inverse() * d));
      StateVec6 x;
      x << g, (l / g.dot(b.J * g)) * (b.J * g) + d;
      out.push_back(x);
    }
  }
  return out;
}

LevelSetComponents level_set_components(const HeavyTopBody& body, double l, double h, double k,
                                        const SecondIntegral& K, int seeds) {
  std::vector<StateVec6> points;
  for (StateVec6 x : energy_surface_lattice(body, l, h, seeds))
    if (project_to_level_set(body, l, h, k, K, x)) points.push_back(x);
  LevelSetComponents out;
  out.points = static_cast<int>(points.size());
  if (points.size() < 2) return out;
  // The count n is where the spanning tree's edges split into n − 1 long ones (between
  // components) and the short rest (within): the largest ratio e(n−1)/e(n) of consecutive
  // edges, n ≤ 16. Calibrated on the Euler and Lagrange tops (tests/test_level_set_components.cpp):
  // there the edges within a torus stay below 7 × the median edge and the ratio below 1.2,
  // and the edges between tori are above 10 × the median with a ratio above 2.5.
  constexpr int max_components = 16;
  constexpr double split = 2.5, single = 1.8, within = 8.0, between = 6.0, lone = 5.0;
  const std::vector<double> e = spanning_tree_edges(points);
  const double median = e[e.size() / 2];
  out.spacing = median;
  for (std::size_t i = 0; i < std::min<std::size_t>(8, e.size()); ++i) out.longest.push_back(e[i] / median);
  int n = 1;
  double ratio = 0.0;
  for (int m = 2; m <= max_components && static_cast<std::size_t>(m) <= e.size(); ++m) {
    const double r = e[static_cast<std::size_t>(m - 2)] / e[static_cast<std::size_t>(m - 1)];
    if (r > ratio) ratio = r, n = m;
  }
  out.gap = ratio;
  if (ratio >= split) {
    const double least_between = e[static_cast<std::size_t>(n - 2)], most_within = e[static_cast<std::size_t>(n - 1)];
    out.components = (least_between >= between * median && most_within <= within * median) ? n : -1;
  } else {
    out.components = (ratio < single && e.front() <= lone * median) ? 1 : -1;
  }
  return out;
}

}  // namespace lgi::experiments
