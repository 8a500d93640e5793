#include "experiments/analysis/cardan_energy_draw.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "experiments/analysis/seeded_random.hpp"

namespace lgi::experiments {
namespace {

using system::Mat3;
using system::Vec3;
using std::numbers::pi;
constexpr std::uint64_t energy_draw_stream = 0xe4e5afULL;  // apart from cardan_section's streams

}  // namespace

double cardan_sampled_minimum_potential(const system::CardanTop& top, int n) {
  double lowest = std::numeric_limits<double>::infinity();
  const double step = 2.0 * pi / n;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) lowest = std::min(lowest, top.potential(Vec3(i * step, j * step, k * step)));
  return lowest;
}

double cardan_energy_density_bound(const system::CardanTop& top, double h) {
  // M = EᵀJE + FᵀKF + C_o e1e1ᵀ with unit columns E e_k and F e1 (docs/cardan.md §2), so
  // M₁₁ ≤ λ(J) + max(B_i, C_i) + C_o, M₂₂ ≤ λ(J) + A_i, M₃₃ = J₃₃; det M ≤ M₁₁M₂₂M₃₃ (Hadamard).
  const double j_max = Eigen::SelfAdjointEigenSolver<Mat3>(top.J, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff();
  const system::SuspensionParameters& s = top.suspension;
  const double m11 = j_max + std::max(s.inner_inertia(1), s.inner_inertia(2)) + s.outer_inertia;
  const double m22 = j_max + s.inner_inertia(0), m33 = top.J(2, 2);
  // |U| ≤ |g| (m|χ| + m_i|c_i| + m_o|c_o|): rotations keep lengths, γ is a unit vector (eq. (5)).
  const double u_low = -std::abs(top.g) * (top.mass * top.chi.norm() + s.inner_mass * s.inner_center.norm() +
                                           s.outer_mass * s.outer_center.norm());
  return std::sqrt(m11 * m22 * m33 * std::max(h - u_low, 0.0));
}

bool draw_cardan_energy_point(const system::CardanTop& top, double h, std::uint64_t seed, std::int64_t index,
                              system::TorusState& x, std::int64_t max_tries) {
  const double bound = cardan_energy_density_bound(top, h);
  if (!(bound > 0.0)) return false;
  CounterRng rng(seed, index, energy_draw_stream);
  for (std::int64_t attempt = 0; attempt < max_tries; ++attempt) {
    const Vec3 q(2.0 * pi * rng.uniform(), 2.0 * pi * rng.uniform(), 2.0 * pi * rng.uniform());
    const double keep = rng.uniform();
    const double surplus = h - top.potential(q);
    if (!(surplus > 0.0)) continue;
    const Mat3 M = top.mass_matrix(q);
    const double density = std::sqrt(std::max(M.determinant(), 0.0) * surplus);
    if (!(keep * bound < density)) continue;
    const Eigen::LLT<Mat3> llt(M);
    if (llt.info() != Eigen::Success) continue;  // M singular here (gimbal lock without ring inertia): density 0
    const double z = 2.0 * rng.uniform() - 1.0, phi = 2.0 * pi * rng.uniform(), r = std::sqrt(1.0 - z * z);
    const Vec3 y(r * std::cos(phi), r * std::sin(phi), z);  // uniform on S² (Archimedes)
    x.q = q;
    const Vec3 Ly = llt.matrixL() * y;
    x.p = std::sqrt(2.0 * surplus) * Ly;  // ½ pᵀM⁻¹p = surplus
    return true;
  }
  return false;
}

}  // namespace lgi::experiments
